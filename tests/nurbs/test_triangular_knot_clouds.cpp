// Tests of nurbs/triangular_knot_clouds.h: the standard placement satisfies the DMS conditions
// on several domains and degrees, and every violated condition is reported with the knot.

#include "dnurbs/nurbs/triangular_knot_clouds.h"

#include <gtest/gtest.h>

#include "../common/error_message.h"
#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/simplex_spline.h"
#include "triangular_test_helpers.h"

namespace dnurbs {
namespace {

using testing::error_message;

TEST(StandardKnotClouds, SatisfyTheDmsConditionsOnEveryTestDomainUpToTheMaximumDegree) {
  for (const auto& [name, triangulation] : test::triangular_test_domains()) {
    for (int n = 1; n <= kMaxTriangularDegree; ++n) {
      const TriangularKnotClouds clouds = standard_knot_clouds(triangulation, n);
      EXPECT_NO_THROW(check_knot_clouds(triangulation, clouds)) << name << " degree " << n;
      for (int i = 0; i < triangulation.vertex_count(); ++i) {
        EXPECT_EQ(clouds.knot(i, 0), triangulation.vertex(i));
        // Within the cloud radius 0.3 h_i (h_i <= the longest edge at i).
        for (int b = 1; b <= n; ++b) {
          const double distance = (clouds.knot(i, b) - triangulation.vertex(i)).norm();
          EXPECT_GT(distance, 0.0);
          EXPECT_LE(distance, 0.3 * triangulation.diameter());
        }
      }
    }
  }
}

TEST(StandardKnotClouds, BoundaryKnotsLieOutsideTheDomain) {
  const Triangulation l_shape = l_shape_triangulation(2);
  const TriangularKnotClouds clouds = standard_knot_clouds(l_shape, 3);
  int outside = 0;
  for (int i = 0; i < l_shape.vertex_count(); ++i) {
    for (int b = 1; b <= 3; ++b) {
      const bool located = l_shape.locate(clouds.knot(i, b)) >= 0;
      if (l_shape.is_boundary_vertex(i)) {
        EXPECT_FALSE(located) << "vertex " << i << " knot " << b;
        ++outside;
      } else {
        EXPECT_TRUE(located) << "vertex " << i << " knot " << b;
      }
    }
  }
  EXPECT_EQ(outside, 3 * 16);  // 16 boundary vertices on the L's perimeter of 8 half-units
}

TEST(KnotCloudChecks, EachViolatedConditionNamesTheKnot) {
  const Triangulation square =
      rectangle_triangulation(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), 2, 2);
  const int n = 2;
  const TriangularKnotClouds good = standard_knot_clouds(square, n);
  const int corner = 0;  // boundary vertex (0, 0)
  const int center = 4;  // interior vertex (0.5, 0.5)
  ASSERT_EQ(square.vertex(center), Eigen::Vector2d(0.5, 0.5));
  auto with_knot = [&](int vertex, int b, const Eigen::Vector2d& position) {
    Eigen::MatrixX2d knots = good.knots();
    knots.row(vertex * (n + 1) + b) = position.transpose();
    return TriangularKnotClouds(square, n, knots);
  };
  // Condition 4: a boundary knot inside the domain.
  EXPECT_NE(error_message([&] {
              check_knot_clouds(square, with_knot(corner, 1, Eigen::Vector2d(0.05, 0.02)));
            }).find("t[0][1] lies inside the domain across the boundary edge"),
            std::string::npos);
  // Condition 2: an interior knot moved across a whole triangle flips knot triangles.
  EXPECT_NE(error_message([&] {
              check_knot_clouds(square, with_knot(center, 1, Eigen::Vector2d(0.95, 0.07)));
            }).find("DMS condition"),
            std::string::npos);
  // Condition 5: three knots of one cloud on a line.
  const Eigen::Vector2d t1 = good.knot(center, 1);
  const Eigen::Vector2d on_line = square.vertex(center) + 0.5 * (t1 - square.vertex(center));
  EXPECT_NE(error_message([&] {
              check_knot_clouds(square, with_knot(center, 2, on_line));
            }).find("collinear"),
            std::string::npos);
  // Condition 1 and sizes, at construction.
  EXPECT_NE(error_message([&] {
              with_knot(center, 0, Eigen::Vector2d(0.5, 0.51));
            }).find("must be vertex 4"),
            std::string::npos);
  EXPECT_THROW(TriangularKnotClouds(square, n, Eigen::MatrixX2d::Zero(5, 2)), Error);
  EXPECT_THROW(TriangularKnotClouds(square, 0, square.vertices()), Error);
  EXPECT_THROW(with_knot(center, 2, Eigen::Vector2d(std::nan(""), 0.5)), Error);
  // Settings.
  KnotCloudSettings settings;
  settings.radius = 0.6;
  EXPECT_THROW(standard_knot_clouds(square, n, settings), Error);
  EXPECT_THROW(standard_knot_clouds(square, kMaxTriangularDegree + 1), Error);
  // Clouds ten times too large fail condition 2 (never silently).
  Eigen::MatrixX2d large = good.knots();
  for (int i = 0; i < square.vertex_count(); ++i) {
    for (int b = 1; b <= n; ++b) {
      large.row(i * (n + 1) + b) =
          square.vertex(i).transpose() + 10.0 * (good.knot(i, b) - square.vertex(i)).transpose();
    }
  }
  EXPECT_NE(error_message([&] {
              check_knot_clouds(square, TriangularKnotClouds(square, n, large));
            }).find("DMS condition"),
            std::string::npos);
}

}  // namespace
}  // namespace dnurbs
