#pragma once
// Shapes and measures shared by the knot operation tests (insertion, removal, degree
// elevation): random open and periodic curves from fixed seeds and the largest deviation
// between two shapes over their domain.

#include <algorithm>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs::testing {

// Random control points in [-1, 1]^3 and weights in [0.5, 2] (all 1 if not rational).
inline void random_control_points(int count, std::mt19937& generator, bool rational,
                                  Eigen::MatrixX3d& points, Eigen::VectorXd& weights) {
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  points.resize(count, 3);
  weights.resize(count);
  for (int i = 0; i < count; ++i) {
    points.row(i) << coordinate(generator), coordinate(generator), coordinate(generator);
    weights[i] = rational ? weight(generator) : 1.0;
  }
}

// A clamped curve over [-0.5, 2] with uneven interior knots, one of them double.
inline NurbsCurve random_open_curve(int degree, unsigned seed, bool rational) {
  std::mt19937 generator(seed);
  const KnotVector knots = KnotVector::clamped_from_breakpoints(degree, {-0.5, 0.1, 0.4, 1.3, 2.0});
  std::vector<double> values = knots.knots();
  values.insert(std::find(values.begin(), values.end(), 0.4), 0.4);  // double knot at 0.4
  KnotVector doubled(degree, values);
  Eigen::MatrixX3d points;
  Eigen::VectorXd weights;
  random_control_points(doubled.control_point_count(), generator, rational, points, weights);
  return {std::move(doubled), std::move(points), std::move(weights)};
}

// A periodic curve over [0.3, 2.3] with uneven spacing and a double knot at 1.1.
inline NurbsCurve random_periodic_curve(int degree, unsigned seed, bool rational) {
  std::mt19937 generator(seed);
  KnotVector knots =
      KnotVector::periodic(degree, {0.3, 0.5, 0.8, 1.1, 1.1, 1.4, 1.5, 1.9, 2.05, 2.3});
  Eigen::MatrixX3d points;
  Eigen::VectorXd weights;
  random_control_points(knots.control_point_count(), generator, rational, points, weights);
  return {std::move(knots), std::move(points), std::move(weights)};
}

// Largest distance between the two curves at 401 parameters over the domain of `a`.
inline double max_deviation(const NurbsCurve& a, const NurbsCurve& b) {
  const double start = a.knots().domain_start();
  const double end = a.knots().domain_end();
  double worst = 0.0;
  for (int i = 0; i <= 400; ++i) {
    const double u = start + (end - start) * i / 400.0;
    worst = std::max(worst, (a.point(u) - b.point(u)).norm());
  }
  return worst;
}

// Largest distance between the two surfaces on a 21 x 21 grid (441 parameter pairs).
inline double max_deviation(const NurbsSurface& a, const NurbsSurface& b) {
  double worst = 0.0;
  for (int i = 0; i <= 20; ++i) {
    const double u = a.knots_u().domain_start() +
                     (a.knots_u().domain_end() - a.knots_u().domain_start()) * i / 20.0;
    for (int j = 0; j <= 20; ++j) {
      const double v = a.knots_v().domain_start() +
                       (a.knots_v().domain_end() - a.knots_v().domain_start()) * j / 20.0;
      worst = std::max(worst, (a.point(u, v) - b.point(u, v)).norm());
    }
  }
  return worst;
}

}  // namespace dnurbs::testing
