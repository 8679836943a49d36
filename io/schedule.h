#pragma once
// Values that change over a scene's time: a constant or keyframes interpolated by a natural cubic
// spline (TargetTrajectory::keyframes), constant before the first keyframe and after the last.
// Forces, springs and constraint targets of scene files are schedules.

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/constraints/target_trajectory.h"
#include "dnurbs/dynamics/core/forces.h"

namespace dnurbs {

/// A 3-vector that is a constant or keyframed in time.
/// JSON: `[x, y, z]` or `{"times": [t0, t1, ...], "values": [[x, y, z], ...]}`.
struct VectorSchedule {
  std::vector<double> times;            ///< empty for a constant
  std::vector<Eigen::Vector3d> values;  ///< one value (constant) or one per time
  /// The value at time t.
  Eigen::Vector3d at(double time) const;
  bool operator==(const VectorSchedule&) const = default;
};

/// A scalar that is a constant or keyframed in time (as VectorSchedule).
/// JSON: `p` or `{"times": [...], "values": [...]}`.
struct ScalarSchedule {
  std::vector<double> times;
  std::vector<double> values;
  double at(double time) const;
  bool operator==(const ScalarSchedule&) const = default;
};

/// The schedule as a function of time (the spline is built once, here).
VectorOfTime vector_of_time(const VectorSchedule& schedule);
ScalarOfTime scalar_of_time(const ScalarSchedule& schedule);
/// The schedule as a constraint target trajectory.
TargetTrajectory trajectory(const VectorSchedule& schedule);

}  // namespace dnurbs
