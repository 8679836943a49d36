#pragma once
// Tolerance-bounded knot removal of open and periodic NURBS curves and surfaces (Piegl & Tiller,
// The NURBS Book, section 5.4 and eq. 5.30), done on homogeneous control points (w P, w).

#include "dnurbs/nurbs/knot_insertion.h"
#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs {

/// The outcome of removing a knot from a curve.
struct CurveKnotRemoval {
  /// The curve with the knot removed `removed_count` times (the input curve if 0).
  NurbsCurve curve;
  /// How many times the knot was removed, 0..requested.
  int removed_count = 0;
  /// True if the knot was removed as many times as requested.
  bool succeeded = false;
};

/// The outcome of removing a knot from a surface along one direction.
struct SurfaceKnotRemoval {
  /// The surface with the knot removed `removed_count` times (the input surface if 0).
  NurbsSurface surface;
  int removed_count = 0;
  bool succeeded = false;
};

/// Removes the interior knot u up to `times` times, each removal only if the curve moves by at
/// most `tolerance` (a distance in model units). One removal undoes Boehm's insertion (Piegl &
/// Tiller eq. 5.15, the equations A5.8 solves): its p - s + 1 equations for the p - s new
/// points are solved in the least-squares sense by Householder QR, which stays accurate when
/// knots nearly coincide (A5.8's recursion divides by alpha and 1 - alpha there), and the
/// removal is done if every old control point is reproduced within the tolerance, which bounds
/// the curve's motion by it (P&T eq. 5.29). For a rational curve the homogeneous points are
/// compared against tolerance * w_min / (1 + |P|_max) (P&T eq. 5.30), which bounds the distance
/// the same way. The bound holds for every removal step, so removing a knot j times moves the
/// curve by at most j * tolerance. Removal stops at the first step that fails; the removals
/// before it are kept.
///
/// Periodic curves: u wraps into the period (KnotVector::wrap_to_period, so the seam given as
/// the period end is the knot t_p) and is removed in every period: each step unwraps five periods
/// into an open curve, removes u at every copy of it, and reads the periodic control points off
/// the middle (periodic_window.h). A copy of the seam knot is taken from the end of the period
/// list (else from its start), so the period keeps its start; removing the seam's only copy
/// moves the period start to the next knot t_{p+1} (the curve is the same function of the
/// parameter, its domain is shifted).
///
/// Throws Error naming the value if u is not a knot of the curve (open curves: not an interior
/// knot), times is outside 1..multiplicity of u, a periodic curve would keep fewer than p + 1
/// control points, or tolerance is negative or not finite.
CurveKnotRemoval remove_knot(const NurbsCurve& curve, double u, int times, double tolerance);

/// Removes the interior knot u along `direction` from every row (kU: every curve of fixed v
/// index; kV: every curve of fixed u index) of the control net. Each removal step is done only
/// if every row succeeds within the tolerance (w_min and |P|_max taken over the whole net for a
/// rational surface). Periodic directions as for curves; throws Error like the curve version.
SurfaceKnotRemoval remove_knot(const NurbsSurface& surface, SurfaceDirection direction, double u,
                               int times, double tolerance);

}  // namespace dnurbs
