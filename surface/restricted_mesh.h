#pragma once
// The restricted (semi-regular) binary multi-triangulation of Goldenstein et al. 2005, section 4.2
// over the (u, v) domain of a ParametricSurface, adapted by stellar edge splits and welds
// (section 4.1).
//
// Base mesh: either a grid of base_cells_u by base_cells_v cells, each cell split by its diagonal
// into two right triangles that form a basic block (the diagonal is the block's internal edge),
// or any compliant triangulation of a region of the (u, v) plane (compliant_triangulation.h,
// section 5.1). Every triangle stores its apex (corner 0) and is split across the opposite edge,
// its refinement edge: newest-vertex bisection. Splitting an edge splits both triangles that
// share it (a diamond), and a neighbor whose own refinement edge differs is split first
// (interleaved refinement), so the mesh stays conforming (no T-junctions) and neighbors differ by
// at most one level: a restricted quad-tree. Only the current mesh is stored; a vertex made by a
// split is keyed by the edge it split (the keys of its two parent vertices), so a weld (the
// inverse stellar operator) rebuilds exactly the parents, and two meshes over the same base have
// the same keys for the same vertices.
//
// On a grid base, seams of periodic directions are identified (one vertex), and a pole's vertices
// stay distinct in (u, v) but merge into one vertex of the output mesh, where the triangles with
// an edge on the pole collapse and are dropped. A triangulated base identifies nothing.

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/surface/compliant_triangulation.h"
#include "dnurbs/surface/parametric_surface.h"
#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

class RestrictedMesh;

/// What a refinement test sees of a triangle (a current one or the parent a weld would make):
/// corner 0 is the apex, the split edge is corners 1-2. Corners are counter-clockwise in (u, v)
/// and their parameters are unwrapped across a seam (adjacent in the plane: the seam corner of
/// a periodic direction has u = u_max, not u_min); points and normals are the surface's at the
/// vertices. Tests that look at the mesh around the triangle (the neighbors across its edges,
/// the triangles around its corners) ask `mesh` about `triangle`, a current triangle of it.
struct RestrictedTriangleGeometry {
  std::array<Eigen::Vector2d, 3> uv;
  std::array<Eigen::Vector3d, 3> points;
  std::array<Eigen::Vector3d, 3> normals;
  int level = 0;  ///< bisections from the base mesh (0 for a base triangle)
  const RestrictedMesh* mesh = nullptr;
  int triangle = -1;
};

/// The application's refinement test (Goldenstein et al. 2005, section 5): true if the triangle
/// needs to be split. Coarsening welds a vertex when the test is false for every parent the weld
/// restores (seen in the mesh after the weld).
using RefinementTest = std::function<bool(const RestrictedTriangleGeometry&)>;

/// The adaptive mesh over a surface's (u, v) domain (see the file comment).
class RestrictedMesh {
 public:
  /// Deepest bisection: 20 halvings of a base triangle's edges, so a grid base's (u, v) stay
  /// exact binary fractions of a cell (at most 10 + 20 bits).
  static constexpr int kMaxLevel = 40;
  /// Largest base grid along a direction.
  static constexpr int kMaxBaseCells = 1024;
  /// Default depth limit of refine().
  static constexpr int kDefaultMaxLevel = 24;

  /// The base mesh: 2 base_cells_u base_cells_v right triangles. Throws Error naming the value
  /// if a count is below 1 (below 3 along a periodic direction) or above kMaxBaseCells.
  RestrictedMesh(const ParametricSurface& surface, int base_cells_u, int base_cells_v);
  /// The base mesh: a compliant triangulation (make_compliant) whose (u, v) lie in the surface's
  /// domain. Throws Error naming the vertex outside the domain, or the number of compliance
  /// violations (compliance_violations) if there are any.
  RestrictedMesh(const ParametricSurface& surface, const BlockTriangulation& base);

  const ParametricSurface& surface() const { return surface_; }
  /// The grid of a grid base (0 for a triangulated base).
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
  bool weld(int vertex) { return weld_restoring(vertex, nullptr); }

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
  /// The unit normal of a current triangle's vertex points, (x1 - x0) x (x2 - x0) normalized (its
  /// corners counter-clockwise in (u, v)), zero for a triangle collapsed in space.
  Eigen::Vector3d facet_normal(int triangle) const;
  /// The mean of the facet normals of the current triangles around a current vertex, normalized
  /// (zero if they cancel).
  Eigen::Vector3d averaged_facet_normal(int vertex) const;
  /// Every current triangle as the keys of its corners (apex first), sorted: equal for two meshes
  /// over the same base when they have the same triangles, and different otherwise unless two
  /// distinct vertices' keys collide (about n^2 / 2^64 for n vertices). A base vertex's key is its
  /// index in the base (a grid base: i (base_cells_v + 1) + j, seams identified); a split
  /// vertex's key is a 64-bit mix of its edge's two keys (order-free), with the top bit set.
  std::vector<std::array<std::uint64_t, 3>> triangle_keys() const;

  /// The current mesh with each pole merged into one vertex and the triangles collapsed there
  /// dropped (ParametricSurfaceMeshBuilder): vertices, unit normals, uv = (u, v), triangles
  /// wound along the surface normal.
  TriangleMesh to_triangle_mesh(std::string name = "surface") const;

 private:
  struct Vertex {
    std::uint64_t key = 0;
    std::array<std::uint64_t, 2> split_edge{0, 0};  // keys of the edge it split (none: base)
    bool from_split = false;
    bool alive = false;
    Eigen::Vector2d uv = Eigen::Vector2d::Zero();  // canonical (seam vertices at the start)
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    std::vector<int> incident;  // current triangles using it
  };
  // Corners in base coordinates: cell units on a grid base (exact binary fractions, unwrapped
  // across a seam), (u, v) on a triangulated base.
  struct Triangle {
    std::array<int, 3> vertex{-1, -1, -1};
    std::array<Eigen::Vector2d, 3> corner;
    int level = 0;
    bool alive = false;
  };

  Eigen::Vector2d parameter_at(const Eigen::Vector2d& corner) const;
  int create_vertex(const Eigen::Vector2d& corner, std::uint64_t key);
  int add_triangle(const std::array<int, 3>& vertex, const std::array<Eigen::Vector2d, 3>& corner,
                   int level);
  void remove_triangle(int triangle);
  void split_compatible(int triangle, int& count, std::vector<int>* created);
  void bisect(int triangle, int partner, std::vector<int>* created);
  // The parents that welding `vertex` restores (vertices apex first, base coordinates).
  bool weld_parents(int vertex, std::vector<Triangle>& parents) const;
  // Welds `vertex` if it can; the restored parents' ids go to `parents` (if not null).
  bool weld_restoring(int vertex, std::vector<int>* parents);
  static std::uint64_t edge_key(int a, int b);
  void check_triangle(int triangle) const;
  void check_vertex(int vertex) const;

  ParametricSurface surface_;
  int base_cells_u_ = 0;
  int base_cells_v_ = 0;
  std::vector<Vertex> vertices_;
  std::vector<int> free_vertices_;
  std::vector<Triangle> triangles_;
  std::vector<int> free_triangles_;
  std::unordered_map<std::uint64_t, std::array<int, 2>> edges_;
  int triangle_count_ = 0;
  int vertex_count_ = 0;
};

}  // namespace dnurbs
