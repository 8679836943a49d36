#include "dnurbs/vision/tetrahedral_decomposition.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

/// The axes of a family's projection: primary a, then the other two b < c.
std::array<int, 3> family_axes(int family) {
  const Eigen::Vector3i d = TetrahedralGrid::direction(family);
  const int a = d.x() == 1 ? 0 : (d.y() == 1 ? 1 : 2);
  const int b = a == 0 ? 1 : 0;
  const int c = a == 2 ? 1 : 2;
  return {a, b, c};
}

/// (u, v, along) of a grid-unit point for a family's lines.
Eigen::Vector3d project(int family, const Eigen::Vector3d& g) {
  const Eigen::Vector3i d = TetrahedralGrid::direction(family);
  const auto [a, b, c] = family_axes(family);
  return {g[b] - d[b] * g[a], g[c] - d[c] * g[a], g[a]};
}

/// Edge function of p against the line a -> b, computed in a canonical vertex order so that
/// the two triangles sharing an edge get exactly opposite values.
double edge_function(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const bool swap = a.x() > b.x() || (a.x() == b.x() && a.y() > b.y());
  const Eigen::Vector2d& first = swap ? b : a;
  const Eigen::Vector2d& second = swap ? a : b;
  const double value = (second.x() - first.x()) * (p.y() - first.y()) -
                       (second.y() - first.y()) * (p.x() - first.x());
  return swap ? -value : value;
}

/// The top-left rule for the edge a -> b of a counter-clockwise triangle: a point on the edge
/// belongs to the triangle only if the edge runs downward, or leftward when horizontal; the
/// neighbor across the edge traverses it the other way and so gets the point exactly once.
bool owns_edge(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return b.y() < a.y() || (b.y() == a.y() && b.x() < a.x());
}

/// Marching-tetrahedra triangles of one tetrahedron (grid vertex coordinates, inside flags).
void tetrahedron_triangles(
    const std::array<Eigen::Vector3i, 4>& tet, const std::array<bool, 4>& in,
    const std::function<int(const Eigen::Vector3i&, const Eigen::Vector3i&)>& node,
    std::vector<Eigen::Vector3i>& triangles) {
  std::array<int, 4> inside_ids{};
  std::array<int, 4> outside_ids{};
  int inside_count = 0;
  int outside_count = 0;
  for (int k = 0; k < 4; ++k) {
    if (in[static_cast<std::size_t>(k)]) {
      inside_ids[static_cast<std::size_t>(inside_count++)] = k;
    } else {
      outside_ids[static_cast<std::size_t>(outside_count++)] = k;
    }
  }
  const auto det = [](const Eigen::Vector3i& p, const Eigen::Vector3i& q,
                      const Eigen::Vector3i& r) { return p.dot(q.cross(r)); };
  const auto at = [&](int k) { return tet[static_cast<std::size_t>(k)]; };
  if (inside_count == 1 || inside_count == 3) {
    // One lone vertex L: a triangle on its three edges. Its normal n satisfies
    // sign(n . (p1 - L)) = sign det(O1 - L, O2 - L, O3 - L) for any node fractions.
    const bool lone_inside = inside_count == 1;
    const int lone = lone_inside ? inside_ids[0] : outside_ids[0];
    const auto& others = lone_inside ? outside_ids : inside_ids;
    std::array<int, 3> o{others[0], others[1], others[2]};
    const long long orientation =
        det(at(o[0]) - at(lone), at(o[1]) - at(lone), at(o[2]) - at(lone));
    if ((orientation > 0) != lone_inside) {
      std::swap(o[1], o[2]);
    }
    triangles.emplace_back(node(at(lone), at(o[0])), node(at(lone), at(o[1])),
                           node(at(lone), at(o[2])));
    return;
  }
  if (inside_count == 2) {
    // Inside A, B and outside C, D: the quad AC, BC, BD, AD, whose normal points from {A, B} to
    // {C, D} when det(B - A, D - C, C + D - A - B) > 0 (the sign at the midpoints, which no
    // choice of node fractions in (0, 1) can flip).
    const Eigen::Vector3i a = at(inside_ids[0]);
    const Eigen::Vector3i b = at(inside_ids[1]);
    const Eigen::Vector3i c = at(outside_ids[0]);
    const Eigen::Vector3i d = at(outside_ids[1]);
    std::array<int, 4> quad{node(a, c), node(b, c), node(b, d), node(a, d)};
    if (det(b - a, d - c, c + d - a - b) < 0) {
      std::reverse(quad.begin(), quad.end());
    }
    triangles.emplace_back(quad[0], quad[1], quad[2]);
    triangles.emplace_back(quad[0], quad[2], quad[3]);
  }
}

}  // namespace

TetrahedralCrossings::TetrahedralCrossings(const TetrahedralGrid& grid, const TriangleMesh& mesh)
    : cells_(grid.cells()) {
  for (int family = 0; family < TetrahedralGrid::kFamilies; ++family) {
    const Eigen::Vector3i d = TetrahedralGrid::direction(family);
    const auto [a, b, c] = family_axes(family);
    const long long size_u = cells_[b] + d[b] * cells_[a] + 1;
    const long long size_v = cells_[c] + d[c] * cells_[a] + 1;
    lines_[static_cast<std::size_t>(family)].resize(static_cast<std::size_t>(size_u * size_v));
  }
  std::vector<Eigen::Vector3d> g(static_cast<std::size_t>(mesh.vertex_count()));
  for (int i = 0; i < mesh.vertex_count(); ++i) {
    if (!mesh.vertices.row(i).allFinite()) {
      throw make_error("T-surface mesh vertex ", i, " is not finite");
    }
    g[static_cast<std::size_t>(i)] = grid.to_grid(mesh.vertices.row(i).transpose());
  }
  for (int f = 0; f < mesh.triangle_count(); ++f) {
    const Eigen::Vector3i triangle = mesh.triangles.row(f).transpose();
    if (triangle.minCoeff() < 0 || triangle.maxCoeff() >= mesh.vertex_count()) {
      throw make_error("T-surface mesh triangle ", f, " indexes a vertex outside [0, ",
                       mesh.vertex_count(), ")");
    }
    for (int family = 0; family < TetrahedralGrid::kFamilies; ++family) {
      std::array<Eigen::Vector3d, 3> p;
      for (int k = 0; k < 3; ++k) {
        p[static_cast<std::size_t>(k)] = project(family, g[static_cast<std::size_t>(triangle[k])]);
      }
      const std::array<Eigen::Vector2d, 3> q{p[0].head<2>(), p[1].head<2>(), p[2].head<2>()};
      const double area = edge_function(q[0], q[1], q[2]);
      if (area == 0.0) {
        continue;  // seen edge-on: the line grazes it, its neighbors carry the crossing
      }
      const int sign = area > 0.0 ? 1 : -1;
      const Eigen::Vector2d low = q[0].cwiseMin(q[1]).cwiseMin(q[2]);
      const Eigen::Vector2d high = q[0].cwiseMax(q[1]).cwiseMax(q[2]);
      for (auto v = static_cast<long long>(std::ceil(low.y())); v <= high.y(); ++v) {
        for (auto u = static_cast<long long>(std::ceil(low.x())); u <= high.x(); ++u) {
          const int index = line_index(family, u, v);
          if (index < 0) {
            continue;
          }
          const Eigen::Vector2d point(static_cast<double>(u), static_cast<double>(v));
          // Edge functions of the counter-clockwise order (reversed for a clockwise projection).
          std::array<double, 3> e{};
          bool inside = true;
          for (std::size_t k = 0; k < 3 && inside; ++k) {
            const Eigen::Vector2d& from = q[(k + 1) % 3];
            const Eigen::Vector2d& to = q[(k + 2) % 3];
            e[k] = sign * edge_function(from, to, point);
            inside = e[k] > 0.0 ||
                     (e[k] == 0.0 && (sign > 0 ? owns_edge(from, to) : owns_edge(to, from)));
          }
          if (!inside) {
            continue;
          }
          const double total = e[0] + e[1] + e[2];
          const double along = (e[0] * p[0].z() + e[1] * p[1].z() + e[2] * p[2].z()) / total;
          lines_[static_cast<std::size_t>(family)][static_cast<std::size_t>(index)].push_back(
              {along, sign});
        }
      }
    }
  }
  for (auto& family : lines_) {
    for (auto& line : family) {
      std::sort(line.begin(), line.end(),
                [](const GridCrossing& x, const GridCrossing& y) { return x.along < y.along; });
    }
  }
}

int TetrahedralCrossings::line_index(int family, long long u, long long v) const {
  const Eigen::Vector3i d = TetrahedralGrid::direction(family);
  const auto [a, b, c] = family_axes(family);
  const long long shifted_u = u + static_cast<long long>(d[b]) * cells_[a];
  const long long shifted_v = v + static_cast<long long>(d[c]) * cells_[a];
  const long long size_u = cells_[b] + d[b] * cells_[a] + 1;
  const long long size_v = cells_[c] + d[c] * cells_[a] + 1;
  if (shifted_u < 0 || shifted_u >= size_u || shifted_v < 0 || shifted_v >= size_v) {
    return -1;
  }
  return static_cast<int>(shifted_u + size_u * shifted_v);
}

const std::vector<GridCrossing>& TetrahedralCrossings::line(int family,
                                                            const Eigen::Vector3i& first) const {
  const Eigen::Vector3d p = project(family, first.cast<double>());
  const int index = line_index(family, std::llround(p.x()), std::llround(p.y()));
  if (index < 0) {
    throw make_error("grid vertex (", first.x(), ", ", first.y(), ", ", first.z(),
                     ") has no line of edge family ", family);
  }
  return lines_[static_cast<std::size_t>(family)][static_cast<std::size_t>(index)];
}

std::vector<char> inside_vertices(const TetrahedralGrid& grid,
                                  const TetrahedralCrossings& crossings) {
  std::vector<char> inside(static_cast<std::size_t>(grid.vertex_count()), 0);
  const Eigen::Vector3i& n = grid.cells();
  for (int k = 1; k < n.z(); ++k) {
    for (int j = 1; j < n.y(); ++j) {
      const auto& line = crossings.line(0, Eigen::Vector3i(0, j, k));
      // Winding number of (i, j, k): the signed crossings beyond it in +x, swept from +x.
      int winding = 0;
      auto crossing = line.rbegin();
      for (int i = n.x(); i >= 0; --i) {
        while (crossing != line.rend() && crossing->along > i) {
          winding += crossing->sign;
          ++crossing;
        }
        const Eigen::Vector3i g(i, j, k);
        if (!grid.on_border(g) && winding > 0) {
          inside[static_cast<std::size_t>(grid.vertex_index(g))] = 1;
        }
      }
    }
  }
  return inside;
}

double crossing_fraction(const TetrahedralCrossings& crossings, int family,
                         const Eigen::Vector3i& first, bool first_inside) {
  return crossing_fraction_on_line(crossings.line(family, first), first[family_axes(family)[0]],
                                   first_inside);
}

TriangleMesh boundary_mesh(const TetrahedralGrid& grid, const std::vector<char>& inside,
                           const EdgeFraction& fraction) {
  if (inside.size() != static_cast<std::size_t>(grid.vertex_count())) {
    throw make_error("inside flags: ", inside.size(), " for a grid of ", grid.vertex_count(),
                     " vertices");
  }
  const auto is_inside = [&](const Eigen::Vector3i& g) {
    return inside[static_cast<std::size_t>(grid.vertex_index(g))] != 0 && !grid.on_border(g);
  };
  std::vector<int> node_of_edge(static_cast<std::size_t>(TetrahedralGrid::kFamilies) *
                                    static_cast<std::size_t>(grid.vertex_count()),
                                -1);
  std::vector<Eigen::Vector3d> nodes;
  const auto node = [&](const Eigen::Vector3i& p, const Eigen::Vector3i& q) {
    const bool p_first = (q - p).minCoeff() >= 0;
    const Eigen::Vector3i& first = p_first ? p : q;
    const int family = TetrahedralGrid::family_of(q - p);
    int& id = node_of_edge[static_cast<std::size_t>(grid.edge_id(family, first))];
    if (id < 0) {
      const double t = fraction(family, first, is_inside(first));
      id = static_cast<int>(nodes.size());
      nodes.push_back(grid.vertex_position(first) +
                      t * grid.cell_size() * TetrahedralGrid::direction(family).cast<double>());
    }
    return id;
  };
  std::vector<Eigen::Vector3i> triangles;
  const Eigen::Vector3i n = grid.cells();
  for (int k = 0; k < n.z(); ++k) {
    for (int j = 0; j < n.y(); ++j) {
      for (int i = 0; i < n.x(); ++i) {
        for (const auto& tet : TetrahedralGrid::cube_tetrahedra(Eigen::Vector3i(i, j, k))) {
          const std::array<bool, 4> in{is_inside(tet[0]), is_inside(tet[1]), is_inside(tet[2]),
                                       is_inside(tet[3])};
          if (in[0] == in[1] && in[1] == in[2] && in[2] == in[3]) {
            continue;
          }
          tetrahedron_triangles(tet, in, node, triangles);
        }
      }
    }
  }
  TriangleMesh mesh;
  mesh.name = "t_surface";
  mesh.vertices.resize(static_cast<Eigen::Index>(nodes.size()), 3);
  for (std::size_t v = 0; v < nodes.size(); ++v) {
    mesh.vertices.row(static_cast<Eigen::Index>(v)) = nodes[v].transpose();
  }
  mesh.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    mesh.triangles.row(static_cast<Eigen::Index>(f)) = triangles[f].transpose();
  }
  return mesh;
}

}  // namespace dnurbs
