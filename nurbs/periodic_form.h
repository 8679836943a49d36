#pragma once
// Periodic shapes in exchange formats that have no periodic knot vector (STEP, IGES, OBJ): a
// periodic basis is written as the open, unclamped basis over its extended knot vector with the
// first p control points repeated at the end (the same curve over the same domain), and a file's
// open shape is read back as periodic when its knots and control points have exactly that form.

#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"
#include "dnurbs/nurbs/shape.h"

namespace dnurbs {

/// The open form of a curve: a periodic curve of n distinct control points becomes the open
/// curve over its extended knot vector (n + 2p + 1 knots) with n + p control points (the first p
/// repeated) and the same domain, equal to it everywhere on the domain. An open curve is returned
/// unchanged.
NurbsCurve open_form(const NurbsCurve& curve);

/// The open form of a surface, direction by direction as for curves: control points
/// (n_u + p_u * periodic_u) by (n_v + p_v * periodic_v), u index outer.
NurbsSurface open_form(const NurbsSurface& surface);

/// The open form of a curve or surface (the overloads above), as exchange formats write them.
Shape open_form(const Shape& shape);

/// The periodic form of an open curve that is the open form of a periodic one: its knots are a
/// periodic extension (t_{i+n} - t_i the same period T for every i, to kPeriodicSeamTolerance
/// relative) and its last p control points and weights repeat its first p (to 1e-12 relative to
/// the largest coordinate). Any other curve, and every periodic one, is returned unchanged, so
/// that periodic_form(open_form(c)) == c.
NurbsCurve periodic_form(const NurbsCurve& curve);

/// The periodic form of a surface, direction by direction: a direction becomes periodic when
/// its knots are a periodic extension and, for every control point row along it, the last p
/// control points and weights repeat the first p.
NurbsSurface periodic_form(const NurbsSurface& surface);

}  // namespace dnurbs
