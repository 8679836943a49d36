#include "dnurbs/nurbs/swung_shapes.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "dnurbs/nurbs/shape_generators.h"

namespace dnurbs {

NurbsCurve unit_circle_trajectory() {
  return periodic_circle(1.0);
}

SwungSurface swung_sphere(double radius) {
  check_shape_size(radius, "swung sphere radius");
  return SwungSurface(half_circle_xz(radius), unit_circle_trajectory());
}

SwungSurface swung_torus(double major_radius, double minor_radius) {
  check_shape_size(major_radius, "swung torus major radius");
  check_shape_size(minor_radius, "swung torus minor radius");
  if (!(minor_radius < major_radius)) {
    throw make_error("swung torus minor radius ", minor_radius, " must be below the major radius ",
                     major_radius);
  }
  // The tube's periodic circle, turned from the xy into the xz plane and moved to x = R.
  const NurbsCurve tube = periodic_circle(minor_radius);
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(tube.control_point_count(), 3);
  points.col(0) = tube.control_points().col(0).array() + major_radius;
  points.col(2) = tube.control_points().col(1);
  return SwungSurface(NurbsCurve(tube.knots(), std::move(points), tube.weights()),
                      unit_circle_trajectory());
}

SwungSurface swung_open_profile(double x0, double z0, double x1, double z1,
                                int profile_control_points) {
  for (const auto& [value, name] :
       {std::pair{x0, "x0"}, std::pair{z0, "z0"}, std::pair{x1, "x1"}, std::pair{z1, "z1"}}) {
    if (!std::isfinite(value)) {
      throw make_error("swung open profile ", name, " is ", value, ", must be finite");
    }
  }
  if (x0 < 0.0 || x1 < 0.0 || (x0 == 0.0 && x1 == 0.0)) {
    throw make_error("swung open profile x0 = ", x0, ", x1 = ", x1,
                     ": both must be >= 0 and one > 0 (the distance from the axis)");
  }
  if (x0 == x1 && z0 == z1) {
    throw make_error("swung open profile from (", x0, ", ", z0, ") to (", x1, ", ", z1,
                     ") has zero length");
  }
  return SwungSurface(straight_profile(x0, z0, x1, z1, profile_control_points, 1.0),
                      unit_circle_trajectory());
}

SwungSurface swung_cylinder(double radius, double height, int profile_control_points) {
  check_shape_size(radius, "swung cylinder radius");
  check_shape_size(height, "swung cylinder height");
  return swung_open_profile(radius, 0.0, radius, height, profile_control_points);
}

SwungSurface swung_cone(double radius, double height, int profile_control_points) {
  check_shape_size(radius, "swung cone radius");
  check_shape_size(height, "swung cone height");
  return swung_open_profile(radius, 0.0, 0.0, height, profile_control_points);
}

SwungSurface swung_hat(double brim_radius, double crown_radius, double height) {
  check_shape_size(brim_radius, "swung hat brim radius");
  check_shape_size(crown_radius, "swung hat crown radius");
  check_shape_size(height, "swung hat height");
  if (!(crown_radius < brim_radius)) {
    throw make_error("swung hat crown radius ", crown_radius, " must be below the brim radius ",
                     brim_radius);
  }
  const double c = crown_radius;
  const double brim = brim_radius - crown_radius;
  Eigen::MatrixX3d points(8, 3);
  // Apex on the axis, flat top, the crown's side, then the brim out to (brim_radius, 0, 0).
  points << 0.0, 0.0, height, 0.6 * c, 0.0, height, c, 0.0, height, c, 0.0, 0.45 * height, c, 0.0,
      0.05 * height, c + 0.3 * brim, 0.0, 0.0, c + 0.65 * brim, 0.0, 0.0, brim_radius, 0.0, 0.0;
  return SwungSurface(NurbsCurve(KnotVector::clamped_uniform(3, 8), std::move(points)),
                      unit_circle_trajectory());
}

}  // namespace dnurbs
