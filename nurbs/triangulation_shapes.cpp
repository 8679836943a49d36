#include "dnurbs/nurbs/triangulation_shapes.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "dnurbs/core/error.h"

namespace dnurbs {

Triangulation rectangle_triangulation(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                      int cells_u, int cells_v, DiagonalPattern pattern) {
  return grid_cells_triangulation(
      lo, hi, cells_u, cells_v, [](int, int) { return true; }, pattern);
}

Triangulation grid_cells_triangulation(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                       int cells_u, int cells_v,
                                       const std::function<bool(int, int)>& keep,
                                       DiagonalPattern pattern) {
  if (cells_u < 1 || cells_v < 1) {
    throw make_error("grid of ", cells_u, " by ", cells_v, " cells: counts must be >= 1");
  }
  if (!lo.allFinite() || !hi.allFinite() || !(hi.x() > lo.x()) || !(hi.y() > lo.y())) {
    throw make_error("grid rectangle [(", lo.x(), ", ", lo.y(), "), (", hi.x(), ", ", hi.y(),
                     ")] is empty or not finite");
  }
  const int rows = cells_v + 1;
  std::vector<int> used(static_cast<size_t>((cells_u + 1) * rows), -1);
  std::vector<std::array<int, 3>> triangles;
  auto grid = [rows](int i, int j) { return i * rows + j; };
  for (int i = 0; i < cells_u; ++i) {
    for (int j = 0; j < cells_v; ++j) {
      if (!keep(i, j)) {
        continue;
      }
      const int a = grid(i, j);
      const int b = grid(i + 1, j);
      const int c = grid(i + 1, j + 1);
      const int d = grid(i, j + 1);
      if (pattern == DiagonalPattern::kUniform || (i + j) % 2 == 0) {
        triangles.push_back({a, b, c});
        triangles.push_back({a, c, d});
      } else {
        triangles.push_back({a, b, d});
        triangles.push_back({b, c, d});
      }
    }
  }
  if (triangles.empty()) {
    throw make_error("grid of ", cells_u, " by ", cells_v, " cells: no cell is kept");
  }
  for (const auto& triangle : triangles) {
    for (const int v : triangle) {
      used[static_cast<size_t>(v)] = 0;
    }
  }
  std::vector<Eigen::Vector2d> vertices;
  for (int i = 0; i <= cells_u; ++i) {
    for (int j = 0; j <= cells_v; ++j) {
      if (used[static_cast<size_t>(grid(i, j))] < 0) {
        continue;
      }
      used[static_cast<size_t>(grid(i, j))] = static_cast<int>(vertices.size());
      // Exact end values at the last row and column.
      const double u = i == cells_u ? hi.x() : lo.x() + (hi.x() - lo.x()) * i / cells_u;
      const double v = j == cells_v ? hi.y() : lo.y() + (hi.y() - lo.y()) * j / cells_v;
      vertices.emplace_back(u, v);
    }
  }
  Eigen::MatrixX2d vertex_matrix(static_cast<Eigen::Index>(vertices.size()), 2);
  for (size_t k = 0; k < vertices.size(); ++k) {
    vertex_matrix.row(static_cast<Eigen::Index>(k)) = vertices[k].transpose();
  }
  Eigen::MatrixX3i triangle_matrix(static_cast<Eigen::Index>(triangles.size()), 3);
  for (size_t t = 0; t < triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) {
      triangle_matrix(static_cast<Eigen::Index>(t), c) =
          used[static_cast<size_t>(triangles[t][static_cast<size_t>(c)])];
    }
  }
  return {std::move(vertex_matrix), std::move(triangle_matrix)};
}

Triangulation l_shape_triangulation(int cells) {
  return grid_cells_triangulation(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(2.0, 2.0), 2 * cells,
                                  2 * cells,
                                  [cells](int i, int j) { return i < cells || j < cells; });
}

Triangulation square_with_hole_triangulation(int cells) {
  return grid_cells_triangulation(
      Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(3.0, 3.0), 3 * cells, 3 * cells,
      [cells](int i, int j) { return i < cells || i >= 2 * cells || j < cells || j >= 2 * cells; });
}

Triangulation refine_triangulation(const Triangulation& triangulation) {
  const int old_count = triangulation.vertex_count();
  std::vector<Eigen::Vector2d> added;
  std::map<std::uint64_t, int> midpoint;
  auto midpoint_of = [&](int a, int b) {
    const auto low = static_cast<std::uint64_t>(std::min(a, b));
    const auto high = static_cast<std::uint64_t>(std::max(a, b));
    const auto [it, inserted] =
        midpoint.emplace((low << 32U) | high, old_count + static_cast<int>(added.size()));
    if (inserted) {
      added.push_back(0.5 * (triangulation.vertex(a) + triangulation.vertex(b)));
    }
    return it->second;
  };
  Eigen::MatrixX3i triangles(4 * triangulation.triangle_count(), 3);
  for (int t = 0; t < triangulation.triangle_count(); ++t) {
    const int a = triangulation.triangles()(t, 0);
    const int b = triangulation.triangles()(t, 1);
    const int c = triangulation.triangles()(t, 2);
    const int ab = midpoint_of(a, b);
    const int bc = midpoint_of(b, c);
    const int ca = midpoint_of(c, a);
    const Eigen::Index row = 4 * static_cast<Eigen::Index>(t);
    triangles.row(row) << a, ab, ca;
    triangles.row(row + 1) << ab, b, bc;
    triangles.row(row + 2) << ca, bc, c;
    triangles.row(row + 3) << ab, bc, ca;
  }
  Eigen::MatrixX2d vertices(old_count + static_cast<int>(added.size()), 2);
  vertices.topRows(old_count) = triangulation.vertices();
  for (size_t k = 0; k < added.size(); ++k) {
    vertices.row(old_count + static_cast<Eigen::Index>(k)) = added[k].transpose();
  }
  return {std::move(vertices), std::move(triangles)};
}

}  // namespace dnurbs
