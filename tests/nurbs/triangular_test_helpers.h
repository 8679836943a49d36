#pragma once
// Domains and polynomial blossoms shared by the triangular B-spline tests.

#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/nurbs/triangulation_shapes.h"

namespace dnurbs::test {

/// Named test domains: a square grid, an L-shape, a square with a hole, and a grid whose
/// interior vertices are moved by up to 0.05 (irregular triangles).
inline std::vector<std::pair<std::string, Triangulation>> triangular_test_domains() {
  std::vector<std::pair<std::string, Triangulation>> domains;
  domains.emplace_back("square",
                       rectangle_triangulation(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), 3, 3));
  domains.emplace_back("l_shape", l_shape_triangulation(1));
  domains.emplace_back("hole", square_with_hole_triangulation(1));
  const Triangulation grid =
      rectangle_triangulation(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), 4, 4);
  Eigen::MatrixX2d vertices = grid.vertices();
  std::srand(3);
  for (Eigen::Index i = 0; i < vertices.rows(); ++i) {
    if (vertices(i, 0) > 0 && vertices(i, 0) < 1 && vertices(i, 1) > 0 && vertices(i, 1) < 1) {
      vertices.row(i) += 0.05 * Eigen::RowVector2d::Random();
    }
  }
  domains.emplace_back("perturbed", Triangulation(vertices, grid.triangles()));
  return domains;
}

/// The blossom of the monomial u^a v^b (a + b <= n) at the n points `arguments` (n by 2): the
/// symmetric multi-affine function that equals u^a v^b on the diagonal, i.e. the coefficient of
/// X^a Y^b in prod_k (1 + u_k X + v_k Y) divided by n! / (a! b! (n - a - b)!).
inline double monomial_blossom(int a, int b, const Eigen::MatrixX2d& arguments) {
  const int n = static_cast<int>(arguments.rows());
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(n + 1, n + 1);  // c(i, j): X^i Y^j
  c(0, 0) = 1.0;
  for (int k = 0; k < n; ++k) {
    for (int i = k + 1; i >= 0; --i) {
      for (int j = k + 1 - i; j >= 0; --j) {
        if (i + j == 0) {
          continue;
        }
        double added = 0.0;
        if (i > 0) {
          added += c(i - 1, j) * arguments(k, 0);
        }
        if (j > 0) {
          added += c(i, j - 1) * arguments(k, 1);
        }
        c(i, j) += added;
      }
    }
  }
  double multinomial = 1.0;  // n! / (a! b! (n - a - b)!)
  for (int k = 1; k <= n; ++k) {
    multinomial *= k;
  }
  for (int k = 1; k <= a; ++k) {
    multinomial /= k;
  }
  for (int k = 1; k <= b; ++k) {
    multinomial /= k;
  }
  for (int k = 1; k <= n - a - b; ++k) {
    multinomial /= k;
  }
  return c(a, b) / multinomial;
}

}  // namespace dnurbs::test
