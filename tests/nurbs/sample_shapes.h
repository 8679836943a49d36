#pragma once
// Curves and surfaces the NURBS tests share: random rational shapes with repeated knots and
// periodic ones, built from fixed seeds so that every run sees the same shapes.

#include <random>

#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs::testing {

/// A rational curve of the given degree with interior knots of multiplicity up to degree - 1.
inline NurbsCurve random_rational_curve(int degree, unsigned seed, bool rational = true) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  std::uniform_real_distribution<double> weight(0.4, 2.5);
  std::vector<double> breakpoints = {0.0, 0.2, 0.45, 0.7, 1.0};
  std::vector<double> knots(static_cast<size_t>(degree + 1), 0.0);
  knots.push_back(0.2);
  for (int r = 0; r < degree - 1; ++r) {
    knots.push_back(0.45);  // a repeated knot: continuity C^1 there
  }
  knots.push_back(0.7);
  knots.insert(knots.end(), static_cast<size_t>(degree + 1), 1.0);
  KnotVector knot_vector(degree, knots);
  const int count = knot_vector.control_point_count();
  Eigen::MatrixX3d points(count, 3);
  Eigen::VectorXd weights(count);
  for (int i = 0; i < count; ++i) {
    points.row(i) << coordinate(generator), coordinate(generator), coordinate(generator);
    weights[i] = rational ? weight(generator) : 1.0;
  }
  return NurbsCurve(std::move(knot_vector), std::move(points), std::move(weights));
}

/// A rational surface with degrees (p, q), a repeated knot in u, open or periodic in v.
inline NurbsSurface random_rational_surface(int degree_u, int degree_v, unsigned seed,
                                            bool periodic_u = false, bool periodic_v = false) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  const KnotVector knots_u =
      periodic_u ? KnotVector::periodic(degree_u, {0.0, 0.1, 0.3, 0.3, 0.55, 0.8, 0.9, 1.0})
                 : KnotVector(degree_u, [&] {
                     std::vector<double> knots(static_cast<size_t>(degree_u + 1), 0.0);
                     knots.insert(knots.end(), {0.25, 0.5, 0.5, 0.8});
                     knots.insert(knots.end(), static_cast<size_t>(degree_u + 1), 1.0);
                     return knots;
                   }());
  const KnotVector knots_v =
      periodic_v ? KnotVector::periodic(degree_v, {0.0, 0.15, 0.35, 0.5, 0.7, 0.85, 1.0})
                 : KnotVector::clamped_from_breakpoints(degree_v, {0.0, 0.3, 0.65, 1.0});
  const int count = knots_u.control_point_count() * knots_v.control_point_count();
  Eigen::MatrixX3d points(count, 3);
  Eigen::VectorXd weights(count);
  for (int i = 0; i < count; ++i) {
    points.row(i) << coordinate(generator), coordinate(generator), coordinate(generator);
    weights[i] = weight(generator);
  }
  return NurbsSurface(knots_u, knots_v, std::move(points), std::move(weights));
}

}  // namespace dnurbs::testing
