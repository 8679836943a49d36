#include "dnurbs/dynamics/triangular/triangular_tessellation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

#include "dnurbs/core/error.h"

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

// A conforming triangle mesh of the domain refined by longest-edge bisection (Rivara 1984):
// a triangle is bisected only together with the neighbour across its longest edge once that
// edge is the neighbour's longest too, so no vertex ever hangs on an edge.
class BisectionMesh {
 public:
  explicit BisectionMesh(const TriangularNurbsSurface& surface)
      : surface_(surface), builder_(surface) {
    const Triangulation& triangulation = surface.basis().triangulation();
    for (int v = 0; v < triangulation.vertex_count(); ++v) {
      builder_.add_vertex(triangulation.vertex_triangles(v).front(), triangulation.vertex(v));
    }
    for (int t = 0; t < triangulation.triangle_count(); ++t) {
      add({triangulation.triangles()(t, 0), triangulation.triangles()(t, 1),
           triangulation.triangles()(t, 2)},
          t, 0);
    }
  }

  int triangle_count() const { return static_cast<int>(corners_.size()); }
  bool alive(int id) const { return alive_[static_cast<size_t>(id)]; }
  int level(int id) const { return level_[static_cast<size_t>(id)]; }
  double chord_error(int id) const {
    return dnurbs::chord_error(surface_, builder_, domain_[static_cast<size_t>(id)],
                               corners_[static_cast<size_t>(id)]);
  }

  // Longest-edge propagation: refine the neighbour across the longest edge first until the two
  // share their longest edge, then bisect both. New triangles are appended to `created`.
  void refine(int start, std::vector<int>& created) {
    std::vector<int> path = {start};
    while (!path.empty()) {
      const int id = path.back();
      if (!alive(id)) {
        path.pop_back();
        continue;
      }
      const int e = longest(id);
      const auto& c = corners_[static_cast<size_t>(id)];
      const int a = c[static_cast<size_t>((e + 1) % 3)];
      const int b = c[static_cast<size_t>((e + 2) % 3)];
      const auto across = owner_.find(edge_key(b, a));
      const int other = across == owner_.end() ? -1 : across->second;
      const int f = other < 0 ? -1 : opposite_corner(corners_[static_cast<size_t>(other)], a, b);
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
  }

  TriangleMesh mesh(std::string name) const {
    std::vector<std::array<int, 3>> triangles;
    for (size_t id = 0; id < corners_.size(); ++id) {
      if (alive_[id]) {
        triangles.push_back(corners_[id]);
      }
    }
    return builder_.mesh(triangles, std::move(name));
  }

 private:
  int add(const std::array<int, 3>& c, int t, int l) {
    const int id = static_cast<int>(corners_.size());
    corners_.push_back(c);
    domain_.push_back(t);
    level_.push_back(l);
    alive_.push_back(true);
    for (int e = 0; e < 3; ++e) {
      owner_[edge_key(c[static_cast<size_t>(e)], c[static_cast<size_t>((e + 1) % 3)])] = id;
    }
    return id;
  }

  // The corner opposite the longest edge (a strict order: length, then the vertex indices, so
  // that both triangles of an edge agree).
  int longest(int id) const {
    const auto& c = corners_[static_cast<size_t>(id)];
    auto key = [&](int e) {
      const int a = c[static_cast<size_t>((e + 1) % 3)];
      const int b = c[static_cast<size_t>((e + 2) % 3)];
      return std::make_tuple((builder_.parameter(a) - builder_.parameter(b)).squaredNorm(),
                             std::min(a, b), std::max(a, b));
    };
    int best = 0;
    for (int e = 1; e < 3; ++e) {
      if (key(e) > key(best)) {
        best = e;
      }
    }
    return best;
  }

  // Bisects triangle id across the edge opposite corner e (the midpoint shared with the
  // neighbour); returns the two children.
  std::array<int, 2> bisect(int id, int e) {
    const auto c = corners_[static_cast<size_t>(id)];
    const int apex = c[static_cast<size_t>(e)];
    const int a = c[static_cast<size_t>((e + 1) % 3)];
    const int b = c[static_cast<size_t>((e + 2) % 3)];
    const int t = domain_[static_cast<size_t>(id)];
    const auto key = edge_key(std::min(a, b), std::max(a, b));
    auto found = midpoint_.find(key);
    if (found == midpoint_.end()) {
      const Eigen::Vector2d u = 0.5 * (builder_.parameter(a) + builder_.parameter(b));
      found = midpoint_.emplace(key, builder_.add_vertex(t, u)).first;
    }
    const int m = found->second;
    alive_[static_cast<size_t>(id)] = false;
    owner_.erase(edge_key(a, b));
    const int l = level(id) + 1;
    return {add({apex, a, m}, t, l), add({apex, m, b}, t, l)};
  }

  const TriangularNurbsSurface& surface_;
  MeshBuilder builder_;
  // Per mesh triangle: corners, domain triangle, bisection level, alive.
  std::vector<std::array<int, 3>> corners_;
  std::vector<int> domain_;
  std::vector<int> level_;
  std::vector<bool> alive_;
  std::unordered_map<std::uint64_t, int> owner_;     // directed edge -> its triangle
  std::unordered_map<std::uint64_t, int> midpoint_;  // undirected edge -> its midpoint vertex
};

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
    const Eigen::Vector2d u =
        (l[0] * triangulation.corner(t, 0) + l[1] * triangulation.corner(t, 1) +
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
  BisectionMesh mesh(surface);
  // Refine every triangle above the error bound (and below the level bound), then its
  // children, until none is left.
  std::vector<int> queue(static_cast<size_t>(mesh.triangle_count()));
  for (size_t k = 0; k < queue.size(); ++k) {
    queue[k] = static_cast<int>(k);
  }
  std::vector<int> created;
  while (!queue.empty()) {
    const int id = queue.back();
    queue.pop_back();
    if (!mesh.alive(id) || mesh.level(id) >= max_level || mesh.chord_error(id) <= max_error) {
      continue;
    }
    created.clear();
    mesh.refine(id, created);
    queue.insert(queue.end(), created.begin(), created.end());
  }
  return mesh.mesh(std::move(name));
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

TriangleMesh tessellate_triangular_model(const TriangularDNurbsSurface& model,
                                         const ConstVectorRef& q, int subdivisions,
                                         double max_error, std::string name) {
  const TriangularNurbsSurface surface = model.surface(q);
  if (max_error > 0.0) {
    return tessellate_triangular_surface_adaptive(surface, max_error, 20, std::move(name));
  }
  return tessellate_triangular_surface(surface, subdivisions, std::move(name));
}

}  // namespace dnurbs
