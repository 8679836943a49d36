#pragma once
// The two-phase T-snake reparameterization on the affine cell image decomposition (ACID)
// (McInerney & Terzopoulos, T-snakes: Topology adaptive snakes, Medical Image Analysis 4(2)
// 2000; Terzopoulos, Deformable Models: Classic, Topology-Adaptive and Generalized
// Formulations, section 3.1 and Fig. 4(b)-(d)). Phase I intersects the deformed snake elements
// with the grid edges; the inside grid vertices are those the deformed snakes wind around
// positively; phase II builds the new snakes from the boundary triangles (mixed inside/outside
// vertices), with a node at one intersection point on every edge that joins an inside to an
// outside vertex. This is where merging and splitting happen.

#include <array>
#include <vector>

#include "dnurbs/vision/contour.h"
#include "dnurbs/vision/freudenthal_grid.h"

namespace dnurbs {

/// Nodes never sit closer to a grid vertex than this fraction of their edge (keeps the new
/// elements of non-zero length and every node strictly inside its edge).
inline constexpr double kAcidEdgeMargin = 1e-3;

/// One intersection of a snake element with a grid line of one edge family.
///
/// along  the position along the line in grid units (x for horizontal lines, y for vertical and
///        diagonal lines)
/// sign   +1 if the element crosses the line towards increasing level (y for horizontal lines, x
///        for vertical ones, x - y for diagonal ones), -1 otherwise
struct GridCrossing {
  double along;
  int sign;
};

/// Phase I: every intersection of the snake elements with the grid lines of the three edge
/// families, each line's crossings sorted by `along`. lines[family][line] with line = j for
/// horizontal lines (y = j), i for vertical lines (x = i), i - j + cells_y for diagonal lines.
/// Elements are half-open in level (an element includes its lower end), so a node lying exactly on
/// a line is counted once. Parts of elements outside the grid are ignored.
struct GridCrossings {
  std::array<std::vector<std::vector<GridCrossing>>, 3> lines;
};

/// The node of a boundary edge from the crossings of its line (sorted by along): the fraction
/// (0 at the edge's first vertex, at along = start; 1 at along = start + 1) of the crossing on the
/// edge nearest its outside vertex, its midpoint 0.5 if the edge has no crossing, kept
/// kAcidEdgeMargin away from the vertices.
double crossing_fraction_on_line(const std::vector<GridCrossing>& line, double start,
                                 bool first_inside);

/// Throws Error naming the contour and node for a node that is not finite.
GridCrossings grid_crossings(const FreudenthalGrid& grid, const std::vector<Contour>& contours);

/// The inside grid vertices: winding number of the deformed contours > 0 (counted along each
/// horizontal grid line from its crossings), so the union of overlapping snake regions is inside
/// (merging) and regions where a snake has folded over itself are outside (splitting). Vertices
/// on the grid border are always outside, so every new contour closes inside the grid.
///
/// returns  vertex_count flags, 1 for inside
std::vector<char> inside_vertices(const FreudenthalGrid& grid, const GridCrossings& crossings);

/// Phase II: the new contours from the boundary triangles. Every grid edge joining an inside to an
/// outside vertex gets one node, at the crossing on that edge nearest its outside vertex (its
/// midpoint if the edge has no crossing), kept kAcidEdgeMargin away from the vertices; in each
/// boundary triangle one element separates its inside from its outside vertices. Elements are
/// oriented with the inside on their left: outer boundaries are counter-clockwise, holes
/// clockwise. The contours are simple and pairwise disjoint.
///
/// inside   vertex_count flags from inside_vertices (or any flags with the border outside)
/// returns  one Contour (#N by 2) per connected boundary component
std::vector<Contour> boundary_contours(const FreudenthalGrid& grid, const std::vector<char>& inside,
                                       const GridCrossings& crossings);

}  // namespace dnurbs
