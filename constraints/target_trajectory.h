#pragma once
// Targets of point constraints: a fixed point, a function of time, or keyframes interpolated by
// a natural cubic spline (so the target's acceleration, which enters sigma, is continuous).

#include <functional>
#include <vector>

#include <Eigen/Core>

namespace dnurbs {

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
  /// Keyframes (strictly increasing times, at least 2), interpolated by a natural cubic spline
  /// per coordinate; before the first and after the last keyframe the target rests there.
  static TargetTrajectory keyframes(const std::vector<double>& times,
                                    const std::vector<Eigen::Vector3d>& points);

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
  std::vector<Eigen::Vector3d> second_derivatives_;  ///< spline moments at the keyframes
  int segment(double time) const;
};

}  // namespace dnurbs
