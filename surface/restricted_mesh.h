#pragma once
// The restricted (semi-regular) binary multi-triangulation of Goldenstein et al. 2005, section 4.2
// over the (u, v) domain of a ParametricSurface, adapted by stellar edge splits and welds
// (section 4.1).
//
// Base mesh: a grid of base_cells_u by base_cells_v cells, each cell split by its diagonal into
// two right triangles that form a basic block (the diagonal is the block's internal edge).
// Every triangle stores its apex (the vertex at the right angle in (u, v) cell units, corner 0)
// and is split across the opposite edge, its longest: newest-vertex bisection. Splitting an edge
// splits both triangles that share it (a diamond), and a neighbor whose own split edge differs
// is split first (interleaved refinement), so the mesh stays conforming (no T-junctions) and
// neighbors differ by at most one level: a restricted quad-tree. Only the current mesh is
// stored; a vertex remembers the edge it split, so a weld (the inverse stellar operator)
// rebuilds exactly the parents.
//
// Seams of periodic directions are identified (one vertex), and a pole's vertices stay distinct
// in (u, v) but merge into one vertex of the output mesh, where the triangles with an edge on
// the pole collapse and are dropped.

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/surface/parametric_surface.h"
#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// What a refinement test sees of a triangle (a current one or the parent a weld would make):
/// corner 0 is the apex, the split edge is corners 1-2. Corners are counter-clockwise in (u, v)
/// and their parameters are unwrapped across a seam (adjacent in the plane: the seam corner of
/// a periodic direction has u = u_max, not u_min); points and normals are the surface's at the
/// vertices.
struct RestrictedTriangleGeometry {
  std::array<Eigen::Vector2d, 3> uv;
  std::array<Eigen::Vector3d, 3> points;
  std::array<Eigen::Vector3d, 3> normals;
  int level = 0;  ///< bisections from the base mesh (0 for a base triangle)
};

/// The application's refinement test (Goldenstein et al. 2005, section 5): true if the triangle
/// needs to be split. Coarsening welds a vertex when the test is false for every parent the weld
/// restores.
using RefinementTest = std::function<bool(const RestrictedTriangleGeometry&)>;

/// The adaptive mesh over a surface's (u, v) domain (see the file comment).
class RestrictedMesh {
 public:
  /// Bisection depth supported by the integer (u, v) lattice of the vertices.
  static constexpr int kMaxLevel = 40;
  /// Largest base grid along a direction.
  static constexpr int kMaxBaseCells = 1024;
  /// Default depth limit of refine().
  static constexpr int kDefaultMaxLevel = 24;

  /// The base mesh: 2 base_cells_u base_cells_v right triangles. Throws Error naming the value
  /// if a count is below 1 (below 3 along a periodic direction) or above kMaxBaseCells.
  RestrictedMesh(const ParametricSurface& surface, int base_cells_u, int base_cells_v);

  const ParametricSurface& surface() const { return surface_; }
  int base_cells_u() const { return base_cells_u_; }
  int base_cells_v() const { return base_cells_v_; }

  // Adaptation ------------------------------------------------------------------------------
  /// Splits, until no triangle below `max_level` passes the test, every triangle that does
  /// (with the forced splits of its neighbors). Returns the number of triangles bisected.
  /// Throws Error if max_level is outside [0, kMaxLevel].
  int refine(const RefinementTest& needs_refinement, int max_level = kDefaultMaxLevel);
  /// Welds, newest vertices first and until none is left, every vertex whose weld restores
  /// parents that all fail the test. Returns the number of welds. Refinement by a test followed
  /// by coarsening by the same test leaves the refined mesh unchanged; coarsening by a test that
  /// is always false returns the base mesh.
  int coarsen(const RefinementTest& needs_refinement);
  /// Splits triangle `triangle` across its split edge, first splitting (recursively) any
  /// neighbor that does not share that edge as its own split edge. Returns the number of
  /// triangles bisected. Throws Error for a triangle that is not current or at kMaxLevel.
  int split(int triangle);
  /// True if `vertex` can be welded: it was made by a split and its triangles are exactly the
  /// four (two on an open boundary) children of that split.
  bool can_weld(int vertex) const;
  /// Welds `vertex` if can_weld(vertex); returns whether it did.
  bool weld(int vertex);

  // Queries ---------------------------------------------------------------------------------
  /// Ids of the current triangles, ascending.
  std::vector<int> triangles() const;
  int triangle_count() const { return triangle_count_; }
  /// Current vertices of the (u, v) mesh (a pole's vertices counted separately).
  int parameter_vertex_count() const { return vertex_count_; }
  /// The vertex ids of a current triangle, apex first, counter-clockwise in (u, v).
  const std::array<int, 3>& triangle_vertices(int triangle) const;
  int level(int triangle) const;
  RestrictedTriangleGeometry geometry(int triangle) const;
  /// The triangle across the edge opposite corner k (0, 1, 2), or -1 on an open boundary.
  int neighbor(int triangle, int k) const;
  /// The largest level difference between two triangles sharing an edge (at most 1).
  int max_neighbor_level_difference() const;
  /// The deepest level of a current triangle.
  int max_level() const;
  /// Parameters (u, v) of a current vertex (seam vertices at the domain start).
  Eigen::Vector2d parameter(int vertex) const;
  /// Every current triangle as the lattice keys of its corners (apex first), sorted: equal for
  /// two meshes exactly when they have the same triangles.
  std::vector<std::array<std::uint64_t, 3>> lattice_triangles() const;

  /// The current mesh with each pole merged into one vertex and the triangles collapsed there
  /// dropped (ParametricSurfaceMeshBuilder): vertices, unit normals, uv = (u, v), triangles
  /// wound along the surface normal.
  TriangleMesh to_triangle_mesh(std::string name = "surface") const;

 private:
  using Lattice = Eigen::Matrix<std::int64_t, 2, 1>;
  struct Vertex {
    Lattice lattice = Lattice::Zero();  // canonical (seam identified) lattice coordinates
    std::uint64_t key = 0;
    std::array<std::uint64_t, 2> split_edge{0, 0};  // keys of the edge it split (none: base)
    bool from_split = false;
    bool alive = false;
    Eigen::Vector2d uv = Eigen::Vector2d::Zero();
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    std::vector<int> incident;  // current triangles using it
  };
  struct Triangle {
    std::array<int, 3> vertex{-1, -1, -1};
    std::array<Lattice, 3> corner;  // unwrapped lattice coordinates of the corners
    int level = 0;
    bool alive = false;
  };

  Lattice canonical(const Lattice& x) const;
  std::uint64_t lattice_key(const Lattice& canonical_lattice) const;
  Eigen::Vector2d unwrapped_parameter(const Lattice& x) const;
  int find_or_create_vertex(const Lattice& unwrapped);
  int add_triangle(const std::array<int, 3>& vertex, const std::array<Lattice, 3>& corner,
                   int level);
  void remove_triangle(int triangle);
  void split_compatible(int triangle, int& count, std::vector<int>* created);
  void bisect(int triangle, int partner, std::vector<int>* created);
  // The parents that welding `vertex` restores (vertices apex first, unwrapped corners).
  bool weld_parents(int vertex, std::vector<Triangle>& parents) const;
  RestrictedTriangleGeometry geometry_of(const std::array<int, 3>& vertex,
                                         const std::array<Lattice, 3>& corner, int level) const;
  static std::uint64_t edge_key(int a, int b);
  void check_triangle(int triangle) const;

  ParametricSurface surface_;
  int base_cells_u_ = 0;
  int base_cells_v_ = 0;
  std::int64_t extent_u_ = 0;  // lattice units along u (base_cells_u << kCellShift)
  std::int64_t extent_v_ = 0;
  std::vector<Vertex> vertices_;
  std::vector<int> free_vertices_;
  std::unordered_map<std::uint64_t, int> vertex_by_key_;
  std::vector<Triangle> triangles_;
  std::vector<int> free_triangles_;
  std::unordered_map<std::uint64_t, std::array<int, 2>> edges_;
  int triangle_count_ = 0;
  int vertex_count_ = 0;
};

}  // namespace dnurbs
