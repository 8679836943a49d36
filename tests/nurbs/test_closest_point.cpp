#include "nurbs/closest_point.h"

#include <cmath>

#include <gtest/gtest.h>

#include "nurbs/primitive_shapes.h"
#include "sample_shapes.h"

namespace dnurbs {
namespace {

TEST(ClosestPoint, ProjectsOntoTheCircleRadially) {
  const NurbsCurve circle = full_circle(2.0);
  for (int i = 0; i < 50; ++i) {
    const double angle = 0.1 + i * 0.12;
    const Eigen::Vector3d query(3.0 * std::cos(angle), 3.0 * std::sin(angle), 0.7);
    const CurveProjection projection = closest_point(circle, query);
    // The nearest circle point lies on the ray of the query's angle; Newton converges to
    // rounding (1e-15 relative) on this convex problem.
    EXPECT_NEAR(
        (projection.point - Eigen::Vector3d(2.0 * std::cos(angle), 2.0 * std::sin(angle), 0))
            .norm(),
        0.0, 1e-12);
    EXPECT_NEAR(projection.distance, std::hypot(1.0, 0.7), 1e-12);
  }
}

TEST(ClosestPoint, RecoversTheParametersOfSurfacePoints) {
  // A wavy rational patch: a grid of control points lifted and jittered (a surface without
  // folds, as projection needs; on a folded one the nearest point can be another sheet's).
  NurbsSurface surface = testing::random_rational_surface(3, 3, 81);
  Eigen::MatrixX3d points = surface.control_points();
  const int count_v = surface.control_point_count_v();
  for (int i = 0; i < surface.control_point_count(); ++i) {
    const double x = i / count_v;
    const double y = i % count_v;
    points.row(i) << x + 0.1 * points(i, 0), y + 0.1 * points(i, 1), 0.5 * points(i, 2);
  }
  surface.set_control_points(points);
  const NurbsSurface unit_sphere = sphere(1.0);
  for (int i = 0; i < 30; ++i) {
    const Eigen::Vector2d uv(0.05 + 0.03 * i, 0.9 - 0.025 * i);
    const Eigen::Vector3d on_sphere = unit_sphere.point(uv.x(), uv.y());
    const SurfaceProjection projection = closest_point(unit_sphere, 1.5 * on_sphere);
    EXPECT_NEAR((projection.point - on_sphere).norm(), 0.0, 1e-12);
    EXPECT_NEAR(projection.distance, 0.5, 1e-12);
    // A point on the random surface projects to itself (distance ~ 0).
    const SurfaceProjection self = closest_point(surface, surface.point(uv.x(), uv.y()));
    EXPECT_LT(self.distance, 1e-10);
  }
}

}  // namespace
}  // namespace dnurbs
