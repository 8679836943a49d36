#include "dnurbs/dynamics/triangular/triangular_local_sculpting.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/triangular/triangular_boundary_conditions.h"

namespace dnurbs {

std::vector<int> border_control_points(const TriangularBSplineBasis& basis) {
  // Columns of C with an entry above the tolerance: the B-splines seen on the boundary
  const Eigen::SparseMatrix<double> conditions =
      boundary_trace_conditions(basis, BoundaryCondition::kSimplySupported);
  std::vector<int> border;
  for (int column = 0; column < conditions.outerSize(); ++column) {
    for (Eigen::SparseMatrix<double>::InnerIterator entry(conditions, column); entry; ++entry) {
      if (std::abs(entry.value()) > kBorderTraceTolerance) {
        border.push_back(column);
        break;
      }
    }
  }
  return border;
}

std::vector<int> triangular_sculpted_control_points(const TriangularBSplineBasis& basis,
                                                    const SculptedRegion& region, int margin) {
  if (margin < 0) {
    throw make_error("local sculpting: margin ", margin, " is negative");
  }
  const Triangulation& triangulation = basis.triangulation();
  std::vector<char> kept(static_cast<size_t>(basis.function_count()), 0);
  std::vector<char> triangles(static_cast<size_t>(triangulation.triangle_count()), 0);
  // The B-splines non-zero at every parameter, and the triangles involved
  TriangularBasisValues values;
  for (const Eigen::Vector2d& u : region.parameters) {
    if (!u.allFinite()) {
      throw make_error("local sculpting: parameter (", u.x(), ", ", u.y(), ") is not finite");
    }
    const int t = triangulation.locate(u);
    if (t < 0) {
      throw make_error("local sculpting: parameter (", u.x(), ", ", u.y(),
                       ") is outside the triangulated domain");
    }
    triangles[static_cast<size_t>(t)] = 1;
    basis.evaluate_in_triangle(t, u, 0, values);
    for (int a = 0; a < values.count; ++a) {
      if (values.value(0, a) != 0.0) {
        kept[static_cast<size_t>(values.function[static_cast<size_t>(a)])] = 1;
      }
    }
  }
  for (const int i : region.control_points) {
    if (i < 0 || i >= basis.function_count()) {
      throw make_error("local sculpting: control point ", i, " is outside 0..",
                       basis.function_count() - 1);
    }
    kept[static_cast<size_t>(i)] = 1;
  }
  for (int f = 0; f < basis.function_count(); ++f) {
    if (kept[static_cast<size_t>(f)]) {
      triangles[static_cast<size_t>(basis.triangle_of(f))] = 1;
    }
  }
  // Grow the triangles by `margin` rings of vertex neighbours; keep all their B-splines
  for (int ring = 0; ring < margin; ++ring) {
    std::vector<char> grown = triangles;
    for (int t = 0; t < triangulation.triangle_count(); ++t) {
      if (!triangles[static_cast<size_t>(t)]) {
        continue;
      }
      for (int c = 0; c < 3; ++c) {
        for (const int s : triangulation.vertex_triangles(triangulation.triangles()(t, c))) {
          grown[static_cast<size_t>(s)] = 1;
        }
      }
    }
    triangles = std::move(grown);
  }
  std::vector<int> result;
  for (int f = 0; f < basis.function_count(); ++f) {
    if (kept[static_cast<size_t>(f)] ||
        (margin > 0 && triangles[static_cast<size_t>(basis.triangle_of(f))])) {
      result.push_back(f);
    }
  }
  return result;
}

}  // namespace dnurbs
