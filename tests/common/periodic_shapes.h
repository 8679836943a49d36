#pragma once
// Exact periodic rational shapes for tests: the rational quadratic circle and torus with
// periodic knot vectors (8 distinct control points per circle).

#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "nurbs/nurbs_curve.h"
#include "nurbs/nurbs_surface.h"

namespace dnurbs::testing {

/// Period knots t_2..t_10 of the periodic rational quadratic circle.
inline std::vector<double> circle_period_knots() {
  return {0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0};
}

/// (x, y, weight) of the 8 distinct control points of the unit circle, from angle 0.
inline std::array<std::array<double, 3>, 8> unit_circle_control_points() {
  const double s = std::sqrt(0.5);
  return {{{1, 0, 1},
           {1, 1, s},
           {0, 1, 1},
           {-1, 1, s},
           {-1, 0, 1},
           {-1, -1, s},
           {0, -1, 1},
           {1, -1, s}}};
}

/// The periodic circle of the given radius in the xy plane about the origin.
inline NurbsCurve periodic_circle(double radius) {
  Eigen::MatrixX3d points(8, 3);
  Eigen::VectorXd weights(8);
  const auto circle = unit_circle_control_points();
  for (int i = 0; i < 8; ++i) {
    const auto& c = circle[static_cast<size_t>(i)];
    points.row(i) << radius * c[0], radius * c[1], 0.0;
    weights(i) = c[2];
  }
  return NurbsCurve(KnotVector::periodic(2, circle_period_knots()), points, weights);
}

/// The torus about the z axis (u around z, v around the tube), periodic in u and v.
inline NurbsSurface periodic_torus(double major_radius, double minor_radius) {
  const auto circle = unit_circle_control_points();
  const KnotVector knots = KnotVector::periodic(2, circle_period_knots());
  Eigen::MatrixX3d points(64, 3);
  Eigen::VectorXd weights(64);
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      const auto& a = circle[static_cast<size_t>(i)];
      const auto& b = circle[static_cast<size_t>(j)];
      const double distance = major_radius + minor_radius * b[0];
      points.row(i * 8 + j) << distance * a[0], distance * a[1], minor_radius * b[1];
      weights(i * 8 + j) = a[2] * b[2];
    }
  }
  return NurbsSurface(knots, knots, points, weights);
}

}  // namespace dnurbs::testing
