#pragma once
// Exact rational shapes: circles, arcs and surfaces of revolution (Piegl & Tiller ch. 7-8).

#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs {

/// The check of every size a shape generator takes (a radius, a length, a height): throws Error
/// "<name> must be finite and > 0, got <value>" otherwise.
void check_shape_size(double value, const char* name);

/// The rational quadratic full circle of the given radius in the xy plane around `centre`:
/// 9 control points on a square, weights 1 and sqrt(2)/2, knots
/// {0,0,0,1/4,1/4,1/2,1/2,3/4,3/4,1,1,1}.
NurbsCurve full_circle(double radius, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());

/// The same circle as a closed (periodic) curve without a seam: 8 distinct control points,
/// period knots {0, 1/4, 1/4, 1/2, 1/2, 3/4, 3/4, 1, 1}.
NurbsCurve periodic_circle(double radius, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());

/// The rational quadratic half circle in the xz plane from the south pole (0, 0, -r) through
/// (r, 0, 0) to the north pole (0, 0, r): 5 control points, knots {0,0,0,1/2,1/2,1,1,1}.
NurbsCurve half_circle_xz(double radius);

/// The surface obtained by sweeping `profile` (u direction) once around the z axis (v direction,
/// the 9-point rational quadratic circle). Weights multiply: w_ij = w_i^profile w_j^circle.
NurbsSurface surface_of_revolution(const NurbsCurve& profile);

/// The rational sphere of the given radius about the origin: surface_of_revolution(half_circle_xz).
NurbsSurface sphere(double radius);

/// A torus about the z axis with tube centre distance `major_radius` and tube radius
/// `minor_radius`.
NurbsSurface torus(double major_radius, double minor_radius);

/// The torus as a surface periodic in both directions (u around the z axis, v around the tube
/// from the outer equator upwards), 8 x 8 distinct control points, centred at `centre`.
NurbsSurface periodic_torus(double major_radius, double minor_radius,
                            const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());

}  // namespace dnurbs
