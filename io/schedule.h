#pragma once
// Values that change over a scene's time: a constant or keyframes interpolated per coordinate by
// TargetTrajectory::keyframes, constant before the first keyframe and after the last. Forces,
// springs and constraint targets of scene files are schedules. The interpolation defaults to
// monotone (Fritsch & Carlson 1980): what a designer keys is never exceeded between keyframes
// (a natural cubic spline through a push of -3 held for 1 s and released in 0.05 s reaches -14);
// "cubic" is there for targets whose acceleration must be continuous (Interpolation says why).

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/constraints/target_trajectory.h"
#include "dnurbs/dynamics/core/forces.h"

namespace dnurbs {

/// The JSON name of an interpolation: "monotone", "cubic" or "linear".
const char* interpolation_name(Interpolation interpolation);

/// A 3-vector that is a constant or keyframed in time.
/// JSON: `[x, y, z]` or `{"times": [t0, t1, ...], "values": [[x, y, z], ...]}` with optional
/// `"interpolation": "monotone"` (default), `"cubic"` or `"linear"`.
struct VectorSchedule {
  std::vector<double> times;                               ///< empty for a constant
  std::vector<Eigen::Vector3d> values;                     ///< one value (constant) or one per time
  Interpolation interpolation = Interpolation::kMonotone;  ///< between keyframes
  /// The value at time t.
  Eigen::Vector3d at(double time) const;
  bool operator==(const VectorSchedule&) const = default;
};

/// A scalar that is a constant or keyframed in time (as VectorSchedule).
/// JSON: `p` or `{"times": [...], "values": [...]}` with optional `"interpolation"`.
struct ScalarSchedule {
  std::vector<double> times;
  std::vector<double> values;
  Interpolation interpolation = Interpolation::kMonotone;
  double at(double time) const;
  bool operator==(const ScalarSchedule&) const = default;
};

/// The schedule as a function of time (the interpolant is built once, here).
VectorOfTime vector_of_time(const VectorSchedule& schedule);
ScalarOfTime scalar_of_time(const ScalarSchedule& schedule);
/// The schedule as a constraint target trajectory.
TargetTrajectory trajectory(const VectorSchedule& schedule);

}  // namespace dnurbs
