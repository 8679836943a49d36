#pragma once
// Base meshes for the restricted mesh (restricted_mesh.h) from arbitrary triangulations of a
// region of the (u, v) plane (Goldenstein et al. 2005, section 5.1: a base mesh made compliant
// with the structure of the restricted binary multi-triangulation, section 4.2, "through a
// one-time application of carefully selected edge splits").
//
// A triangulation is compliant when every triangle has a refinement edge and each interior
// refinement edge is the refinement edge of the neighbour across it too: the triangles pair into
// basic blocks (diamonds) across their common refinement edge, and a triangle whose refinement
// edge is on the boundary is a block of its own half. Newest-vertex bisection from such a
// labelling stays conforming (interleaved refinement).

#include <Eigen/Core>

namespace dnurbs {

/// A triangulation of a region of the (u, v) plane labelled for the restricted mesh.
///
/// uv         #V by 2 vertex parameters (u, v)
/// triangles  #T by 3 vertex indices, counter-clockwise in (u, v), apex first: the refinement
///            edge of a triangle is its corners 1-2
struct BlockTriangulation {
  Eigen::MatrixX2d uv;
  Eigen::MatrixX3i triangles;
};

/// make_compliant's result: the labelled triangulation (the input's vertices first, in their
/// order, then one vertex per split edge at the edge's midpoint) and what it took.
struct CompliantTriangulation {
  BlockTriangulation mesh;
  int paired_blocks = 0;     ///< pairs of input triangles across a common edge (no split)
  int boundary_splits = 0;   ///< input triangles halved across a boundary edge
  bool barycentric = false;  ///< the fallback: every input triangle split 1-to-3
  int added_vertices = 0;    ///< mesh.uv.rows() minus the input's vertex count
};

/// Labels a conforming triangulation (each edge shared by at most two triangles; any winding,
/// made counter-clockwise in (u, v)). A maximum matching of the dual graph (Edmonds' blossom
/// algorithm) pairs the most triangles across common edges into blocks; a triangle left over is
/// then matched to a boundary edge through an augmenting path (which keeps the number of pairs),
/// and that boundary edge is split, halving the triangle into one block (one added vertex each).
/// If a triangle is still left over (no alternating path reaches the boundary, e.g. a closed
/// region of odd size), every input triangle is split 1-to-3 at its centroid instead: each child's
/// refinement edge is the input edge it keeps, shared with the neighbour's child.
/// Throws Error naming the triangle or edge for an index out of range, a repeated or collinear
/// corner, or an edge shared by more than two triangles.
CompliantTriangulation make_compliant(const Eigen::MatrixX2d& uv,
                                      const Eigen::MatrixX3i& triangles);

/// The fallback of make_compliant on its own: every triangle split 1-to-3 at its centroid (the
/// centroids appended after the input's vertices), each child's refinement edge the input edge it
/// keeps. Adds one vertex per triangle and triples them. Throws Error as make_compliant.
CompliantTriangulation make_compliant_by_barycentric_split(const Eigen::MatrixX2d& uv,
                                                           const Eigen::MatrixX3i& triangles);

/// Interior refinement edges that are not the refinement edge of the triangle across them, plus
/// triangles that are not counter-clockwise in (u, v): 0 for a compliant triangulation. Throws
/// Error as make_compliant for a non-conforming triangulation.
int compliance_violations(const BlockTriangulation& triangulation);

}  // namespace dnurbs
