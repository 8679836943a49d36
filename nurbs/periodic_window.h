#pragma once
// Periodic B-splines seen through an open window: a stretch of the bi-infinite periodic spline
// written as an open (unclamped) one, so that the open algorithms of Piegl & Tiller (degree
// elevation A5.9, knot removal A5.8) apply, and the way back from an open representation to the
// control points of a periodic knot vector.

#include <Eigen/Core>

#include "dnurbs/nurbs/knot_insertion.h"
#include "dnurbs/nurbs/knot_vector.h"

namespace dnurbs {

/// The open (unclamped) B-spline that equals the periodic one with knot vector `knots` and
/// control rows `rows` (knots.control_point_count() by #columns) over the bi-infinite control
/// indices first..first + count - 1: knots t_first..t_{first+count+p} (KnotVector::
/// extended_knot) and rows P_{i mod n}. Its domain is [t_{first+p}, t_{first+count}].
/// Throws Error if `knots` is not periodic or count < p + 1.
KnotsAndRows unwrap_periodic(const KnotVector& knots, const Eigen::MatrixXd& rows, int first,
                             int count);

/// The clamped B-spline equal to the open `window` over its domain [t_p, t_{m-p}]: both domain
/// ends are inserted up to multiplicity p (Piegl & Tiller A5.4), then the knots and rows outside
/// are dropped and the ends repeated p + 1 times. The window's rows go with window.knots.
KnotsAndRows clamp_window(const KnotsAndRows& window);

/// The control rows (target.control_point_count() by #columns) of the periodic B-spline with
/// knot vector `target` that equals the open `window` wherever the window represents it.
///
/// A B-spline coefficient depends only on the function and the knots of its basis function (it
/// is the blossom of the polynomial piece at the interior knots; de Boor & Fix, Spline
/// approximation by quasi-interpolants, J. Approx. Theory 8, 1973; Ramshaw, Blossoms are polar
/// forms, CAGD 6, 1989). So periodic basis function i (for i = p..p + n - 1, one per control
/// point, i mod n) takes the coefficient of the window basis function with the same knots
/// t_i..t_{i+p+1} (equal to a relative kPeriodicSeamTolerance) whose support lies inside the
/// window's domain. Throws Error if one has no such match (the window is too short).
Eigen::MatrixXd wrap_periodic(const KnotsAndRows& window, const KnotVector& target);

}  // namespace dnurbs
