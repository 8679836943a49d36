#pragma once
// Boundary conditions of triangular D-NURBS surfaces. Unlike tensor-product splines with
// clamped knots, the trace of a DMS spline on a boundary edge depends on many B-splines (the
// knots of boundary vertices lie outside the domain, so the supports of most B-splines of a
// boundary triangle cross the edge), and fixing control points does not fix the boundary. The
// conditions are imposed exactly instead: the trace on a boundary edge is a univariate
// polynomial of degree n between the points where knot segments meet the edge, so it vanishes
// if it vanishes at n + 1 points of every such piece (and its normal derivative, of degree
// n - 1, likewise). The admissible coordinates are the null space of these conditions.

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "dnurbs/nurbs/triangular_bspline_basis.h"

namespace dnurbs {

/// Which quantities vanish on the boundary.
enum class BoundaryCondition {
  kSimplySupported,  ///< the value (w = 0; the moment condition is natural)
  kClamped           ///< the value and the normal derivative (w = dw/dn = 0)
};

/// The conditions C c = 0 on scalar B-spline coefficients c (one per B-spline) under which
/// sum_a c_a N_a and, for kClamped, its normal derivative vanish on every listed boundary edge
/// (rows of `edges`, pairs of vertex indices as Triangulation::boundary_edges(); all boundary
/// edges if empty). Rows: samples at n + 1 Gauss-Legendre points of every piece of every edge
/// between the points where knot segments meet it (values taken from inside the domain).
/// C is #samples by function_count(). Throws Error for an edge that is not a boundary edge.
Eigen::SparseMatrix<double> boundary_trace_conditions(const TriangularBSplineBasis& basis,
                                                      BoundaryCondition condition,
                                                      const Eigen::MatrixX2i& edges = {});

/// A basis Z (function_count() by #admissible) of the coefficients that satisfy C c = 0:
/// coefficients of B-splines that no condition involves map to themselves, the others to an
/// orthonormal basis of the null space of their columns of C (rank-revealing QR, rank by the
/// relative threshold 1e-10). Solving a problem A c = f under the conditions is
/// (Z^T A Z) y = Z^T f, c = Z y.
Eigen::SparseMatrix<double> constraint_null_space(const Eigen::SparseMatrix<double>& conditions);

}  // namespace dnurbs
