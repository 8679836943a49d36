#pragma once
// Writing scene files: the JSON forms of the values SceneReader reads, in the key order the
// writers of the model, force and constraint types use, so that parse(write(parse(text))) equals
// parse(text) and numbers round-trip exactly.

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "dnurbs/io/schedule.h"

namespace dnurbs {

/// A JSON value being written (keys keep their insertion order).
using JsonOut = nlohmann::ordered_json;

/// [v0, v1, ...].
template <int N>
JsonOut json_array(const Eigen::Matrix<double, N, 1>& v) {
  JsonOut a = JsonOut::array();
  for (int i = 0; i < N; ++i) {
    a.push_back(v(i));
  }
  return a;
}
/// A material parameter [u, v].
JsonOut parameter_json(const Eigen::Vector2d& u);
/// [[m11, m12], [m21, m22]].
JsonOut matrix2_json(const Eigen::Matrix2d& m);
/// A constant as its value, keyframes as {"times": [...], "values": [...], "interpolation": ...}.
JsonOut schedule_json(const VectorSchedule& schedule);
JsonOut schedule_json(const ScalarSchedule& schedule);

}  // namespace dnurbs
