#pragma once
// Which control points of a triangular NURBS surface a boundary condition or a local sculpting
// region involves (Qin & Terzopoulos, "Triangular NURBS and their dynamic generalizations",
// Computer Aided Geometric Design 14, 1997): control point a belongs to B-spline a of the DMS
// basis, whose support is the convex hull of its knot set V_beta^I.

#include <vector>

#include "dnurbs/dynamics/core/sculpted_region.h"
#include "dnurbs/nurbs/triangular_bspline_basis.h"

namespace dnurbs {

/// Relative size below which a B-spline's value on the boundary counts as zero in
/// border_control_points (the B-splines sum to one, so this bounds how far a neighbouring
/// control point's motion can move the border).
inline constexpr double kBorderTraceTolerance = 1e-12;

/// The B-splines (control points) whose trace on the domain boundary is not zero: the non-zero
/// columns of boundary_trace_conditions(basis, kSimplySupported)
/// (triangular_boundary_conditions.h), whose samples at n + 1 points of every polynomial piece
/// of every boundary edge see every non-zero trace. Fixing them holds the whole border curve
/// (a sufficient condition; the exact simply supported condition constrains combinations only
/// and leaves more freedom). Sorted, distinct.
std::vector<int> border_control_points(const TriangularBSplineBasis& basis);

/// Local sculpting: the B-splines that are non-zero at one of the region's parameters and the
/// listed control points; with margin m >= 1, also every B-spline of the domain triangles
/// within m rings (triangles sharing a vertex) of those B-splines' triangles and of the
/// triangles containing the parameters. Sorted, distinct. Throws Error naming the value for
/// margin < 0, a parameter that is not finite or lies outside the domain, or a control point
/// index out of range.
std::vector<int> triangular_sculpted_control_points(const TriangularBSplineBasis& basis,
                                                    const SculptedRegion& region, int margin);

}  // namespace dnurbs
