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

namespace {

// Natural cubic spline moments: tridiagonal system with zero end moments.
std::vector<Eigen::Vector3d> natural_spline_moments(const std::vector<double>& times,
                                                    const std::vector<Eigen::Vector3d>& points) {
  const size_t n = times.size();
  std::vector<Eigen::Vector3d> moments(n, Eigen::Vector3d::Zero());
  if (n <= 2) {
    return moments;
  }
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
      value -= upper[i] * moments[i + 1];
    }
    moments[i] = value / diagonal[i];
  }
  return moments;
}

// The slope at an end keyframe from the three-point one-sided formula of the end segment
// (secant `near`, width h_near) and the next (`far`, h_far), set to 0 when its sign is not the
// end secant's (Moler 2004, Numerical Computing with MATLAB, section 3.6, pchip).
double end_slope(double h_near, double h_far, double near, double far) {
  const double slope = ((2.0 * h_near + h_far) * near - h_near * far) / (h_near + h_far);
  return slope * near > 0.0 ? slope : 0.0;
}

// Hermite slopes of the monotone piecewise cubic, per coordinate (Fritsch & Carlson 1980,
// "Monotone piecewise cubic interpolation", SIAM J. Numer. Anal. 17(2), 238-246): three-point
// slopes, 0 at a keyframe where the secants change sign (a local extremum stays there), then on
// each segment with secant delta != 0 (alpha, beta) = (d_k, d_k+1) / delta is scaled into the
// circle alpha^2 + beta^2 <= 9, inside their monotonicity region (their section 4); on a flat
// segment both slopes are 0. Linear data keep slopes = the common secant, so they are reproduced.
std::vector<Eigen::Vector3d> monotone_slopes(const std::vector<double>& times,
                                             const std::vector<Eigen::Vector3d>& points) {
  const size_t n = times.size();
  std::vector<double> h(n - 1);
  std::vector<Eigen::Vector3d> secant(n - 1);
  for (size_t k = 0; k + 1 < n; ++k) {
    h[k] = times[k + 1] - times[k];
    secant[k] = (points[k + 1] - points[k]) / h[k];
  }
  std::vector<Eigen::Vector3d> slopes(n, Eigen::Vector3d::Zero());
  for (int c = 0; c < 3; ++c) {
    if (n == 2) {
      slopes[0](c) = slopes[1](c) = secant[0](c);
      continue;
    }
    for (size_t i = 1; i + 1 < n; ++i) {
      const double left = secant[i - 1](c);
      const double right = secant[i](c);
      slopes[i](c) =
          left * right > 0.0 ? (h[i] * left + h[i - 1] * right) / (h[i - 1] + h[i]) : 0.0;
    }
    slopes[0](c) = end_slope(h[0], h[1], secant[0](c), secant[1](c));
    slopes[n - 1](c) = end_slope(h[n - 2], h[n - 3], secant[n - 2](c), secant[n - 3](c));
    for (size_t k = 0; k + 1 < n; ++k) {
      const double delta = secant[k](c);
      if (delta == 0.0) {
        slopes[k](c) = slopes[k + 1](c) = 0.0;
        continue;
      }
      const double alpha = slopes[k](c) / delta;
      const double beta = slopes[k + 1](c) / delta;
      const double radius2 = alpha * alpha + beta * beta;
      if (radius2 > 9.0) {
        const double tau = 3.0 / std::sqrt(radius2);
        slopes[k](c) = tau * alpha * delta;
        slopes[k + 1](c) = tau * beta * delta;
      }
    }
  }
  return slopes;
}

}  // namespace

TargetTrajectory TargetTrajectory::keyframes(const std::vector<double>& times,
                                             const std::vector<Eigen::Vector3d>& points,
                                             Interpolation interpolation) {
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
  target.interpolation_ = interpolation;
  switch (interpolation) {
    case Interpolation::kCubic:
      target.derivatives_ = natural_spline_moments(times, points);
      break;
    case Interpolation::kMonotone:
      target.derivatives_ = monotone_slopes(times, points);
      break;
    case Interpolation::kLinear:
      break;
  }
  return target;
}

int TargetTrajectory::segment(double time) const {
  const auto upper = std::upper_bound(times_.begin(), times_.end(), time);
  const auto index = static_cast<int>(upper - times_.begin()) - 1;
  return std::clamp(index, 0, static_cast<int>(times_.size()) - 2);
}

namespace {

// a y0 + b y1 (a + b = 1), exactly y0 in a coordinate where y0 = y1 (a flat segment stays flat).
Eigen::Vector3d chord(double a, double b, const Eigen::Vector3d& y0, const Eigen::Vector3d& y1) {
  const Eigen::Vector3d mixed = a * y0 + b * y1;
  return (y0.array() == y1.array()).select(y0, mixed);
}

}  // namespace

Eigen::Vector3d TargetTrajectory::interpolate(double time, int order) const {
  const auto i = static_cast<size_t>(segment(time));
  const double h = times_[i + 1] - times_[i];
  const Eigen::Vector3d& y0 = points_[i];
  const Eigen::Vector3d& y1 = points_[i + 1];
  const Eigen::Vector3d secant = (y1 - y0) / h;
  const double b = (time - times_[i]) / h;
  const double a = (times_[i + 1] - time) / h;
  switch (interpolation_) {
    case Interpolation::kLinear:
      return order == 0 ? chord(a, b, y0, y1) : (order == 1 ? secant : Eigen::Vector3d::Zero());
    case Interpolation::kMonotone: {
      // The Hermite cubic as the chord plus h g(b), g = a b (a e0 - b e1) with e = d - delta:
      // g(0) = g(1) = 0, g'(0) = e0, g'(1) = e1. Linear data (e = 0) give exactly the chord,
      // as the cubic and linear kinds do.
      const Eigen::Vector3d e0 = derivatives_[i] - secant;
      const Eigen::Vector3d e1 = derivatives_[i + 1] - secant;
      if (order == 0) {
        return chord(a, b, y0, y1) + (h * a * b) * (a * e0 - b * e1);
      }
      if (order == 1) {
        return secant + (1.0 - b) * (1.0 - 3.0 * b) * e0 - b * (2.0 - 3.0 * b) * e1;
      }
      return ((6.0 * b - 4.0) * e0 + (6.0 * b - 2.0) * e1) / h;
    }
    case Interpolation::kCubic:
      break;
  }
  const Eigen::Vector3d& m0 = derivatives_[i];
  const Eigen::Vector3d& m1 = derivatives_[i + 1];
  if (order == 0) {
    return a * y0 + b * y1 + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * (h * h / 6.0);
  }
  if (order == 1) {
    return secant + (-(3.0 * a * a - 1.0) * m0 + (3.0 * b * b - 1.0) * m1) * (h / 6.0);
  }
  return a * m0 + b * m1;
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
  return interpolate(time, 0);
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
  return interpolate(time, 1);
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
  return interpolate(time, 2);
}

}  // namespace dnurbs
