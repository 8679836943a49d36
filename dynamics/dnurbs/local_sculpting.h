#pragma once
// Local sculpting: when a designer pushes on one place of a large D-NURBS shape, only the
// control points whose basis functions reach that place (and a few rings around them) need to
// move; freezing the rest removes their coordinates from the system (a smaller matrix and
// factor, a cheaper step) at the price of a stiffer response near the frozen border. This
// chooses those control points from where the forces, springs and constraints act; the error
// against the full solve falls as the margin grows (tests/dynamics/test_local_sculpting.cpp,
// bench needs.csv).

#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/sculpted_region.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs {

/// The control points that influence the region: the (p + 1)(q + 1) whose basis functions are
/// non-zero on the knot span of each parameter (N_{k-p..k}, Piegl & Tiller A2.1-A2.2), and the
/// listed control points, each grown by `margin` rings of the control net (index distance at
/// most `margin` along u and along v, wrapping across periodic directions). Sorted, distinct.
/// Throws Error naming the value for margin < 0, a parameter outside the domain or not finite,
/// or a control point index out of range.
std::vector<int> sculpted_control_points(const NurbsSurface& surface, const SculptedRegion& region,
                                         int margin);
/// The same for a curve (ring = index distance along the curve).
std::vector<int> sculpted_control_points(const NurbsCurve& curve, const SculptedRegion& region,
                                         int margin);

/// Fixes (DNurbsModel::fix_control_point) every control point of the model's initial shape that
/// is not in sculpted_control_points(region, margin); a free weight stays free. Returns the
/// number of control points frozen. Throws Error as sculpted_control_points.
int freeze_outside_sculpted_region(DNurbsSurface& model, const SculptedRegion& region, int margin);
int freeze_outside_sculpted_region(DNurbsCurve& model, const SculptedRegion& region, int margin);

}  // namespace dnurbs
