#include "dnurbs/nurbs/primitive_shapes.h"

#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

const double half_sqrt2 = std::sqrt(0.5);

// (x, y, weight) of the 8 distinct control points of the periodic unit circle, from angle 0.
constexpr int kPeriodicCirclePoints = 8;
Eigen::Matrix<double, kPeriodicCirclePoints, 3> periodic_unit_circle() {
  Eigen::Matrix<double, kPeriodicCirclePoints, 3> circle;
  circle << 1, 0, 1, 1, 1, half_sqrt2, 0, 1, 1, -1, 1, half_sqrt2, -1, 0, 1, -1, -1, half_sqrt2, 0,
      -1, 1, 1, -1, half_sqrt2;
  return circle;
}

KnotVector periodic_circle_knots() {
  return KnotVector::periodic(2, {0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0});
}

}  // namespace

void check_shape_size(double value, const char* name) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    throw make_error(name, " must be finite and > 0, got ", value);
  }
}

NurbsCurve full_circle(double radius, const Eigen::Vector3d& centre) {
  check_shape_size(radius, "circle radius");
  Eigen::MatrixX3d points(9, 3);
  points << 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0, -1, 0, 0, -1, -1, 0, 0, -1, 0, 1, -1, 0, 1, 0, 0;
  points *= radius;
  points.rowwise() += centre.transpose();
  Eigen::VectorXd weights(9);
  weights << 1, half_sqrt2, 1, half_sqrt2, 1, half_sqrt2, 1, half_sqrt2, 1;
  KnotVector knots(2, {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1});
  return NurbsCurve(std::move(knots), std::move(points), std::move(weights));
}

NurbsCurve periodic_circle(double radius, const Eigen::Vector3d& centre) {
  check_shape_size(radius, "circle radius");
  const auto circle = periodic_unit_circle();
  Eigen::MatrixX3d points(kPeriodicCirclePoints, 3);
  for (int i = 0; i < kPeriodicCirclePoints; ++i) {
    points.row(i) << centre.x() + radius * circle(i, 0), centre.y() + radius * circle(i, 1),
        centre.z();
  }
  return NurbsCurve(periodic_circle_knots(), std::move(points), circle.col(2));
}

NurbsCurve half_circle_xz(double radius) {
  check_shape_size(radius, "half circle radius");
  Eigen::MatrixX3d points(5, 3);
  points << 0, 0, -1, 1, 0, -1, 1, 0, 0, 1, 0, 1, 0, 0, 1;
  points *= radius;
  Eigen::VectorXd weights(5);
  weights << 1, half_sqrt2, 1, half_sqrt2, 1;
  KnotVector knots(2, {0, 0, 0, 0.5, 0.5, 1, 1, 1});
  return NurbsCurve(std::move(knots), std::move(points), std::move(weights));
}

NurbsSurface surface_of_revolution(const NurbsCurve& profile) {
  if (profile.is_periodic()) {
    throw make_error("surface_of_revolution needs an open profile curve");
  }
  const NurbsCurve circle = full_circle(1.0);
  const int profile_count = profile.control_point_count();
  Eigen::MatrixX3d points(profile_count * 9, 3);
  Eigen::VectorXd weights(profile_count * 9);
  for (int i = 0; i < profile_count; ++i) {
    const Eigen::Vector3d p = profile.control_points().row(i).transpose();
    const double radius = std::hypot(p.x(), p.y());
    // Profile points lie in a half plane through the axis; rotate its angle by the circle's.
    const double angle = std::atan2(p.y(), p.x());
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    for (int j = 0; j < 9; ++j) {
      const Eigen::Vector3d unit = circle.control_points().row(j).transpose();
      const int row = i * 9 + j;
      points.row(row) << radius * (c * unit.x() - s * unit.y()),
          radius * (s * unit.x() + c * unit.y()), p.z();
      weights[row] = profile.weights()[i] * circle.weights()[j];
    }
  }
  return NurbsSurface(profile.knots(), circle.knots(), std::move(points), std::move(weights));
}

NurbsSurface sphere(double radius) {
  return surface_of_revolution(half_circle_xz(radius));
}

NurbsSurface torus(double major_radius, double minor_radius) {
  check_shape_size(major_radius, "torus major radius");
  check_shape_size(minor_radius, "torus minor radius");
  if (!(minor_radius < major_radius)) {
    throw make_error("torus minor radius ", minor_radius, " must be below the major radius ",
                     major_radius);
  }
  // The tube's circle in the xz plane centred at (R, 0, 0).
  const NurbsCurve unit = full_circle(minor_radius);
  Eigen::MatrixX3d points(9, 3);
  for (int i = 0; i < 9; ++i) {
    points.row(i) << major_radius + unit.control_points()(i, 0), 0.0, unit.control_points()(i, 1);
  }
  return surface_of_revolution(NurbsCurve(unit.knots(), points, unit.weights()));
}

NurbsSurface periodic_torus(double major_radius, double minor_radius,
                            const Eigen::Vector3d& centre) {
  check_shape_size(major_radius, "torus major radius");
  check_shape_size(minor_radius, "torus minor radius");
  const auto circle = periodic_unit_circle();
  const int n = kPeriodicCirclePoints;
  Eigen::MatrixX3d points(n * n, 3);
  Eigen::VectorXd weights(n * n);
  for (int i = 0; i < n; ++i) {    // u: around the z axis
    for (int j = 0; j < n; ++j) {  // v: around the tube
      const double distance = major_radius + minor_radius * circle(j, 0);
      points.row(i * n + j) =
          centre.transpose() + Eigen::RowVector3d(distance * circle(i, 0), distance * circle(i, 1),
                                                  minor_radius * circle(j, 1));
      weights[i * n + j] = circle(i, 2) * circle(j, 2);
    }
  }
  return NurbsSurface(periodic_circle_knots(), periodic_circle_knots(), std::move(points),
                      std::move(weights));
}

}  // namespace dnurbs
