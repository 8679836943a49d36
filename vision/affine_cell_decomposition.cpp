#include "dnurbs/vision/affine_cell_decomposition.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

/// The level (which line of the family) and the position along the line of a point in grid units.
double level_of(int family, const Eigen::Vector2d& g) {
  return family == FreudenthalGrid::kHorizontal
             ? g.y()
             : (family == FreudenthalGrid::kVertical ? g.x() : g.x() - g.y());
}
double along_of(int family, const Eigen::Vector2d& g) {
  return family == FreudenthalGrid::kHorizontal ? g.x() : g.y();
}

/// The line index offset of a family (diagonal levels start at -cells_y).
int line_offset(const FreudenthalGrid& grid, int family) {
  return family == FreudenthalGrid::kDiagonal ? grid.cells_y() : 0;
}

}  // namespace

double crossing_fraction_on_line(const std::vector<GridCrossing>& line, double start,
                                 bool first_inside) {
  const auto lower = std::lower_bound(line.begin(), line.end(), start,
                                      [](const GridCrossing& c, double v) { return c.along < v; });
  const auto upper = std::upper_bound(line.begin(), line.end(), start + 1.0,
                                      [](double v, const GridCrossing& c) { return v < c.along; });
  if (lower == upper) {
    return 0.5;
  }
  const double along = first_inside ? std::prev(upper)->along : lower->along;
  return std::clamp(along - start, kAcidEdgeMargin, 1.0 - kAcidEdgeMargin);
}

GridCrossings grid_crossings(const FreudenthalGrid& grid, const std::vector<Contour>& contours) {
  GridCrossings crossings;
  const std::array<int, 3> line_count{grid.cells_y() + 1, grid.cells_x() + 1,
                                      grid.cells_x() + grid.cells_y() + 1};
  for (int family = 0; family < 3; ++family) {
    crossings.lines[static_cast<std::size_t>(family)].resize(
        static_cast<std::size_t>(line_count[static_cast<std::size_t>(family)]));
  }
  for (std::size_t c = 0; c < contours.size(); ++c) {
    const Contour& contour = contours[c];
    const Eigen::Index n = contour.rows();
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!contour.row(i).allFinite()) {
        throw make_error("contour ", c, " node ", i, " is not finite");
      }
    }
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector2d a = grid.to_grid(contour.row(i).transpose());
      const Eigen::Vector2d b = grid.to_grid(contour.row((i + 1) % n).transpose());
      for (int family = 0; family < 3; ++family) {
        auto& lines = crossings.lines[static_cast<std::size_t>(family)];
        const double la = level_of(family, a);
        const double lb = level_of(family, b);
        if (la == lb) {
          continue;
        }
        // Phase I: the lines L with min <= L < max, the element half-open at its upper end.
        const int sign = lb > la ? 1 : -1;
        const double low = std::min(la, lb);
        const double high = std::max(la, lb);
        const int offset = line_offset(grid, family);
        const int first = std::max(static_cast<int>(std::ceil(low)), -offset);
        const int last = static_cast<int>(lines.size()) - 1 - offset;
        for (int level = first; level < high && level <= last; ++level) {
          const double s = (level - la) / (lb - la);
          const double along =
              along_of(family, a) + s * (along_of(family, b) - along_of(family, a));
          lines[static_cast<std::size_t>(level) + static_cast<std::size_t>(offset)].push_back(
              {along, sign});
        }
      }
    }
  }
  for (auto& family : crossings.lines) {
    for (auto& line : family) {
      std::sort(line.begin(), line.end(),
                [](const GridCrossing& a, const GridCrossing& b) { return a.along < b.along; });
    }
  }
  return crossings;
}

std::vector<char> inside_vertices(const FreudenthalGrid& grid, const GridCrossings& crossings) {
  std::vector<char> inside(static_cast<std::size_t>(grid.vertex_count()), 0);
  for (int j = 1; j < grid.cells_y(); ++j) {
    const auto& line = crossings.lines[FreudenthalGrid::kHorizontal][static_cast<std::size_t>(j)];
    // Winding number of vertex (i, j): the signed crossings to its right, swept right to left.
    int winding = 0;
    auto crossing = line.rbegin();
    for (int i = grid.cells_x(); i >= 0; --i) {
      while (crossing != line.rend() && crossing->along > i) {
        winding += crossing->sign;
        ++crossing;
      }
      if (!grid.on_border(i, j) && winding > 0) {
        inside[static_cast<std::size_t>(grid.vertex_index(i, j))] = 1;
      }
    }
  }
  return inside;
}

std::vector<Contour> boundary_contours(const FreudenthalGrid& grid, const std::vector<char>& inside,
                                       const GridCrossings& crossings) {
  if (inside.size() != static_cast<std::size_t>(grid.vertex_count())) {
    throw make_error("inside flags: ", inside.size(), " for a grid of ", grid.vertex_count(),
                     " vertices");
  }
  const auto is_inside = [&](const Eigen::Vector2i& v) {
    return inside[static_cast<std::size_t>(grid.vertex_index(v.x(), v.y()))] != 0 &&
           !grid.on_border(v.x(), v.y());
  };
  // One node per boundary edge, numbered in order of first use.
  std::vector<int> node_of_edge(static_cast<std::size_t>(3 * grid.vertex_count()), -1);
  std::vector<Eigen::Vector2d> nodes;
  std::vector<int> next;
  const auto node = [&](const Eigen::Vector2i& a, const Eigen::Vector2i& b) {
    const int edge = grid.edge_between(a, b);
    int& id = node_of_edge[static_cast<std::size_t>(edge)];
    if (id < 0) {
      const int family = edge / grid.vertex_count();
      const Eigen::Vector2i first = (a.x() + a.y() <= b.x() + b.y()) ? a : b;
      const double start = family == FreudenthalGrid::kHorizontal ? first.x() : first.y();
      const int line =
          family == FreudenthalGrid::kHorizontal
              ? first.y()
              : (family == FreudenthalGrid::kVertical ? first.x()
                                                      : first.x() - first.y() + grid.cells_y());
      const double fraction = crossing_fraction_on_line(
          crossings.lines[static_cast<std::size_t>(family)][static_cast<std::size_t>(line)], start,
          is_inside(first));
      const Eigen::Vector2d g =
          first.cast<double>() + fraction * FreudenthalGrid::direction(family).cast<double>();
      id = static_cast<int>(nodes.size());
      nodes.push_back(grid.origin() + grid.cell_size() * g);
      next.push_back(-1);
    }
    return id;
  };
  // Phase II: in each counter-clockwise boundary triangle the element runs from the edge that
  // leaves the inside (inside -> outside in counter-clockwise order) to the edge that enters it,
  // which puts the inside on the element's left.
  for (int j = 0; j < grid.cells_y(); ++j) {
    for (int i = 0; i < grid.cells_x(); ++i) {
      for (const auto& triangle : grid.cell_triangles(i, j)) {
        int from = -1;
        int to = -1;
        for (std::size_t k = 0; k < 3; ++k) {
          const Eigen::Vector2i& a = triangle[k];
          const Eigen::Vector2i& b = triangle[(k + 1) % 3];
          if (is_inside(a) && !is_inside(b)) {
            from = node(a, b);
          } else if (!is_inside(a) && is_inside(b)) {
            to = node(a, b);
          }
        }
        if (from >= 0) {
          next[static_cast<std::size_t>(from)] = to;
        }
      }
    }
  }
  // Each node has one successor and one predecessor: the elements form disjoint cycles.
  std::vector<Contour> contours;
  std::vector<char> used(nodes.size(), 0);
  for (std::size_t start = 0; start < nodes.size(); ++start) {
    if (used[start] != 0) {
      continue;
    }
    std::vector<int> cycle;
    for (int n = static_cast<int>(start); used[static_cast<std::size_t>(n)] == 0;
         n = next[static_cast<std::size_t>(n)]) {
      if (next[static_cast<std::size_t>(n)] < 0) {
        throw make_error("ACID phase II: boundary node ", n, " has no successor");
      }
      used[static_cast<std::size_t>(n)] = 1;
      cycle.push_back(n);
    }
    Contour contour(static_cast<Eigen::Index>(cycle.size()), 2);
    for (std::size_t k = 0; k < cycle.size(); ++k) {
      contour.row(static_cast<Eigen::Index>(k)) =
          nodes[static_cast<std::size_t>(cycle[k])].transpose();
    }
    contours.push_back(std::move(contour));
  }
  return contours;
}

}  // namespace dnurbs
