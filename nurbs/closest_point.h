#pragma once
// Closest-point projection onto NURBS curves and surfaces and point inversion, as one-off calls.
// Each call builds a CurveProjector or SurfaceProjector (curve_projector.h, surface_projector.h)
// and runs one query: the globally nearest point, found with a guarantee (convex-hull bounds on
// Bezier pieces, exact isolation of the stationary points, Newton's method to round-off, ends,
// boundary curves and corners included). For many queries on one shape, build the projector once.

#include <Eigen/Core>

#include "dnurbs/nurbs/curve_projector.h"
#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"
#include "dnurbs/nurbs/surface_projector.h"

namespace dnurbs {

/// The globally nearest point of `curve` to `point`; see CurveProjector::closest_point.
CurveProjection closest_point(const NurbsCurve& curve, const Eigen::Vector3d& point);
/// The globally nearest point of `surface` to `point`; see SurfaceProjector::closest_point.
SurfaceProjection closest_point(const NurbsSurface& surface, const Eigen::Vector3d& point);

/// Point inversion: the parameter of a point on `curve`, to round-off; throws Error naming the
/// distance if `point` is farther than `tolerance` (model units) from the curve.
double invert_point(const NurbsCurve& curve, const Eigen::Vector3d& point, double tolerance);
/// Point inversion: the parameters (u, v) of a point on `surface`, to round-off; throws Error
/// naming the distance if `point` is farther than `tolerance` (model units) from the surface.
Eigen::Vector2d invert_point(const NurbsSurface& surface, const Eigen::Vector3d& point,
                             double tolerance);

}  // namespace dnurbs
