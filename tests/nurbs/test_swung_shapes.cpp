// Tests of nurbs/swung_shapes.h: the prototype swung surfaces are the exact quadrics and torus
// they name, and the open hat has the shape its parameters describe.

#include "dnurbs/nurbs/swung_shapes.h"

#include <cmath>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

constexpr int kSamples = 200;

TEST(SwungSphere, RadiusErrorIsBelow1e13Everywhere) {
  for (const double radius : {1.0, 2.5}) {
    const SwungSurface sphere = swung_sphere(radius);
    double worst = 0.0;
    for (int i = 0; i <= kSamples; ++i) {
      for (int j = 0; j <= kSamples; ++j) {
        const double u = static_cast<double>(i) / kSamples;
        const double v = static_cast<double>(j) / kSamples;
        worst = std::max(worst, std::abs(sphere.point(u, v).norm() - radius) / radius);
      }
    }
    // Exact rational circles in both curves; rounding of two quotients and one product.
    EXPECT_LT(worst, 1e-13) << "radius " << radius;
  }
  // The poles are single points on the axis.
  const SwungSurface sphere = swung_sphere(2.5);
  for (const double v : {0.0, 0.3, 0.9}) {
    EXPECT_EQ(sphere.point(0.0, v), Eigen::Vector3d(0.0, 0.0, -2.5));
    EXPECT_EQ(sphere.point(1.0, v), Eigen::Vector3d(0.0, 0.0, 2.5));
  }
}

TEST(SwungTorus, DistanceToTheTubeCircleIsTheMinorRadius) {
  const double major = 3.0;
  const double minor = 0.8;
  const SwungSurface torus = swung_torus(major, minor);
  double worst = 0.0;
  for (int i = 0; i <= kSamples; ++i) {
    for (int j = 0; j <= kSamples; ++j) {
      const Eigen::Vector3d x =
          torus.point(static_cast<double>(i) / kSamples, static_cast<double>(j) / kSamples);
      // (sqrt(x^2 + y^2) - R)^2 + z^2 = r^2 on the torus.
      worst = std::max(worst, std::abs(std::hypot(x.head<2>().norm() - major, x.z()) - minor));
    }
  }
  EXPECT_LT(worst, 1e-13);  // exact rational circles, rounding only
  EXPECT_TRUE(torus.profile().is_periodic());
  EXPECT_TRUE(torus.trajectory().is_periodic());
}

TEST(SwungCylinderAndCone, RadiusFollowsTheStraightProfileAndHeightIsLinearInU) {
  const double radius = 1.5;
  const double height = 2.0;
  const SwungSurface cylinder = swung_cylinder(radius, height, 6);
  const SwungSurface cone = swung_cone(radius, height, 5);
  EXPECT_EQ(cylinder.profile().control_point_count(), 6);
  for (int i = 0; i <= 50; ++i) {
    for (int j = 0; j <= 50; ++j) {
      const double u = i / 50.0;
      const double v = j / 50.0;
      const Eigen::Vector3d c = cylinder.point(u, v);
      const Eigen::Vector3d k = cone.point(u, v);
      // Greville-spaced collinear control points: z = height u exactly up to rounding.
      EXPECT_NEAR(c.z(), height * u, 1e-14);
      EXPECT_NEAR(c.head<2>().norm(), radius, 1e-14);
      EXPECT_NEAR(k.z(), height * u, 1e-14);
      EXPECT_NEAR(k.head<2>().norm(), radius * (1.0 - u), 1e-14);
    }
  }
  EXPECT_EQ(cone.point(1.0, 0.4), Eigen::Vector3d(0.0, 0.0, height));  // the apex
}

TEST(SwungHat, IsAnOpenSurfaceFromTheApexToTheBrim) {
  const SwungSurface hat = swung_hat(2.0, 1.0, 1.2);
  EXPECT_FALSE(hat.profile().is_periodic());
  EXPECT_TRUE(hat.trajectory().is_periodic());
  for (const double v : {0.0, 0.25, 0.6}) {
    EXPECT_EQ(hat.point(0.0, v), Eigen::Vector3d(0.0, 0.0, 1.2));  // apex on the axis
    EXPECT_NEAR(hat.point(1.0, v).head<2>().norm(), 2.0, 1e-14);   // brim edge radius
    EXPECT_EQ(hat.point(1.0, v).z(), 0.0);                         // brim at z = 0
    // Flat top: the normal at the apex is the axis (the limit at the collapsed pole).
    EXPECT_NEAR(std::abs(hat.unit_normal(0.0, v).z()), 1.0, 1e-14);
  }
  EXPECT_NE(testing::error_message([] {
              (void)swung_hat(1.0, 1.0, 1.0);
            }).find("crown radius 1 must be below the brim radius 1"),
            std::string::npos);
}

TEST(SwungOpenProfile, IsTheStraightSegmentSweptAroundTheAxis) {
  // A disk from the axis out to radius 1.5 at z = 0.4, and a slanted band.
  const SwungSurface disk = swung_open_profile(0.0, 0.4, 1.5, 0.4, 6);
  const SwungSurface band = swung_open_profile(1.0, 0.0, 2.0, 1.0, 3);
  EXPECT_EQ(disk.profile().control_point_count(), 6);
  EXPECT_EQ(band.profile().degree(), 2);  // min(3, count - 1)
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 20; ++j) {
      const double u = i / 20.0;
      const double v = j / 20.0;
      // Greville-spaced collinear control points: the profile is linear in u (rounding).
      EXPECT_NEAR(disk.point(u, v).head<2>().norm(), 1.5 * u, 1e-14);
      EXPECT_NEAR(disk.point(u, v).z(), 0.4, 1e-15);  // sum N_i = 1 up to rounding
      EXPECT_NEAR(band.point(u, v).head<2>().norm(), 1.0 + u, 1e-14);
      EXPECT_NEAR(band.point(u, v).z(), u, 1e-14);
    }
  }
  EXPECT_NE(testing::error_message([] {
              (void)swung_open_profile(0.0, 0.0, 0.0, 1.0);
            }).find("both must be >= 0 and one > 0"),
            std::string::npos);
  EXPECT_NE(testing::error_message([] {
              (void)swung_open_profile(1.0, 1.0, 1.0, 1.0);
            }).find("has zero length"),
            std::string::npos);
  EXPECT_NE(
      testing::error_message([] { (void)swung_open_profile(-1.0, 0.0, 1.0, 1.0); }).find("x0 = -1"),
      std::string::npos);
  EXPECT_NE(testing::error_message([] {
              (void)swung_open_profile(1.0, std::nan(""), 1.0, 1.0);
            }).find("z0 is nan"),
            std::string::npos);
}

TEST(SwungShapes, RejectBadDimensions) {
  EXPECT_NE(testing::error_message([] { (void)swung_sphere(-1.0); }).find("radius"),
            std::string::npos);
  EXPECT_NE(testing::error_message([] {
              (void)swung_torus(1.0, 2.0);
            }).find("minor radius 2 must be below the major radius 1"),
            std::string::npos);
  EXPECT_NE(testing::error_message([] {
              (void)swung_cylinder(1.0, 1.0, 1);
            }).find("at least 2 control points, got 1"),
            std::string::npos);
  EXPECT_THROW((void)swung_cone(1.0, std::nan(""), 4), Error);
}

}  // namespace
}  // namespace dnurbs
