#include "dnurbs/surface/restricted_mesh.h"

#include <algorithm>
#include <cstdlib>
#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/surface/parametric_surface_mesh_builder.h"

namespace dnurbs {
namespace {

// A base cell is 2^kCellShift lattice units wide, so kMaxLevel = 2 kCellShift bisections keep
// every midpoint on the integer lattice.
constexpr int kCellShift = RestrictedMesh::kMaxLevel / 2;

}  // namespace

RestrictedMesh::RestrictedMesh(const ParametricSurface& surface, int base_cells_u, int base_cells_v)
    : surface_(surface), base_cells_u_(base_cells_u), base_cells_v_(base_cells_v) {
  const ParameterDomain& domain = surface_.domain();
  const int minimum_u = domain.periodic_u ? 3 : 1;
  const int minimum_v = domain.periodic_v ? 3 : 1;
  if (base_cells_u < minimum_u || base_cells_u > kMaxBaseCells) {
    throw make_error("restricted mesh: base_cells_u ", base_cells_u, " is outside [", minimum_u,
                     ", ", kMaxBaseCells, "]");
  }
  if (base_cells_v < minimum_v || base_cells_v > kMaxBaseCells) {
    throw make_error("restricted mesh: base_cells_v ", base_cells_v, " is outside [", minimum_v,
                     ", ", kMaxBaseCells, "]");
  }
  extent_u_ = static_cast<std::int64_t>(base_cells_u) << kCellShift;
  extent_v_ = static_cast<std::int64_t>(base_cells_v) << kCellShift;
  // Goldenstein et al. 2005, section 4.2: the base triangulation is a union of basic blocks, one
  // per cell: (A, B, C) with apex B and (A, C, D) with apex D share their split edge, the diagonal
  // AC
  const std::int64_t cell = std::int64_t{1} << kCellShift;
  for (int i = 0; i < base_cells_u; ++i) {
    for (int j = 0; j < base_cells_v; ++j) {
      const Lattice a(i * cell, j * cell);
      const Lattice b((i + 1) * cell, j * cell);
      const Lattice c((i + 1) * cell, (j + 1) * cell);
      const Lattice d(i * cell, (j + 1) * cell);
      const int va = find_or_create_vertex(a);
      const int vb = find_or_create_vertex(b);
      const int vc = find_or_create_vertex(c);
      const int vd = find_or_create_vertex(d);
      add_triangle({vb, vc, va}, {b, c, a}, 0);
      add_triangle({vd, va, vc}, {d, a, c}, 0);
    }
  }
}

RestrictedMesh::Lattice RestrictedMesh::canonical(const Lattice& x) const {
  Lattice c = x;
  if (surface_.domain().periodic_u && c.x() >= extent_u_) {
    c.x() -= extent_u_;
  }
  if (surface_.domain().periodic_v && c.y() >= extent_v_) {
    c.y() -= extent_v_;
  }
  return c;
}

std::uint64_t RestrictedMesh::lattice_key(const Lattice& c) const {
  return static_cast<std::uint64_t>(c.x()) * static_cast<std::uint64_t>(extent_v_ + 1) +
         static_cast<std::uint64_t>(c.y());
}

Eigen::Vector2d RestrictedMesh::unwrapped_parameter(const Lattice& x) const {
  // Corners lie in [0, extent], so u_at maps the unwrapped seam corner to u_max
  const ParameterDomain& domain = surface_.domain();
  return {domain.u_at(static_cast<double>(x.x()) / static_cast<double>(extent_u_)),
          domain.v_at(static_cast<double>(x.y()) / static_cast<double>(extent_v_))};
}

int RestrictedMesh::find_or_create_vertex(const Lattice& unwrapped) {
  const Lattice c = canonical(unwrapped);
  const std::uint64_t key = lattice_key(c);
  if (const auto found = vertex_by_key_.find(key); found != vertex_by_key_.end()) {
    return found->second;
  }
  int id = 0;
  if (!free_vertices_.empty()) {
    id = free_vertices_.back();
    free_vertices_.pop_back();
  } else {
    id = static_cast<int>(vertices_.size());
    vertices_.emplace_back();
  }
  Vertex& vertex = vertices_[static_cast<size_t>(id)];
  vertex = Vertex{};
  vertex.lattice = c;
  vertex.key = key;
  vertex.alive = true;
  vertex.uv = unwrapped_parameter(c);
  // Goldenstein et al. 2005, section 5: the sampling function evaluates the surface at each new
  // vertex
  vertex.point = surface_.point(vertex.uv.x(), vertex.uv.y());
  vertex.normal = surface_.unit_normal(vertex.uv.x(), vertex.uv.y());
  vertex_by_key_.emplace(key, id);
  ++vertex_count_;
  return id;
}

std::uint64_t RestrictedMesh::edge_key(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

int RestrictedMesh::add_triangle(const std::array<int, 3>& vertex,
                                 const std::array<Lattice, 3>& corner, int level) {
  int id = 0;
  if (!free_triangles_.empty()) {
    id = free_triangles_.back();
    free_triangles_.pop_back();
  } else {
    id = static_cast<int>(triangles_.size());
    triangles_.emplace_back();
  }
  Triangle& t = triangles_[static_cast<size_t>(id)];
  t.vertex = vertex;
  t.corner = corner;
  t.level = level;
  t.alive = true;
  for (int k = 0; k < 3; ++k) {
    vertices_[static_cast<size_t>(vertex[static_cast<size_t>(k)])].incident.push_back(id);
    const int a = vertex[static_cast<size_t>((k + 1) % 3)];
    const int b = vertex[static_cast<size_t>((k + 2) % 3)];
    auto [slot, inserted] = edges_.try_emplace(edge_key(a, b), std::array<int, 2>{-1, -1});
    std::array<int, 2>& pair = slot->second;
    if (pair[0] < 0) {
      pair[0] = id;
    } else if (pair[1] < 0) {
      pair[1] = id;
    } else {
      throw make_error("restricted mesh: edge (", a, ", ", b,
                       ") would be shared by three triangles");
    }
  }
  ++triangle_count_;
  return id;
}

void RestrictedMesh::remove_triangle(int triangle) {
  Triangle& t = triangles_[static_cast<size_t>(triangle)];
  for (int k = 0; k < 3; ++k) {
    std::vector<int>& incident =
        vertices_[static_cast<size_t>(t.vertex[static_cast<size_t>(k)])].incident;
    incident.erase(std::find(incident.begin(), incident.end(), triangle));
    const auto edge = edges_.find(edge_key(t.vertex[static_cast<size_t>((k + 1) % 3)],
                                           t.vertex[static_cast<size_t>((k + 2) % 3)]));
    std::array<int, 2>& pair = edge->second;
    if (pair[0] == triangle) {
      pair[0] = pair[1];
    }
    pair[1] = -1;
    if (pair[0] < 0) {
      edges_.erase(edge);
    }
  }
  t.alive = false;
  free_triangles_.push_back(triangle);
  --triangle_count_;
}

void RestrictedMesh::check_triangle(int triangle) const {
  if (triangle < 0 || triangle >= static_cast<int>(triangles_.size()) ||
      !triangles_[static_cast<size_t>(triangle)].alive) {
    throw make_error("restricted mesh: triangle ", triangle, " is not a current triangle");
  }
}

int RestrictedMesh::neighbor(int triangle, int k) const {
  check_triangle(triangle);
  const Triangle& t = triangles_[static_cast<size_t>(triangle)];
  const auto edge = edges_.find(edge_key(t.vertex[static_cast<size_t>((k + 1) % 3)],
                                         t.vertex[static_cast<size_t>((k + 2) % 3)]));
  const std::array<int, 2>& pair = edge->second;
  return pair[0] == triangle ? pair[1] : pair[0];
}

void RestrictedMesh::bisect(int triangle, int partner, std::vector<int>* created) {
  // Goldenstein et al. 2005, section 4.1: the edge split of the diamond (triangle, partner) at the
  // midpoint m of their common split edge; each (apex x0, x1, x2) becomes (m, x0, x1) and (m, x2,
  // x0), whose split edges are the parent's legs (newest-vertex bisection)
  const std::array<int, 2> pair{triangle, partner};
  std::array<Triangle, 2> parent;
  for (int p = 0; p < 2; ++p) {
    if (pair[static_cast<size_t>(p)] >= 0) {
      parent[static_cast<size_t>(p)] =
          triangles_[static_cast<size_t>(pair[static_cast<size_t>(p)])];
    }
  }
  const Triangle& first = parent[0];
  const Lattice midpoint = (first.corner[1] + first.corner[2]) / 2;
  const int m = find_or_create_vertex(midpoint);
  {
    Vertex& vertex = vertices_[static_cast<size_t>(m)];
    vertex.from_split = true;
    vertex.split_edge = {vertices_[static_cast<size_t>(first.vertex[1])].key,
                         vertices_[static_cast<size_t>(first.vertex[2])].key};
  }
  for (int p = 0; p < 2; ++p) {
    if (pair[static_cast<size_t>(p)] >= 0) {
      remove_triangle(pair[static_cast<size_t>(p)]);
    }
  }
  for (int p = 0; p < 2; ++p) {
    if (pair[static_cast<size_t>(p)] < 0) {
      continue;
    }
    const Triangle& t = parent[static_cast<size_t>(p)];
    const Lattice mid = (t.corner[1] + t.corner[2]) / 2;  // m in this triangle's unwrapping
    const int level = t.level + 1;
    const int c0 =
        add_triangle({m, t.vertex[0], t.vertex[1]}, {mid, t.corner[0], t.corner[1]}, level);
    const int c1 =
        add_triangle({m, t.vertex[2], t.vertex[0]}, {mid, t.corner[2], t.corner[0]}, level);
    if (created != nullptr) {
      created->push_back(c0);
      created->push_back(c1);
    }
  }
}

void RestrictedMesh::split_compatible(int triangle, int& count, std::vector<int>* created) {
  // Goldenstein et al. 2005, section 4.2, interleaved refinement: split the neighbor across the
  // split edge until it shares that edge as its own split edge, then split the pair
  while (true) {
    const Triangle& t = triangles_[static_cast<size_t>(triangle)];
    const int other = neighbor(triangle, 0);
    if (other < 0) {
      bisect(triangle, -1, created);
      count += 1;
      return;
    }
    const Triangle& n = triangles_[static_cast<size_t>(other)];
    if (n.vertex[1] == t.vertex[2] && n.vertex[2] == t.vertex[1]) {
      bisect(triangle, other, created);
      count += 2;
      return;
    }
    split_compatible(other, count, created);
  }
}

int RestrictedMesh::split(int triangle) {
  check_triangle(triangle);
  if (triangles_[static_cast<size_t>(triangle)].level >= kMaxLevel) {
    throw make_error("restricted mesh: triangle ", triangle, " is at the deepest level ",
                     kMaxLevel);
  }
  int count = 0;
  split_compatible(triangle, count, nullptr);
  return count;
}

int RestrictedMesh::refine(const RefinementTest& needs_refinement, int max_level) {
  if (max_level < 0 || max_level > kMaxLevel) {
    throw make_error("restricted mesh: max_level ", max_level, " is outside [0, ", kMaxLevel, "]");
  }
  // Goldenstein et al. 2005, section 5: test every triangle, split those that ask for it, test
  // their children
  std::vector<int> pending = triangles();
  std::vector<int> created;
  int count = 0;
  while (!pending.empty()) {
    const int triangle = pending.back();
    pending.pop_back();
    const Triangle& t = triangles_[static_cast<size_t>(triangle)];
    if (!t.alive || t.level >= max_level || !needs_refinement(geometry(triangle))) {
      continue;
    }
    created.clear();
    split_compatible(triangle, count, &created);
    pending.insert(pending.end(), created.begin(), created.end());
  }
  return count;
}

bool RestrictedMesh::weld_parents(int vertex, std::vector<Triangle>& parents) const {
  parents.clear();
  if (vertex < 0 || vertex >= static_cast<int>(vertices_.size())) {
    return false;
  }
  const Vertex& m = vertices_[static_cast<size_t>(vertex)];
  if (!m.alive || !m.from_split || (m.incident.size() != 2 && m.incident.size() != 4)) {
    return false;
  }
  const int level = triangles_[static_cast<size_t>(m.incident[0])].level;
  for (const int child : m.incident) {
    const Triangle& t = triangles_[static_cast<size_t>(child)];
    if (t.vertex[0] != vertex || t.level != level) {
      return false;
    }
  }
  // The children (m, a, b) and (m, c, a) of a parent (a, b, c) share the edge m-a, where a is
  // not an end of the split edge; the parent's corner c is 2 m - b in the first child's frame
  for (const int child : m.incident) {
    const Triangle& x = triangles_[static_cast<size_t>(child)];
    const std::uint64_t apex_key = vertices_[static_cast<size_t>(x.vertex[1])].key;
    if (apex_key == m.split_edge[0] || apex_key == m.split_edge[1]) {
      continue;
    }
    const Triangle* partner = nullptr;
    for (const int other : m.incident) {
      const Triangle& y = triangles_[static_cast<size_t>(other)];
      if (other != child && y.vertex[2] == x.vertex[1]) {
        partner = &y;
      }
    }
    if (partner == nullptr) {
      return false;
    }
    Triangle parent;
    parent.vertex = {x.vertex[1], x.vertex[2], partner->vertex[1]};
    parent.corner = {x.corner[1], x.corner[2], Lattice(2 * x.corner[0] - x.corner[2])};
    parent.level = level - 1;
    parent.alive = true;
    parents.push_back(parent);
  }
  return 2 * parents.size() == m.incident.size();
}

bool RestrictedMesh::can_weld(int vertex) const {
  std::vector<Triangle> parents;
  return weld_parents(vertex, parents);
}

bool RestrictedMesh::weld(int vertex) {
  std::vector<Triangle> parents;
  if (!weld_parents(vertex, parents)) {
    return false;
  }
  // Goldenstein et al. 2005, section 4.1: the edge weld, inverse of the split
  const std::vector<int> children = vertices_[static_cast<size_t>(vertex)].incident;
  for (const int child : children) {
    remove_triangle(child);
  }
  Vertex& m = vertices_[static_cast<size_t>(vertex)];
  vertex_by_key_.erase(m.key);
  m.alive = false;
  free_vertices_.push_back(vertex);
  --vertex_count_;
  for (const Triangle& parent : parents) {
    add_triangle(parent.vertex, parent.corner, parent.level);
  }
  return true;
}

int RestrictedMesh::coarsen(const RefinementTest& needs_refinement) {
  int welds = 0;
  std::vector<Triangle> parents;
  std::vector<std::pair<int, int>> candidates;  // (-level of the children, vertex)
  while (true) {
    candidates.clear();
    for (int v = 0; v < static_cast<int>(vertices_.size()); ++v) {
      const Vertex& vertex = vertices_[static_cast<size_t>(v)];
      if (vertex.alive && vertex.from_split && !vertex.incident.empty()) {
        candidates.emplace_back(-triangles_[static_cast<size_t>(vertex.incident[0])].level, v);
      }
    }
    std::sort(candidates.begin(), candidates.end());
    int pass = 0;
    for (const auto& [negative_level, v] : candidates) {
      if (!weld_parents(v, parents)) {
        continue;
      }
      const bool keep = std::any_of(parents.begin(), parents.end(), [&](const Triangle& p) {
        return needs_refinement(geometry_of(p.vertex, p.corner, p.level));
      });
      if (!keep) {
        weld(v);
        ++pass;
      }
    }
    welds += pass;
    if (pass == 0) {
      return welds;
    }
  }
}

std::vector<int> RestrictedMesh::triangles() const {
  std::vector<int> ids;
  ids.reserve(static_cast<size_t>(triangle_count_));
  for (int t = 0; t < static_cast<int>(triangles_.size()); ++t) {
    if (triangles_[static_cast<size_t>(t)].alive) {
      ids.push_back(t);
    }
  }
  return ids;
}

const std::array<int, 3>& RestrictedMesh::triangle_vertices(int triangle) const {
  check_triangle(triangle);
  return triangles_[static_cast<size_t>(triangle)].vertex;
}

int RestrictedMesh::level(int triangle) const {
  check_triangle(triangle);
  return triangles_[static_cast<size_t>(triangle)].level;
}

RestrictedTriangleGeometry RestrictedMesh::geometry_of(const std::array<int, 3>& vertex,
                                                       const std::array<Lattice, 3>& corner,
                                                       int level) const {
  RestrictedTriangleGeometry g;
  for (size_t k = 0; k < 3; ++k) {
    const Vertex& v = vertices_[static_cast<size_t>(vertex[k])];
    g.uv[k] = unwrapped_parameter(corner[k]);
    g.points[k] = v.point;
    g.normals[k] = v.normal;
  }
  g.level = level;
  return g;
}

RestrictedTriangleGeometry RestrictedMesh::geometry(int triangle) const {
  check_triangle(triangle);
  const Triangle& t = triangles_[static_cast<size_t>(triangle)];
  return geometry_of(t.vertex, t.corner, t.level);
}

int RestrictedMesh::max_neighbor_level_difference() const {
  int difference = 0;
  for (const int t : triangles()) {
    for (int k = 0; k < 3; ++k) {
      const int n = neighbor(t, k);
      if (n >= 0) {
        difference = std::max(difference, std::abs(level(t) - level(n)));
      }
    }
  }
  return difference;
}

int RestrictedMesh::max_level() const {
  int deepest = 0;
  for (const int t : triangles()) {
    deepest = std::max(deepest, level(t));
  }
  return deepest;
}

Eigen::Vector2d RestrictedMesh::parameter(int vertex) const {
  if (vertex < 0 || vertex >= static_cast<int>(vertices_.size()) ||
      !vertices_[static_cast<size_t>(vertex)].alive) {
    throw make_error("restricted mesh: vertex ", vertex, " is not a current vertex");
  }
  return vertices_[static_cast<size_t>(vertex)].uv;
}

std::vector<std::array<std::uint64_t, 3>> RestrictedMesh::lattice_triangles() const {
  std::vector<std::array<std::uint64_t, 3>> keys;
  keys.reserve(static_cast<size_t>(triangle_count_));
  for (const int t : triangles()) {
    const Triangle& triangle = triangles_[static_cast<size_t>(t)];
    keys.push_back({vertices_[static_cast<size_t>(triangle.vertex[0])].key,
                    vertices_[static_cast<size_t>(triangle.vertex[1])].key,
                    vertices_[static_cast<size_t>(triangle.vertex[2])].key});
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

TriangleMesh RestrictedMesh::to_triangle_mesh(std::string name) const {
  ParametricSurfaceMeshBuilder builder(surface_);
  std::vector<int> index(vertices_.size(), -1);
  auto output_index = [&](int v) {
    int& slot = index[static_cast<size_t>(v)];
    if (slot < 0) {
      const Vertex& vertex = vertices_[static_cast<size_t>(v)];
      slot = builder.add_vertex(vertex.uv.x(), vertex.uv.y(), vertex.point, vertex.normal);
    }
    return slot;
  };
  for (const int t : triangles()) {
    const std::array<int, 3>& v = triangles_[static_cast<size_t>(t)].vertex;
    builder.add_triangle(output_index(v[0]), output_index(v[1]), output_index(v[2]));
  }
  return builder.build(std::move(name));
}

}  // namespace dnurbs
