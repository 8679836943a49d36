#include "dnurbs/dynamics/triangular/triangular_boundary_conditions.h"

#include <algorithm>
#include <cmath>

#include <Eigen/QR>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/gauss_legendre.h"
#include "dnurbs/nurbs/triangular_polynomial_cells.h"

namespace dnurbs {

namespace {

// The boundary triangle that has the directed edge (a, b) and the corner opposite it.
int triangle_of_edge(const Triangulation& triangulation, int a, int b) {
  if (a < 0 || a >= triangulation.vertex_count() || triangulation.boundary_next(a) != b) {
    throw make_error("(", a, ", ", b, ") is not a boundary edge of the triangulation");
  }
  for (const int t : triangulation.vertex_triangles(a)) {
    for (int c = 0; c < 3; ++c) {
      if (triangulation.triangles()(t, c) == a && triangulation.triangles()(t, (c + 1) % 3) == b) {
        return t;
      }
    }
  }
  throw make_error("boundary edge (", a, ", ", b, ") belongs to no triangle");
}

// Parameters s in (0, 1) along [p, q] where the knot segments of triangle t end on it, with 0
// and 1, sorted and without repeats closer than `tolerance` (relative to the edge length).
std::vector<double> edge_breakpoints(const TriangularBSplineBasis& basis, int t,
                                     const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  const double tolerance =
      TriangularBSplineBasis::kSnapTolerance * basis.triangulation().diameter();
  const Eigen::Vector2d edge = q - p;
  const double length = edge.norm();
  std::vector<double> breaks = {0.0, 1.0};
  const Eigen::MatrixX4d segments = knot_segments_in_triangle(basis, t);
  for (Eigen::Index k = 0; k < segments.rows(); ++k) {
    for (int end = 0; end < 2; ++end) {
      const Eigen::Vector2d x =
          segments.row(k).segment<2>(2 * static_cast<Eigen::Index>(end)).transpose();
      if (std::abs(edge.x() * (x.y() - p.y()) - edge.y() * (x.x() - p.x())) <= tolerance * length) {
        const double s = (x - p).dot(edge) / (length * length);
        if (s > 0.0 && s < 1.0) {
          breaks.push_back(s);
        }
      }
    }
  }
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> unique = {breaks.front()};
  for (const double s : breaks) {
    if (s - unique.back() > 1e-12) {
      unique.push_back(s);
    }
  }
  if (unique.back() < 1.0) {
    unique.back() = 1.0;
  }
  return unique;
}

}  // namespace

Eigen::SparseMatrix<double> boundary_trace_conditions(const TriangularBSplineBasis& basis,
                                                      BoundaryCondition condition,
                                                      const Eigen::MatrixX2i& edges) {
  const Triangulation& triangulation = basis.triangulation();
  const Eigen::MatrixX2i list = edges.rows() > 0 ? edges : triangulation.boundary_edges();
  const int n = basis.degree();
  const GaussLegendreRule& rule = gauss_legendre_rule(n + 1);
  const bool clamped = condition == BoundaryCondition::kClamped;
  std::vector<Eigen::Triplet<double>> triplets;
  int row = 0;
  TriangularBasisValues values;
  for (Eigen::Index e = 0; e < list.rows(); ++e) {
    const int t = triangle_of_edge(triangulation, list(e, 0), list(e, 1));
    const Eigen::Vector2d p = triangulation.vertex(list(e, 0));
    const Eigen::Vector2d q = triangulation.vertex(list(e, 1));
    const Eigen::Vector2d normal = Eigen::Vector2d(q.y() - p.y(), p.x() - q.x()).normalized();
    const std::vector<double> breaks = edge_breakpoints(basis, t, p, q);
    for (size_t piece = 0; piece + 1 < breaks.size(); ++piece) {
      for (int g = 0; g <= n; ++g) {
        const double s =
            breaks[piece] + (breaks[piece + 1] - breaks[piece]) * 0.5 * (rule.nodes[g] + 1.0);
        basis.evaluate_in_triangle(t, p + s * (q - p), clamped ? 1 : 0, values);
        for (int a = 0; a < values.count; ++a) {
          const int function = values.function[static_cast<size_t>(a)];
          if (values.value(0, a) != 0.0) {
            triplets.emplace_back(row, function, values.value(0, a));
          }
          if (clamped) {
            const double derivative =
                normal.x() * values.value(1, a) + normal.y() * values.value(2, a);
            if (derivative != 0.0) {
              triplets.emplace_back(row + 1, function, derivative);
            }
          }
        }
        row += clamped ? 2 : 1;
      }
    }
  }
  Eigen::SparseMatrix<double> conditions(row, basis.function_count());
  conditions.setFromTriplets(triplets.begin(), triplets.end());
  return conditions;
}

Eigen::SparseMatrix<double> constraint_null_space(const Eigen::SparseMatrix<double>& conditions) {
  const auto count = conditions.cols();
  // Columns (coefficients) that some condition involves.
  std::vector<int> involved;
  std::vector<int> position(static_cast<size_t>(count), -1);
  for (Eigen::Index j = 0; j < count; ++j) {
    if (conditions.col(j).nonZeros() > 0) {
      position[static_cast<size_t>(j)] = static_cast<int>(involved.size());
      involved.push_back(static_cast<int>(j));
    }
  }
  const auto m = static_cast<Eigen::Index>(involved.size());
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(conditions.rows(), m);
  for (Eigen::Index j = 0; j < count; ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(conditions, j); it; ++it) {
      block(it.row(), position[static_cast<size_t>(j)]) = it.value();
    }
  }
  // Null space of the block: the last m - rank columns of Q in block^T P = Q R.
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(block.transpose());
  qr.setThreshold(1e-10);
  const Eigen::Index rank = qr.rank();
  const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(m, m);
  const Eigen::MatrixXd null = q.rightCols(m - rank);
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::Index column = 0;
  for (Eigen::Index j = 0; j < count; ++j) {
    if (position[static_cast<size_t>(j)] < 0) {
      triplets.emplace_back(j, column++, 1.0);
    }
  }
  for (Eigen::Index k = 0; k < null.cols(); ++k, ++column) {
    for (Eigen::Index i = 0; i < m; ++i) {
      if (std::abs(null(i, k)) > 1e-15) {
        triplets.emplace_back(involved[static_cast<size_t>(i)], column, null(i, k));
      }
    }
  }
  Eigen::SparseMatrix<double> z(count, column);
  z.setFromTriplets(triplets.begin(), triplets.end());
  return z;
}

}  // namespace dnurbs
