#pragma once
// The two-phase T-surface reparameterization on the tetrahedral ACID (Terzopoulos, Deformable
// Models: Classic, Topology-Adaptive and Generalized Formulations, section 3.2; McInerney &
// Terzopoulos, Topology adaptive deformable surfaces for medical image volume segmentation, IEEE
// TMI 18(10) 1999): phase I intersects the grid edges (as rays along their lines) with the
// triangles of the deformed surface; the inside grid vertices are those the surface winds around
// positively; phase II builds the new triangle mesh from the boundary tetrahedra (marching
// tetrahedra), one node on every edge joining an inside to an outside vertex.

#include <array>
#include <functional>
#include <vector>

#include "dnurbs/surface/triangle_mesh.h"
#include "dnurbs/vision/affine_cell_decomposition.h"
#include "dnurbs/vision/tetrahedral_grid.h"

namespace dnurbs {

/// Phase I: every intersection of the grid lines of the 7 edge families with the triangles of a
/// surface. A line of family d (primary axis a, the first axis with d_a = 1; other axes b < c)
/// is the set {p : p_b - d_b p_a = u, p_c - d_c p_a = v} for integer (u, v) in grid units; a
/// crossing stores its position along = p_a and sign = the sign of the triangle's projected
/// orientation in (u, v) (for the x lines, the sign of the normal's x component: +1 where the
/// surface is left going in +x). Points exactly on a shared triangle edge or vertex are counted
/// once by the top-left rule of rasterization, so closed surfaces give exact winding numbers.
class TetrahedralCrossings {
 public:
  /// Throws Error naming the vertex for a non-finite mesh vertex or the triangle for an index
  /// outside the vertex list.
  TetrahedralCrossings(const TetrahedralGrid& grid, const TriangleMesh& mesh);

  /// The crossings of the line of `family` through grid vertex `first`, sorted by along.
  const std::vector<GridCrossing>& line(int family, const Eigen::Vector3i& first) const;

 private:
  /// Dense line index of lattice point (u, v) of a family, -1 outside the grid's range.
  int line_index(int family, long long u, long long v) const;

  Eigen::Vector3i cells_;
  std::array<std::vector<std::vector<GridCrossing>>, TetrahedralGrid::kFamilies> lines_;
};

/// The inside grid vertices: winding number of the surface > 0, counted along each x line from
/// its crossings; border vertices are outside. Returns vertex_count flags, 1 for inside.
std::vector<char> inside_vertices(const TetrahedralGrid& grid,
                                  const TetrahedralCrossings& crossings);

/// Where the node of a boundary edge sits: the fraction (0 at the first vertex, 1 at the other)
/// given the edge's family, first vertex and whether the first vertex is inside.
using EdgeFraction =
    std::function<double(int family, const Eigen::Vector3i& first, bool first_inside)>;

/// The node fraction from phase I: the crossing on the edge nearest its outside vertex, its
/// midpoint when there is none, kept kAcidEdgeMargin away from the vertices.
double crossing_fraction(const TetrahedralCrossings& crossings, int family,
                         const Eigen::Vector3i& first, bool first_inside);

/// Phase II (marching tetrahedra): in each boundary tetrahedron one triangle (one or three inside
/// vertices) or two (two inside vertices) separate the inside from the outside vertices, with
/// their nodes on the tetrahedron's boundary edges at `fraction`. Nodes are shared between the
/// tetrahedra around an edge, so the mesh is closed and manifold; triangles are ordered
/// counter-clockwise seen from outside (normals point from inside to outside vertices).
///
/// inside   vertex_count flags (border vertices count as outside)
/// returns  vertices #V by 3 and triangles #F by 3 (no normals or uv)
TriangleMesh boundary_mesh(const TetrahedralGrid& grid, const std::vector<char>& inside,
                           const EdgeFraction& fraction);

}  // namespace dnurbs
