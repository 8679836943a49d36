#pragma once
// Arguments shared by the bindings of the model types: a state q (None: the model's initial
// coordinates) and 3-vectors.

#include <string>

#include "dnurbs/dynamics/core/model.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

/// The coordinates argument: the model's initial coordinates for None, else (coordinate_count,).
inline Eigen::VectorXd model_state(const Model& model, const py::object& q) {
  if (q.is_none()) {
    return model.initial_coordinates();
  }
  return vector_from_array(q, "q", model.coordinate_count());
}

/// The velocities argument: zero for None, else (velocity_count,).
inline Eigen::VectorXd model_velocity(const Model& model, const py::object& qd) {
  if (qd.is_none()) {
    return Eigen::VectorXd::Zero(model.velocity_count());
  }
  return vector_from_array(qd, "qd", model.velocity_count());
}

/// A 3-vector argument ((3,) or (1, 3)); Error naming `name` otherwise.
inline Eigen::Vector3d vector3_argument(const py::object& value, const std::string& name) {
  return matrix_from_array(value, name, 1, 3, true).row(0).transpose();
}

}  // namespace dnurbs::python
