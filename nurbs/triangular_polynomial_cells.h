#pragma once
// The polynomial pieces of triangular B-splines inside one domain triangle. A simplex spline
// M(. | V) is a polynomial on every region of the plane cut by the segments between pairs of
// its knots (the "complete graph" of V: Micchelli, "On a numerically efficient method for
// computing multivariate B-splines", 1979; Dahmen, Micchelli & Seidel, Mathematics of
// Computation 59, 1992, section 2). The DMS B-splines that do not vanish on a domain
// triangle T are therefore all polynomials on each cell of T cut by the segments of their knot
// sets: the knot segments of the triangles that overlap T, clipped to T.
//
// The cells are found by recursive splitting: a convex polygon (at first T) that the interior
// of some knot segment crosses is cut in two by that segment's line, and each half keeps the
// segments that cross it; what no segment crosses is a cell. Cutting by whole lines refines the
// arrangement of the segments, so the B-splines are polynomials on every cell, and a
// quadrature rule of degree d on each cell integrates every polynomial integrand of degree d
// built from them exactly.

#include <vector>

#include <Eigen/Core>

#include "dnurbs/nurbs/triangular_bspline_basis.h"

namespace dnurbs {

/// A convex polygon, counter-clockwise.
using ConvexPolygon = std::vector<Eigen::Vector2d>;

/// The knot segments that cross the interior of domain triangle t, clipped to it: the segments
/// between two knots of one knot set V_beta^I of an overlapping triangle I (two knots of one
/// cloud, or t_{i,a} and t_{j,b} with a + b <= n), without repeats and without the parts that
/// lie on t's edges. Each row is (u0, v0, u1, v1).
Eigen::MatrixX4d knot_segments_in_triangle(const TriangularBSplineBasis& basis, int t);

/// The cells of domain triangle t on which every B-spline is one polynomial: convex polygons
/// that tile t (their areas sum to t's, up to round-off). Cells thinner than the basis's snap
/// tolerance are dropped (they carry no measurable area).
std::vector<ConvexPolygon> polynomial_cells(const TriangularBSplineBasis& basis, int t);

}  // namespace dnurbs
