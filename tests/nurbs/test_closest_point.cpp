#include "dnurbs/nurbs/closest_point.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/common/error_message.h"
#include "tests/nurbs/brute_force_projection.h"
#include "tests/nurbs/sample_shapes.h"

#include "dnurbs/nurbs/primitive_shapes.h"

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
    const int row = i / count_v;
    const double x = row;
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

TEST(ClosestPoint, CurveRegressionFindsTheGlobalNotALocalMinimum) {
  // Regression: sampling 8 points per span and Newton from the nearest sample returned a local
  // minimum 0.1086 away here, where the curve comes within 0.02549 of the query near its end.
  Eigen::MatrixX3d points(7, 3);
  points << 0.1, -0.8, 0, 0.5, -0.9, 0, 0.5, 0.1, 0, -0.4, -0.3, 0, -0.9, 0.6, 0, 0.4, 0.9, 0, -0.7,
      0.2, 0;
  const NurbsCurve curve(KnotVector::clamped_uniform(3, 7), points);
  const Eigen::Vector3d query(-0.5, 0.3, 0.0);
  const CurveProjection found = closest_point(curve, query);
  // The brute-force reference (Newton from every discrete local minimum of 256 samples per
  // span) and the projector agree to round-off.
  const double reference =
      testing::brute_force_distance(curve, testing::sample_curve(curve, 256), query);
  EXPECT_NEAR(found.distance, reference, 1e-14);
  // The values the reference prints, to their last digits.
  EXPECT_NEAR(found.distance, 0.025486050673061, 1e-14);
  EXPECT_NEAR(found.parameter, 0.984418522510566, 1e-12);
  // Stationary there: (C - Q).C' = 0 to round-off (terms |C| |C'| ~ 10, a few ulps each).
  const CurveDerivatives d = curve.derivatives(found.parameter, 1);
  EXPECT_NEAR((d.row(0).transpose() - query).dot(d.row(1).transpose()), 0.0, 1e-13);
}

TEST(ClosestPoint, SurfaceRegressionBoundaryMinimumIsStationaryAlongTheEdge) {
  // Regression: a bicubic height field and a query beyond its edge v = 1; the sampled Newton
  // search returned (0.5435, 1), 1.76889 away and not stationary along the edge, where the
  // nearest point is (0.52896, 1), 1.76780 away.
  Eigen::MatrixX3d points(16, 3);
  const double heights[16] = {0.9,  -0.2, 0.6,  -0.1, -0.1, -0.2, 0.6, 0.1,
                              -0.7, 0.9,  -0.9, 0.9,  0.0,  -0.9, 0.4, -0.5};
  for (int i = 0; i < 16; ++i) {
    const int row = i / 4;
    points.row(i) << row, i % 4, heights[i];
  }
  const NurbsSurface surface(KnotVector::clamped_uniform(3, 4), KnotVector::clamped_uniform(3, 4),
                             points);
  const Eigen::Vector3d query(1.5, 3.5, 2.0);
  const SurfaceProjection found = closest_point(surface, query);
  EXPECT_EQ(found.parameter.y(), 1.0);
  // The brute-force reference's values (1e-12 in u: the distance is flat there to 2nd order).
  EXPECT_NEAR(found.parameter.x(), 0.5289629413947925, 1e-12);
  EXPECT_NEAR(found.distance, 1.7678030021674385, 1e-14);
  // Stationary along the edge (to round-off of terms ~10), and the distance grows into the
  // domain (a boundary minimum).
  const SurfaceDerivatives d = surface.derivatives(found.parameter.x(), 1.0, 1);
  const Eigen::Vector3d offset = d(0, 0) - query;
  EXPECT_NEAR(offset.dot(d(1, 0)), 0.0, 1e-13);
  EXPECT_LT(offset.dot(d(0, 1)), 0.0);
}

TEST(ClosestPoint, InvertPointGivesTheParametersOfPointsOnTheShape) {
  // Points evaluated to round-off (1e-16) come back to within that over the speed (~10).
  const NurbsCurve circle = full_circle(2.0);
  EXPECT_NEAR(invert_point(circle, circle.point(0.3), 1e-12), 0.3, 1e-14);
  const NurbsSurface unit_sphere = sphere(1.0);
  const Eigen::Vector2d uv = invert_point(unit_sphere, unit_sphere.point(0.35, 0.6), 1e-12);
  EXPECT_NEAR(uv.x(), 0.35, 1e-14);
  EXPECT_NEAR(uv.y(), 0.6, 1e-14);
  EXPECT_THAT(
      testing::error_message([&] { invert_point(circle, Eigen::Vector3d(0.0, 0.0, 1.0), 1e-9); }),
      ::testing::HasSubstr("from the curve, farther than the tolerance 1e-09"));
  EXPECT_THAT(testing::error_message(
                  [&] { invert_point(unit_sphere, Eigen::Vector3d(0.0, 0.0, 0.5), 1e-9); }),
              ::testing::HasSubstr("is 0.5 from the surface"));
}

}  // namespace
}  // namespace dnurbs
