#include "dnurbs/constraints/target_trajectory.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

TargetTrajectory TargetTrajectory::fixed(const Eigen::Vector3d& point) {
  if (!point.allFinite()) {
    throw make_error("constraint target (", point.x(), ", ", point.y(), ", ", point.z(),
                     ") is not finite");
  }
  TargetTrajectory target;
  target.point_ = point;
  return target;
}

TargetTrajectory TargetTrajectory::function(Function position, Function velocity,
                                            Function acceleration) {
  if (!position) {
    throw make_error("constraint target function is empty");
  }
  TargetTrajectory target;
  target.kind_ = Kind::kFunction;
  target.position_ = std::move(position);
  target.velocity_ = std::move(velocity);
  target.acceleration_ = std::move(acceleration);
  return target;
}

TargetTrajectory TargetTrajectory::keyframes(const std::vector<double>& times,
                                             const std::vector<Eigen::Vector3d>& points) {
  if (times.size() < 2 || times.size() != points.size()) {
    throw make_error("keyframes need at least 2 times and one point per time, got ", times.size(),
                     " times and ", points.size(), " points");
  }
  for (size_t i = 0; i < times.size(); ++i) {
    if (!std::isfinite(times[i]) || !points[i].allFinite()) {
      throw make_error("keyframe ", i, " is not finite (time ", times[i], ")");
    }
    if (i > 0 && !(times[i] > times[i - 1])) {
      throw make_error("keyframe times must increase: time ", i, " is ", times[i], " after ",
                       times[i - 1]);
    }
  }
  TargetTrajectory target;
  target.kind_ = Kind::kKeyframes;
  target.times_ = times;
  target.points_ = points;
  // Natural cubic spline moments: tridiagonal system with zero end moments.
  const size_t n = times.size();
  target.second_derivatives_.assign(n, Eigen::Vector3d::Zero());
  if (n > 2) {
    std::vector<double> diagonal(n, 0.0);
    std::vector<double> upper(n, 0.0);
    std::vector<Eigen::Vector3d> rhs(n, Eigen::Vector3d::Zero());
    for (size_t i = 1; i + 1 < n; ++i) {
      const double h0 = times[i] - times[i - 1];
      const double h1 = times[i + 1] - times[i];
      diagonal[i] = 2.0 * (h0 + h1);
      upper[i] = h1;
      rhs[i] = 6.0 * ((points[i + 1] - points[i]) / h1 - (points[i] - points[i - 1]) / h0);
    }
    // Thomas algorithm on rows 1..n-2 (sub-diagonal entry of row i is h_{i-1}).
    for (size_t i = 2; i + 1 < n; ++i) {
      const double factor = (times[i] - times[i - 1]) / diagonal[i - 1];
      diagonal[i] -= factor * upper[i - 1];
      rhs[i] -= factor * rhs[i - 1];
    }
    for (size_t i = n - 2; i >= 1; --i) {
      Eigen::Vector3d value = rhs[i];
      if (i + 2 < n) {
        value -= upper[i] * target.second_derivatives_[i + 1];
      }
      target.second_derivatives_[i] = value / diagonal[i];
    }
  }
  return target;
}

int TargetTrajectory::segment(double time) const {
  const auto upper = std::upper_bound(times_.begin(), times_.end(), time);
  const auto index = static_cast<int>(upper - times_.begin()) - 1;
  return std::clamp(index, 0, static_cast<int>(times_.size()) - 2);
}

Eigen::Vector3d TargetTrajectory::position(double time) const {
  switch (kind_) {
    case Kind::kFixed:
      return point_;
    case Kind::kFunction: {
      Eigen::Vector3d x = position_(time);
      if (!x.allFinite()) {
        throw make_error("constraint target function is not finite at t = ", time);
      }
      return x;
    }
    case Kind::kKeyframes:
      break;
  }
  if (time <= times_.front()) {
    return points_.front();
  }
  if (time >= times_.back()) {
    return points_.back();
  }
  const auto i = static_cast<size_t>(segment(time));
  const double h = times_[i + 1] - times_[i];
  const double a = (times_[i + 1] - time) / h;
  const double b = (time - times_[i]) / h;
  return a * points_[i] + b * points_[i + 1] +
         ((a * a * a - a) * second_derivatives_[i] + (b * b * b - b) * second_derivatives_[i + 1]) *
             (h * h / 6.0);
}

Eigen::Vector3d TargetTrajectory::velocity(double time) const {
  switch (kind_) {
    case Kind::kFixed:
      return Eigen::Vector3d::Zero();
    case Kind::kFunction: {
      if (velocity_) {
        return velocity_(time);
      }
      const double h = 1e-4 * (1.0 + std::abs(time));
      return (position(time + h) - position(time - h)) / (2.0 * h);
    }
    case Kind::kKeyframes:
      break;
  }
  if (time <= times_.front() || time >= times_.back()) {
    return Eigen::Vector3d::Zero();
  }
  const auto i = static_cast<size_t>(segment(time));
  const double h = times_[i + 1] - times_[i];
  const double a = (times_[i + 1] - time) / h;
  const double b = (time - times_[i]) / h;
  return (points_[i + 1] - points_[i]) / h + (-(3.0 * a * a - 1.0) * second_derivatives_[i] +
                                              (3.0 * b * b - 1.0) * second_derivatives_[i + 1]) *
                                                 (h / 6.0);
}

Eigen::Vector3d TargetTrajectory::acceleration(double time) const {
  switch (kind_) {
    case Kind::kFixed:
      return Eigen::Vector3d::Zero();
    case Kind::kFunction: {
      if (acceleration_) {
        return acceleration_(time);
      }
      const double h = 1e-4 * (1.0 + std::abs(time));
      return (position(time + h) - 2.0 * position(time) + position(time - h)) / (h * h);
    }
    case Kind::kKeyframes:
      break;
  }
  if (time <= times_.front() || time >= times_.back()) {
    return Eigen::Vector3d::Zero();
  }
  const auto i = static_cast<size_t>(segment(time));
  const double h = times_[i + 1] - times_[i];
  const double a = (times_[i + 1] - time) / h;
  const double b = (time - times_[i]) / h;
  return a * second_derivatives_[i] + b * second_derivatives_[i + 1];
}

}  // namespace dnurbs
