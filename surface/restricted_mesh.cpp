#include "dnurbs/surface/restricted_mesh.h"

#include <algorithm>
#include <cstdlib>
#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/surface/parametric_surface_mesh_builder.h"

namespace dnurbs {
namespace {

// The splitmix64 finalizer: a bijective mix of 64 bits.
std::uint64_t mix(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// The key of the vertex that splits the edge of keys a and b (see triangle_keys).
std::uint64_t split_vertex_key(std::uint64_t a, std::uint64_t b) {
  constexpr std::uint64_t kSplitBit = std::uint64_t{1} << 63;
  return mix(mix(std::min(a, b)) ^ std::max(a, b)) | kSplitBit;
}

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
  // Grid vertex (i, j), seams identified
  std::unordered_map<std::uint64_t, int> vertex_by_key;
  auto grid_vertex = [&](int i, int j) {
    const int ci = domain.periodic_u && i == base_cells_u ? 0 : i;
    const int cj = domain.periodic_v && j == base_cells_v ? 0 : j;
    const std::uint64_t key =
        static_cast<std::uint64_t>(ci) * static_cast<std::uint64_t>(base_cells_v + 1) +
        static_cast<std::uint64_t>(cj);
    const auto [found, inserted] = vertex_by_key.try_emplace(key, -1);
    if (inserted) {
      found->second = create_vertex(Eigen::Vector2d(ci, cj), key);
    }
    return found->second;
  };
  // Goldenstein et al. 2005, section 4.2: the base triangulation is a union of basic blocks, one
  // per cell: (A, B, C) with apex B and (A, C, D) with apex D share their split edge, the diagonal
  // AC
  for (int i = 0; i < base_cells_u; ++i) {
    for (int j = 0; j < base_cells_v; ++j) {
      const Eigen::Vector2d a(i, j);
      const Eigen::Vector2d b(i + 1, j);
      const Eigen::Vector2d c(i + 1, j + 1);
      const Eigen::Vector2d d(i, j + 1);
      const int va = grid_vertex(i, j);
      const int vb = grid_vertex(i + 1, j);
      const int vc = grid_vertex(i + 1, j + 1);
      const int vd = grid_vertex(i, j + 1);
      add_triangle({vb, vc, va}, {b, c, a}, 0);
      add_triangle({vd, va, vc}, {d, a, c}, 0);
    }
  }
}

RestrictedMesh::RestrictedMesh(const ParametricSurface& surface, const BlockTriangulation& base)
    : surface_(surface) {
  if (const int violations = compliance_violations(base); violations != 0) {
    throw make_error("restricted mesh: the base triangulation has ", violations,
                     " compliance violations (make it compliant with make_compliant)");
  }
  const ParameterDomain& domain = surface_.domain();
  for (int k = 0; k < base.uv.rows(); ++k) {
    const Eigen::Vector2d uv = base.uv.row(k).transpose();
    if (!(uv.x() >= domain.u_min && uv.x() <= domain.u_max && uv.y() >= domain.v_min &&
          uv.y() <= domain.v_max)) {
      throw make_error("restricted mesh: base vertex ", k, " (", uv.x(), ", ", uv.y(),
                       ") is outside the surface's domain [", domain.u_min, ", ", domain.u_max,
                       "] x [", domain.v_min, ", ", domain.v_max, "]");
    }
    create_vertex(uv, static_cast<std::uint64_t>(k));
  }
  for (int t = 0; t < base.triangles.rows(); ++t) {
    const std::array<int, 3> v{base.triangles(t, 0), base.triangles(t, 1), base.triangles(t, 2)};
    add_triangle(v,
                 {base.uv.row(v[0]).transpose(), base.uv.row(v[1]).transpose(),
                  base.uv.row(v[2]).transpose()},
                 0);
  }
}

Eigen::Vector2d RestrictedMesh::parameter_at(const Eigen::Vector2d& corner) const {
  if (base_cells_u_ == 0) {
    return corner;
  }
  // Corners lie in [0, cells], so u_at maps the unwrapped seam corner to u_max
  const ParameterDomain& domain = surface_.domain();
  return {domain.u_at(corner.x() / base_cells_u_), domain.v_at(corner.y() / base_cells_v_)};
}

int RestrictedMesh::create_vertex(const Eigen::Vector2d& corner, std::uint64_t key) {
  Eigen::Vector2d canonical = corner;
  if (base_cells_u_ > 0) {
    // A seam corner of a periodic direction is the vertex at the domain's start
    if (surface_.domain().periodic_u && canonical.x() >= base_cells_u_) {
      canonical.x() -= base_cells_u_;
    }
    if (surface_.domain().periodic_v && canonical.y() >= base_cells_v_) {
      canonical.y() -= base_cells_v_;
    }
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
  vertex.key = key;
  vertex.alive = true;
  vertex.uv = parameter_at(canonical);
  // Goldenstein et al. 2005, section 5: the sampling function evaluates the surface at each new
  // vertex
  vertex.point = surface_.point(vertex.uv.x(), vertex.uv.y());
  vertex.normal = surface_.unit_normal(vertex.uv.x(), vertex.uv.y());
  ++vertex_count_;
  return id;
}

std::uint64_t RestrictedMesh::edge_key(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

int RestrictedMesh::add_triangle(const std::array<int, 3>& vertex,
                                 const std::array<Eigen::Vector2d, 3>& corner, int level) {
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
  const std::uint64_t key_1 = vertices_[static_cast<size_t>(first.vertex[1])].key;
  const std::uint64_t key_2 = vertices_[static_cast<size_t>(first.vertex[2])].key;
  const int m =
      create_vertex(0.5 * (first.corner[1] + first.corner[2]), split_vertex_key(key_1, key_2));
  {
    Vertex& vertex = vertices_[static_cast<size_t>(m)];
    vertex.from_split = true;
    vertex.split_edge = {key_1, key_2};
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
    const Eigen::Vector2d mid = 0.5 * (t.corner[1] + t.corner[2]);  // m in this triangle's frame
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
  // not an end of the split edge; the parent's corner c is the second child's corner 1
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
    parent.corner = {x.corner[1], x.corner[2], partner->corner[1]};
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

bool RestrictedMesh::weld_restoring(int vertex, std::vector<int>* parent_ids) {
  std::vector<Triangle> parents;
  if (!weld_parents(vertex, parents)) {
    return false;
  }
  // Goldenstein et al. 2005, section 4.1: the edge weld, inverse of the split
  const std::vector<int> children = vertices_[static_cast<size_t>(vertex)].incident;
  for (const int child : children) {
    remove_triangle(child);
  }
  vertices_[static_cast<size_t>(vertex)].alive = false;
  free_vertices_.push_back(vertex);
  --vertex_count_;
  if (parent_ids != nullptr) {
    parent_ids->clear();
  }
  for (const Triangle& parent : parents) {
    const int id = add_triangle(parent.vertex, parent.corner, parent.level);
    if (parent_ids != nullptr) {
      parent_ids->push_back(id);
    }
  }
  return true;
}

int RestrictedMesh::coarsen(const RefinementTest& needs_refinement) {
  int welds = 0;
  std::vector<int> parents;
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
      // Weld, and split again if a restored parent needs refinement in the welded mesh (a test
      // may look at the parent's neighbors); the split restores the same children and keys
      if (!weld_restoring(v, &parents)) {
        continue;
      }
      if (std::any_of(parents.begin(), parents.end(),
                      [&](int p) { return needs_refinement(geometry(p)); })) {
        bisect(parents[0], parents.size() > 1 ? parents[1] : -1, nullptr);
      } else {
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

RestrictedTriangleGeometry RestrictedMesh::geometry(int triangle) const {
  check_triangle(triangle);
  const Triangle& t = triangles_[static_cast<size_t>(triangle)];
  RestrictedTriangleGeometry g;
  for (size_t k = 0; k < 3; ++k) {
    const Vertex& v = vertices_[static_cast<size_t>(t.vertex[k])];
    g.uv[k] = parameter_at(t.corner[k]);
    g.points[k] = v.point;
    g.normals[k] = v.normal;
  }
  g.level = t.level;
  g.mesh = this;
  g.triangle = triangle;
  return g;
}

Eigen::Vector3d RestrictedMesh::facet_normal(int triangle) const {
  check_triangle(triangle);
  const std::array<int, 3>& v = triangles_[static_cast<size_t>(triangle)].vertex;
  const Eigen::Vector3d& x0 = vertices_[static_cast<size_t>(v[0])].point;
  const Eigen::Vector3d n = (vertices_[static_cast<size_t>(v[1])].point - x0)
                                .cross(vertices_[static_cast<size_t>(v[2])].point - x0);
  const double length = n.norm();
  return length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

Eigen::Vector3d RestrictedMesh::averaged_facet_normal(int vertex) const {
  check_vertex(vertex);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const int t : vertices_[static_cast<size_t>(vertex)].incident) {
    sum += facet_normal(t);
  }
  const double length = sum.norm();
  return length > 0.0 ? Eigen::Vector3d(sum / length) : Eigen::Vector3d::Zero();
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

void RestrictedMesh::check_vertex(int vertex) const {
  if (vertex < 0 || vertex >= static_cast<int>(vertices_.size()) ||
      !vertices_[static_cast<size_t>(vertex)].alive) {
    throw make_error("restricted mesh: vertex ", vertex, " is not a current vertex");
  }
}

Eigen::Vector2d RestrictedMesh::parameter(int vertex) const {
  check_vertex(vertex);
  return vertices_[static_cast<size_t>(vertex)].uv;
}

std::vector<std::array<std::uint64_t, 3>> RestrictedMesh::triangle_keys() const {
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
