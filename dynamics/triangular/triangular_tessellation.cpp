#include "dynamics/triangular/triangular_tessellation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

#include "core/error.h"

namespace dnurbs {

namespace {

// Vertices and triangles under construction; every vertex is evaluated once, as the limit from
// inside the domain triangle of the mesh triangle that created it.
class MeshBuilder {
 public:
  explicit MeshBuilder(const TriangularNurbsSurface& surface) : surface_(surface) {}

  int add_vertex(int domain_triangle, const Eigen::Vector2d& u) {
    const auto d = surface_.derivatives_in_triangle(domain_triangle, u, 1);
    Eigen::Vector3d normal = d[1].cross(d[2]);
    const double length = normal.norm();
    normal = length > 0.0 ? Eigen::Vector3d(normal / length) : Eigen::Vector3d::UnitZ();
    parameters_.push_back(u);
    positions_.push_back(d[0]);
    normals_.push_back(normal);
    return static_cast<int>(parameters_.size()) - 1;
  }
  const Eigen::Vector2d& parameter(int v) const { return parameters_[static_cast<size_t>(v)]; }
  const Eigen::Vector3d& position(int v) const { return positions_[static_cast<size_t>(v)]; }

  TriangleMesh mesh(const std::vector<std::array<int, 3>>& triangles, std::string name) const {
    TriangleMesh mesh;
    mesh.name = std::move(name);
    const auto count = static_cast<Eigen::Index>(parameters_.size());
    mesh.vertices.resize(count, 3);
    mesh.normals.resize(count, 3);
    mesh.uv.resize(count, 2);
    for (Eigen::Index v = 0; v < count; ++v) {
      mesh.vertices.row(v) = positions_[static_cast<size_t>(v)].transpose();
      mesh.normals.row(v) = normals_[static_cast<size_t>(v)].transpose();
      mesh.uv.row(v) = parameters_[static_cast<size_t>(v)].transpose();
    }
    mesh.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
    for (size_t t = 0; t < triangles.size(); ++t) {
      for (int c = 0; c < 3; ++c) {
        mesh.triangles(static_cast<Eigen::Index>(t), c) = triangles[t][static_cast<size_t>(c)];
      }
    }
    return mesh;
  }

 private:
  const TriangularNurbsSurface& surface_;
  std::vector<Eigen::Vector2d> parameters_;
  std::vector<Eigen::Vector3d> positions_;
  std::vector<Eigen::Vector3d> normals_;
};

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32U) |
         static_cast<std::uint32_t>(b);
}

// Chord error of the mesh triangle (a, b, c) inside domain triangle t: the surface against the
// linear interpolation of the corners at the centroid and the edge midpoints.
double chord_error(const TriangularNurbsSurface& surface, const MeshBuilder& builder, int t,
                   const std::array<int, 3>& corner) {
  static constexpr std::array<std::array<double, 3>, 4> kSamples = {
      {{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}, {0.5, 0.5, 0.0}, {0.0, 0.5, 0.5}, {0.5, 0.0, 0.5}}};
  double error = 0.0;
  for (const auto& l : kSamples) {
    Eigen::Vector2d u = Eigen::Vector2d::Zero();
    Eigen::Vector3d chord = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) {
      u += l[static_cast<size_t>(c)] * builder.parameter(corner[static_cast<size_t>(c)]);
      chord += l[static_cast<size_t>(c)] * builder.position(corner[static_cast<size_t>(c)]);
    }
    error = std::max(error, (surface.derivatives_in_triangle(t, u, 0)[0] - chord).norm());
  }
  return error;
}

// The corner of a triangle that is neither a nor b.
int opposite_corner(const std::array<int, 3>& corner, int a, int b) {
  for (int c = 0; c < 3; ++c) {
    if (corner[static_cast<size_t>(c)] != a && corner[static_cast<size_t>(c)] != b) {
      return c;
    }
  }
  throw make_error("mesh triangle has no corner opposite (", a, ", ", b, ")");
}

}  // namespace

TriangleMesh tessellate_triangular_surface(const TriangularNurbsSurface& surface, int subdivisions,
                                           std::string name) {
  if (subdivisions < 1 || subdivisions > 1024) {
    throw make_error("tessellation subdivisions ", subdivisions, " is outside 1..1024");
  }
  const int s = subdivisions;
  const Triangulation& triangulation = surface.basis().triangulation();
  MeshBuilder builder(surface);
  // Lattice point (i, j, k) / s of triangle t, shared with the neighbours: a domain vertex, a
  // point on a domain edge (keyed by the edge's vertices, lowest first, and its step from the
  // lowest), or a point inside t.
  std::map<std::array<int, 4>, int> index;
  auto vertex = [&](int t, int i, int j) {
    const std::array<int, 3> l = {i, j, s - i - j};
    const std::array<int, 3> corner = {triangulation.triangles()(t, 0),
                                       triangulation.triangles()(t, 1),
                                       triangulation.triangles()(t, 2)};
    std::array<int, 4> key = {2, t, i, j};
    for (int c = 0; c < 3; ++c) {
      if (l[static_cast<size_t>(c)] == s) {
        key = {0, corner[static_cast<size_t>(c)], 0, 0};
      }
    }
    for (int c = 0; c < 3 && key[0] == 2; ++c) {
      if (l[static_cast<size_t>(c)] == 0) {
        // The edge opposite corner c, from corner c + 1 to c + 2.
        const int a = corner[static_cast<size_t>((c + 1) % 3)];
        const int b = corner[static_cast<size_t>((c + 2) % 3)];
        const int step = l[static_cast<size_t>((c + 2) % 3)];  // steps from a towards b
        key = a < b ? std::array<int, 4>{1, a, b, step} : std::array<int, 4>{1, b, a, s - step};
      }
    }
    const auto found = index.find(key);
    if (found != index.end()) {
      return found->second;
    }
    const Eigen::Vector2d u = (l[0] * triangulation.corner(t, 0) + l[1] * triangulation.corner(t, 1) +
                               l[2] * triangulation.corner(t, 2)) /
                              static_cast<double>(s);
    const int v = builder.add_vertex(t, u);
    index.emplace(key, v);
    return v;
  };
  std::vector<std::array<int, 3>> triangles;
  for (int t = 0; t < triangulation.triangle_count(); ++t) {
    for (int i = 0; i < s; ++i) {
      for (int j = 0; i + j < s; ++j) {
        triangles.push_back({vertex(t, i + 1, j), vertex(t, i, j + 1), vertex(t, i, j)});
        if (i + j + 2 <= s) {
          triangles.push_back({vertex(t, i, j + 1), vertex(t, i + 1, j), vertex(t, i + 1, j + 1)});
        }
      }
    }
  }
  return builder.mesh(triangles, std::move(name));
}

TriangleMesh tessellate_triangular_surface_adaptive(const TriangularNurbsSurface& surface,
                                                    double max_error, int max_level,
                                                    std::string name) {
  if (!(max_error > 0.0) || !std::isfinite(max_error)) {
    throw make_error("adaptive tessellation error ", max_error, " is not a positive number");
  }
  if (max_level < 1 || max_level > 40) {
    throw make_error("adaptive tessellation level ", max_level, " is outside 1..40");
  }
  const Triangulation& triangulation = surface.basis().triangulation();
  MeshBuilder builder(surface);
  for (int v = 0; v < triangulation.vertex_count(); ++v) {
    builder.add_vertex(triangulation.vertex_triangles(v).front(), triangulation.vertex(v));
  }
  // Mesh triangles: corners, domain triangle, bisection level, alive; directed edge -> owner.
  std::vector<std::array<int, 3>> corners;
  std::vector<int> domain;
  std::vector<int> level;
  std::vector<bool> alive;
  std::unordered_map<std::uint64_t, int> owner;
  auto add = [&](const std::array<int, 3>& c, int t, int l) {
    const int id = static_cast<int>(corners.size());
    corners.push_back(c);
    domain.push_back(t);
    level.push_back(l);
    alive.push_back(true);
    for (int e = 0; e < 3; ++e) {
      owner[edge_key(c[static_cast<size_t>(e)], c[static_cast<size_t>((e + 1) % 3)])] = id;
    }
    return id;
  };
  for (int t = 0; t < triangulation.triangle_count(); ++t) {
    add({triangulation.triangles()(t, 0), triangulation.triangles()(t, 1),
         triangulation.triangles()(t, 2)},
        t, 0);
  }
  // Longest edge (a strict order: length, then the vertex indices) as the corner opposite it.
  auto longest = [&](int id) {
    const auto& c = corners[static_cast<size_t>(id)];
    auto key = [&](int e) {
      const int a = c[static_cast<size_t>((e + 1) % 3)];
      const int b = c[static_cast<size_t>((e + 2) % 3)];
      return std::make_tuple((builder.parameter(a) - builder.parameter(b)).squaredNorm(),
                             std::min(a, b), std::max(a, b));
    };
    int best = 0;
    for (int e = 1; e < 3; ++e) {
      if (key(e) > key(best)) {
        best = e;
      }
    }
    return best;
  };
  std::unordered_map<std::uint64_t, int> midpoint;
  // Bisects triangle id across the edge opposite corner e (midpoint shared with the neighbour).
  auto bisect = [&](int id, int e) {
    const auto c = corners[static_cast<size_t>(id)];
    const int apex = c[static_cast<size_t>(e)];
    const int a = c[static_cast<size_t>((e + 1) % 3)];
    const int b = c[static_cast<size_t>((e + 2) % 3)];
    const auto key = edge_key(std::min(a, b), std::max(a, b));
    auto found = midpoint.find(key);
    if (found == midpoint.end()) {
      const Eigen::Vector2d u = 0.5 * (builder.parameter(a) + builder.parameter(b));
      found = midpoint.emplace(key, builder.add_vertex(domain[static_cast<size_t>(id)], u)).first;
    }
    const int m = found->second;
    alive[static_cast<size_t>(id)] = false;
    owner.erase(edge_key(a, b));
    const int t = domain[static_cast<size_t>(id)];
    const int l = level[static_cast<size_t>(id)] + 1;
    return std::array<int, 2>{add({apex, a, m}, t, l), add({apex, m, b}, t, l)};
  };
  // Longest-edge propagation: refine the neighbour across the longest edge first until the
  // two share their longest edge, then bisect both.
  std::vector<int> created;
  auto refine = [&](int start) {
    std::vector<int> path = {start};
    while (!path.empty()) {
      const int id = path.back();
      if (!alive[static_cast<size_t>(id)]) {
        path.pop_back();
        continue;
      }
      const int e = longest(id);
      const auto& c = corners[static_cast<size_t>(id)];
      const int a = c[static_cast<size_t>((e + 1) % 3)];
      const int b = c[static_cast<size_t>((e + 2) % 3)];
      const auto across = owner.find(edge_key(b, a));
      const int other = across == owner.end() ? -1 : across->second;
      const int f = other < 0 ? -1 : opposite_corner(corners[static_cast<size_t>(other)], a, b);
      if (other >= 0 && longest(other) != f) {
        path.push_back(other);
        continue;
      }
      for (const int child : bisect(id, e)) {
        created.push_back(child);
      }
      if (other >= 0) {
        for (const int child : bisect(other, f)) {
          created.push_back(child);
        }
      }
      path.pop_back();
    }
  };
  std::vector<int> queue(corners.size());
  for (size_t k = 0; k < queue.size(); ++k) {
    queue[k] = static_cast<int>(k);
  }
  while (!queue.empty()) {
    const int id = queue.back();
    queue.pop_back();
    if (!alive[static_cast<size_t>(id)] || level[static_cast<size_t>(id)] >= max_level ||
        chord_error(surface, builder, domain[static_cast<size_t>(id)],
                    corners[static_cast<size_t>(id)]) <= max_error) {
      continue;
    }
    created.clear();
    refine(id);
    queue.insert(queue.end(), created.begin(), created.end());
  }
  std::vector<std::array<int, 3>> triangles;
  for (size_t id = 0; id < corners.size(); ++id) {
    if (alive[id]) {
      triangles.push_back(corners[id]);
    }
  }
  return builder.mesh(triangles, std::move(name));
}

double triangular_chord_error(const TriangularNurbsSurface& surface, const TriangleMesh& mesh,
                              int samples) {
  if (samples < 2 || samples > 64) {
    throw make_error("chord error samples ", samples, " is outside 2..64");
  }
  if (mesh.uv.rows() != mesh.vertices.rows()) {
    throw make_error("chord error needs the mesh's domain parameters (uv)");
  }
  double error = 0.0;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    for (int i = 0; i <= samples; ++i) {
      for (int j = 0; i + j <= samples; ++j) {
        const std::array<double, 3> l = {static_cast<double>(i) / samples,
                                         static_cast<double>(j) / samples,
                                         static_cast<double>(samples - i - j) / samples};
        Eigen::Vector2d u = Eigen::Vector2d::Zero();
        Eigen::Vector3d chord = Eigen::Vector3d::Zero();
        for (int c = 0; c < 3; ++c) {
          u += l[static_cast<size_t>(c)] * mesh.uv.row(mesh.triangles(t, c)).transpose();
          chord += l[static_cast<size_t>(c)] * mesh.vertices.row(mesh.triangles(t, c)).transpose();
        }
        error = std::max(error, (surface.point(u) - chord).norm());
      }
    }
  }
  return error;
}

TriangleMesh tessellate_triangular_model(const TriangularDNurbsSurface& model, ConstVectorRef q,
                                         int subdivisions, double max_error, std::string name) {
  const TriangularNurbsSurface surface = model.surface(q);
  if (max_error > 0.0) {
    return tessellate_triangular_surface_adaptive(surface, max_error, 20, std::move(name));
  }
  return tessellate_triangular_surface(surface, subdivisions, std::move(name));
}

}  // namespace dnurbs
