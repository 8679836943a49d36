#pragma once
// Bases and surfaces shared by the triangular D-NURBS tests.

#include <memory>
#include <random>

#include <Eigen/Core>

#include "dnurbs/nurbs/triangular_nurbs_surface.h"
#include "dnurbs/nurbs/triangulation_shapes.h"

namespace dnurbs::test {

/// The standard triangular B-spline basis of degree n over a triangulation.
inline std::shared_ptr<const TriangularBSplineBasis> triangular_basis(
    const Triangulation& triangulation, int n) {
  return std::make_shared<const TriangularBSplineBasis>(triangulation,
                                                        standard_knot_clouds(triangulation, n));
}

/// The unit square split into cells x cells cells (alternating diagonals).
inline Triangulation unit_square(int cells) {
  return rectangle_triangulation(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), cells, cells);
}

/// A curved surface (the flat net lifted by a smooth height) with weights in [0.6, 1.6]
/// (all 1 if `rational` is false).
inline TriangularNurbsSurface curved_triangular_surface(
    const std::shared_ptr<const TriangularBSplineBasis>& basis, bool rational, unsigned seed = 5) {
  const TriangularNurbsSurface flat = flat_triangular_surface(basis);
  Eigen::MatrixX3d points = flat.control_points();
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(points.rows());
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> weight(0.6, 1.6);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    points(i, 2) = 0.3 * std::sin(2.0 * points(i, 0)) * std::cos(1.5 * points(i, 1));
    if (rational) {
      weights[i] = weight(random);
    }
  }
  return {basis, points, weights};
}

/// A random velocity of unit-order entries.
inline Eigen::VectorXd random_velocity(Eigen::Index size, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  Eigen::VectorXd v(size);
  for (Eigen::Index i = 0; i < size; ++i) {
    v[i] = entry(random);
  }
  return v;
}

}  // namespace dnurbs::test
