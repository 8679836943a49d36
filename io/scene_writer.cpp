#include "dnurbs/io/scene_writer.h"

namespace dnurbs {

JsonOut parameter_json(const Eigen::Vector2d& u) {
  return JsonOut{u.x(), u.y()};
}

JsonOut matrix2_json(const Eigen::Matrix2d& m) {
  return JsonOut{{m(0, 0), m(0, 1)}, {m(1, 0), m(1, 1)}};
}

JsonOut schedule_json(const VectorSchedule& schedule) {
  if (schedule.times.empty()) {
    return json_array<3>(schedule.values.front());
  }
  JsonOut values = JsonOut::array();
  for (const auto& v : schedule.values) {
    values.push_back(json_array<3>(v));
  }
  return JsonOut{{"times", schedule.times},
                 {"values", values},
                 {"interpolation", interpolation_name(schedule.interpolation)}};
}

JsonOut schedule_json(const ScalarSchedule& schedule) {
  if (schedule.times.empty()) {
    return schedule.values.front();
  }
  return JsonOut{{"times", schedule.times},
                 {"values", schedule.values},
                 {"interpolation", interpolation_name(schedule.interpolation)}};
}

}  // namespace dnurbs
