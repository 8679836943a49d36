#pragma once
// Targets of point constraints: a fixed point, a function of time, or keyframes interpolated by
// a monotone piecewise cubic (the default), a natural cubic spline or straight segments.

#include <functional>
#include <vector>

#include <Eigen/Core>

namespace dnurbs {

/// How keyframes are interpolated between them, per coordinate. What Baumgarte's sigma of a
/// point target constraint sees is the target's acceleration, so the choice matters there:
/// - kMonotone (default): piecewise cubic Hermite with the slopes of Fritsch & Carlson 1980
///   ("Monotone piecewise cubic interpolation", SIAM J. Numer. Anal. 17(2), 238-246), PCHIP.
///   Each segment stays within the range of its two keyframes (no overshoot: a keyed push of 3
///   never pushes harder than 3), linear and constant data are reproduced exactly, and the
///   position and velocity are continuous (C1). The acceleration is the Hermite cubic's second
///   derivative: continuous inside each segment, it may jump at a keyframe, so sigma jumps
///   there too (a finite jump, which the Baumgarte terms absorb in a few steps).
/// - kCubic: the natural cubic spline (zero second derivative at the ends): position, velocity
///   and acceleration continuous (C2), so sigma is continuous; it may overshoot the keyframes
///   near sharp changes (keys -3, -3, 0 at t = 0, 1, 1.05 reach -14.0 at t = 0.577).
/// - kLinear: straight segments: the velocity is the segment's constant slope, jumping at each
///   keyframe, and the acceleration is 0 (the jumps, Dirac impulses, are not seen by sigma;
///   Baumgarte's alpha, beta terms correct the velocity error they leave).
enum class Interpolation { kMonotone, kCubic, kLinear };

/// x(t), xdot(t) and xddot(t) of a target point.
class TargetTrajectory {
 public:
  using Function = std::function<Eigen::Vector3d(double)>;

  /// A target at rest at `point`.
  static TargetTrajectory fixed(const Eigen::Vector3d& point);
  /// x(t) from a function; velocity and acceleration from the given functions, or, when those
  /// are empty, by central differences with step 1e-4 (1 + |t|) (error h^2 |x'''| / 6 and
  /// h^2 |x''''| / 12).
  static TargetTrajectory function(Function position, Function velocity = {},
                                   Function acceleration = {});
  /// Keyframes (strictly increasing times, at least 2), interpolated per coordinate as
  /// `interpolation` says; before the first and after the last keyframe the target rests there.
  static TargetTrajectory keyframes(const std::vector<double>& times,
                                    const std::vector<Eigen::Vector3d>& points,
                                    Interpolation interpolation = Interpolation::kMonotone);

  Eigen::Vector3d position(double time) const;
  Eigen::Vector3d velocity(double time) const;
  Eigen::Vector3d acceleration(double time) const;

 private:
  enum class Kind { kFixed, kFunction, kKeyframes };
  Kind kind_ = Kind::kFixed;
  Eigen::Vector3d point_ = Eigen::Vector3d::Zero();
  Function position_;
  Function velocity_;
  Function acceleration_;
  std::vector<double> times_;
  std::vector<Eigen::Vector3d> points_;
  Interpolation interpolation_ = Interpolation::kMonotone;
  /// At the keyframes: the spline moments (kCubic) or the Hermite slopes (kMonotone).
  std::vector<Eigen::Vector3d> derivatives_;
  int segment(double time) const;
  /// Derivative `order` (0, 1 or 2) of the interpolant at `time` inside the keyframes.
  Eigen::Vector3d interpolate(double time, int order) const;
};

}  // namespace dnurbs
