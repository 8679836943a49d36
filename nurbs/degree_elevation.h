#pragma once
// Degree elevation of NURBS curves and surfaces: the same shape in a basis of higher degree,
// done on homogeneous control points (w P, w) by blossoming (Ramshaw, Blossoms are polar forms,
// CAGD 6, 1989; Prautzsch, Degree elevation of B-spline curves, CAGD 1, 1984).

#include "dnurbs/nurbs/knot_insertion.h"
#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs {

/// Raises the degree of a curve from p to p + degree_increase without changing the curve; every
/// distinct knot's multiplicity grows by degree_increase (so the continuity at it is kept).
///
/// Open curves need a clamped knot vector (end knots repeated p + 1 times). The degree is raised
/// one at a time; each new control point is the mean of p + 1 blossoms of the old curve at its
/// knots, every blossom made of Boehm knot insertions (convex combinations), so the result is
/// exact to round-off however close the knots are (P&T A5.9 loses digits there in its knot
/// removal step).
/// Periodic curves give a periodic curve of degree p + degree_increase over the same period (the
/// seam knot, like every other, gains degree_increase copies, put at the start of the period
/// list): three periods of the curve are unwrapped into a clamped open curve, elevated as above,
/// and the control points of the periodic result read off its middle (periodic_window.h).
/// degree_increase = 0 returns the curve unchanged. Throws Error naming the value if
/// degree_increase < 0, p + degree_increase > kMaxDegree, or an open knot vector is not clamped.
NurbsCurve elevate_degree(const NurbsCurve& curve, int degree_increase);

/// Raises the degree along `direction` (kU: p, kV: q) by degree_increase, applied to every row
/// or column of the control net; the surface does not change. Same rules as the curve version.
NurbsSurface elevate_degree(const NurbsSurface& surface, SurfaceDirection direction,
                            int degree_increase);

}  // namespace dnurbs
