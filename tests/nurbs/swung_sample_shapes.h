#pragma once
// Swung surfaces the swung-surface tests share (tests/nurbs and tests/dynamics/swung): random
// rational profiles and trajectories from fixed seeds, so every run sees the same shapes.

#include <cmath>
#include <numbers>
#include <random>

#include "dnurbs/nurbs/swung_surface.h"
#include "sample_shapes.h"

namespace dnurbs::testing {

/// A random profile in the xz plane: random_rational_curve with its x coordinates mapped into
/// [0.4, 2.0] (away from the axis, so the surface is not degenerate) and y = 0.
inline NurbsCurve random_profile(int degree, unsigned seed, bool rational = true) {
  const NurbsCurve curve = random_rational_curve(degree, seed, rational);
  Eigen::MatrixX3d points = curve.control_points();
  points.col(0) = (1.2 + 0.4 * points.col(0).array()).matrix();
  points.col(1).setZero();
  return NurbsCurve(curve.knots(), points, curve.weights());
}

/// A random trajectory in the xy plane: open (random_rational_curve with z = 0) or periodic (6
/// control points at radii 0.7..1.3 around the origin, unevenly spaced knots).
inline NurbsCurve random_trajectory(int degree, unsigned seed, bool periodic,
                                    bool rational = true) {
  if (!periodic) {
    const NurbsCurve curve = random_rational_curve(degree, seed, rational);
    Eigen::MatrixX3d points = curve.control_points();
    points.col(2).setZero();
    return NurbsCurve(curve.knots(), points, curve.weights());
  }
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> radius(0.7, 1.3);
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  KnotVector knots = KnotVector::periodic(degree, {0.0, 0.15, 0.35, 0.5, 0.7, 0.85, 1.0});
  const int count = knots.control_point_count();
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(count, 3);
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(count);
  for (int j = 0; j < count; ++j) {
    const double angle = 2.0 * std::numbers::pi * j / count;
    const double r = radius(generator);
    points(j, 0) = r * std::cos(angle);
    points(j, 1) = r * std::sin(angle);
    weights[j] = rational ? weight(generator) : 1.0;
  }
  return NurbsCurve(std::move(knots), std::move(points), std::move(weights));
}

/// A random swung surface with alpha = 1.3.
inline SwungSurface random_swung_surface(int profile_degree, int trajectory_degree, unsigned seed,
                                         bool periodic_trajectory, bool rational = true) {
  return SwungSurface(random_profile(profile_degree, seed, rational),
                      random_trajectory(trajectory_degree, seed + 1, periodic_trajectory, rational),
                      1.3);
}

}  // namespace dnurbs::testing
