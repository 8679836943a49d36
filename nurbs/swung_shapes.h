#pragma once
// Prototype swung surfaces (Qin & Terzopoulos, Dynamic NURBS swung surfaces for physics-based
// shape design, CAD 27(2) 1995): exact sphere, torus, cylinder and cone, and an open hat, all
// with the periodic unit circle (Piegl & Tiller ch. 7) as trajectory and alpha = 1, so that the
// profile's x coordinate is the distance from the z axis.

#include "dnurbs/nurbs/swung_surface.h"

namespace dnurbs {

/// The periodic rational quadratic unit circle in the xy plane (8 distinct control points, no
/// seam), the trajectory of every prototype below.
NurbsCurve unit_circle_trajectory();

/// The exact sphere of the given radius about the origin: the half circle from the south pole
/// (0, 0, -r) to the north pole (0, 0, r) (5 control points, Piegl & Tiller ch. 7) swung around
/// the z axis. u runs from south to north, v counter-clockwise, so S_u x S_v points inward.
SwungSurface swung_sphere(double radius);

/// The exact torus: the periodic circle of radius `minor_radius` centred at (major_radius, 0, 0)
/// in the xz plane swung around the z axis (closed in u and v, 8 x 8 control points).
/// Throws Error unless 0 < minor_radius < major_radius.
SwungSurface swung_torus(double major_radius, double minor_radius);

/// The surface swung from the straight open profile from (x0, 0, z0) to (x1, 0, z1) (x0, x1 >= 0,
/// not both 0, and a profile of non-zero length): `profile_control_points` (>= 2) control points
/// at the Greville abscissae of a clamped uniform knot vector of degree min(3, count - 1), so
/// that the profile is linear in u. A disk (z0 = z1, x0 = 0), an annulus, a cylinder or a cone;
/// an end with x = 0 lies on the axis (a pole). Throws Error naming the value otherwise.
SwungSurface swung_open_profile(double x0, double z0, double x1, double z1,
                                int profile_control_points = 4);

/// The open cylinder x^2 + y^2 = r^2, 0 <= z <= height: swung_open_profile(r, 0, r, height).
SwungSurface swung_cylinder(double radius, double height, int profile_control_points = 4);

/// The cone from the circle of radius r at z = 0 to the apex (0, 0, height):
/// swung_open_profile(r, 0, 0, height); its last control point lies on the axis.
SwungSurface swung_cone(double radius, double height, int profile_control_points = 4);

/// An open hat: a cubic profile from the apex (0, 0, height) on the axis over a flat top to the
/// crown's side at x = crown_radius, down to a brim that ends at x = brim_radius, z = 0 (8
/// control points). Throws Error unless 0 < crown_radius < brim_radius and height > 0.
SwungSurface swung_hat(double brim_radius, double crown_radius, double height);

}  // namespace dnurbs
