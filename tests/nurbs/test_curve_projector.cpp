#include "dnurbs/nurbs/curve_projector.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/common/error_message.h"
#include "tests/nurbs/brute_force_projection.h"
#include "tests/nurbs/random_shapes.h"

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/primitive_shapes.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

// A result farther than the brute-force reference by more than this (relative to the size of
// the control net, ~1) is a global miss: both are Newton-refined to ~1e-15, while a wrong local
// minimum is off by far more.
constexpr double kMiss = 1e-10;
// A query on the curve: the distance of the point found is round-off of coordinates of size ~1.
constexpr double kOnCurve = 1e-12;

// A query of kind 0 (on the curve at u), 1 (near: a random offset of 10^-4..10^-1) or 2 (far:
// anywhere in [-3, 3]^3).
Eigen::Vector3d random_query(const Eigen::Vector3d& on, int kind, std::mt19937& generator) {
  const Eigen::Vector3d direction = Eigen::Vector3d(testing::random_real(generator, -1, 1),
                                                    testing::random_real(generator, -1, 1),
                                                    testing::random_real(generator, -1, 1))
                                        .normalized();
  if (kind == 0) {
    return on;
  }
  if (kind == 1) {
    return on + std::pow(10.0, testing::random_real(generator, -4, -1)) * direction;
  }
  return 3.0 * testing::random_real(generator, 0.0, 1.0) * direction;
}

TEST(CurveProjector, FindsTheGlobalMinimumOfFourThousandQueries) {
  // 500 random curves: degrees 1..7, open (clamped or not) and periodic (every seam
  // multiplicity, perturbed seams), repeated knots, weights 0.05..20; 8 queries each.
  std::mt19937 generator(7001U);
  int misses = 0;
  int queries = 0;
  double worst_on_curve = 0.0;
  for (int trial = 0; trial < 500; ++trial) {
    const int degree = 1 + trial % 7;
    const NurbsCurve curve = testing::random_curve(
        degree, testing::trial_options(trial, degree, true), (trial / 7) % 3 != 0, generator);
    const CurveProjector projector(curve);
    const testing::CurveSamples samples = testing::sample_curve(curve, 64);
    const double start = curve.knots().domain_start();
    const double length = curve.knots().domain_end() - start;
    for (int k = 0; k < 8; ++k) {
      const double u = start + length * testing::random_real(generator, 0.0, 1.0);
      const Eigen::Vector3d query = random_query(curve.point(u), k % 3, generator);
      const CurveProjection found = projector.closest_point(query);
      const double reference = testing::brute_force_distance(curve, samples, query);
      ++queries;
      misses += found.distance > reference + kMiss ? 1 : 0;
      EXPECT_LE(found.distance, reference + kMiss) << "trial " << trial << " query " << k;
      // The reference finds the global minimum too (both are distances of curve points).
      EXPECT_GE(found.distance, reference - kMiss) << "trial " << trial << " query " << k;
      EXPECT_EQ(found.distance, (curve.point(found.parameter) - query).norm());
      if (k % 3 == 0) {
        worst_on_curve = std::max(worst_on_curve, found.distance);
        EXPECT_LT(found.distance, kOnCurve) << "trial " << trial;
      }
    }
  }
  EXPECT_EQ(misses, 0);
  std::cout << "[ measured ] " << misses << " misses of " << queries
            << " queries; largest distance of a query on the curve " << worst_on_curve << "\n";
}

TEST(CurveProjector, InvertsPointsOnTheCurveToRoundOff) {
  std::mt19937 generator(7002U);
  double worst = 0.0;
  for (int trial = 0; trial < 300; ++trial) {
    const int degree = 1 + trial % 7;
    testing::RandomKnotOptions options = testing::trial_options(trial, degree, true);
    options.extra_control_points = 1;  // no periodic polyline retracing itself
    const NurbsCurve curve = testing::random_curve(degree, options, trial % 3 != 0, generator);
    const CurveProjector projector(curve);
    const double start = curve.knots().domain_start();
    const double length = curve.knots().domain_end() - start;
    for (int k = 0; k < 10; ++k) {
      const double u = start + length * testing::random_real(generator, 0.0, 1.0);
      const double found = projector.invert(curve.point(u), 1e-9);
      double error = std::abs(found - u) / length;
      if (curve.is_periodic()) {
        error = std::min(error, std::abs(error - 1.0));  // the seam: start and end are one point
      }
      worst = std::max(worst, error);
      // |du| ~ round-off of the point (1e-16) over the speed |C'| (>~ 1e-3 here).
      EXPECT_LT(error, 1e-12) << "trial " << trial << " u " << u;
    }
  }
  std::cout << "[ measured ] worst relative parameter error " << worst << "\n";
}

TEST(CurveProjector, FindsEndsAndKinksExactly) {
  // A clamped cubic with a C^0 knot (multiplicity 3) at 0.5 making a corner at (1, 1, 0).
  Eigen::MatrixX3d points(7, 3);
  points << 0, 0, 0, 0.3, 0.3, 0, 0.6, 0.6, 0, 1, 1, 0, 1.4, 0.6, 0, 1.7, 0.3, 0, 2, 0, 0;
  const NurbsCurve curve(KnotVector(3, {0, 0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1, 1}), points);
  const CurveProjector projector(curve);
  // Beyond the corner, inside the right angle's exterior: the corner is nearest.
  const CurveProjection corner = projector.closest_point(Eigen::Vector3d(1.0, 1.5, 0.2));
  EXPECT_EQ(corner.parameter, 0.5);
  EXPECT_NEAR(corner.distance, std::hypot(0.5, 0.2), 1e-15);  // the control point (1, 1, 0)
  // Behind the ends.
  EXPECT_EQ(projector.closest_point(Eigen::Vector3d(-1.0, -0.5, 0.0)).parameter, 0.0);
  EXPECT_EQ(projector.closest_point(Eigen::Vector3d(3.0, -0.5, 0.0)).parameter, 1.0);
}

TEST(CurveProjector, TiesGoToTheSmallestParameter) {
  // Every point of a circle is as near to its centre: the open circle answers its start, the
  // periodic one its period start.
  for (const NurbsCurve& circle : {full_circle(2.0), periodic_circle(2.0)}) {
    const CurveProjection centre = CurveProjector(circle).closest_point(Eigen::Vector3d::Zero());
    EXPECT_EQ(centre.parameter, 0.0);
    EXPECT_NEAR(centre.distance, 2.0, 1e-15);  // the rational circle's radius, to an ulp
  }
  // A symmetric arch; a query high on its axis has two mirror-image nearest points.
  Eigen::MatrixX3d points(5, 3);
  points << -2, 0, 0, -1, 2, 0, 0, -1, 0, 1, 2, 0, 2, 0, 0;
  const NurbsCurve arch(KnotVector::clamped_uniform(3, 5), points);
  const CurveProjection left = CurveProjector(arch).closest_point(Eigen::Vector3d(0, 3, 0));
  EXPECT_LT(left.parameter, 0.5);
  // Its mirror image u -> 1 - u is as near (to round-off).
  EXPECT_NEAR((arch.point(1.0 - left.parameter) - Eigen::Vector3d(0, 3, 0)).norm(), left.distance,
              1e-14);
  EXPECT_GT(std::abs(left.parameter - 0.5), 0.05);  // a real pair, not the apex
}

TEST(CurveProjector, WithinABoundReportsOnlyNearerPoints) {
  const NurbsCurve circle = full_circle(1.0);
  const CurveProjector projector(circle);
  const Eigen::Vector3d query(3.0, 0.0, 0.0);
  EXPECT_FALSE(projector.closest_point_within(query, 1.9).has_value());
  const std::optional<CurveProjection> found = projector.closest_point_within(query, 2.1);
  ASSERT_TRUE(found.has_value());
  EXPECT_NEAR(found->distance, 2.0, 1e-15);  // the rational circle, to an ulp
  EXPECT_EQ(found->parameter, projector.closest_point(query).parameter);
}

TEST(CurveProjector, BadQueriesThrowErrorNamingTheValue) {
  const CurveProjector projector(full_circle(1.0));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(testing::error_message([&] { projector.closest_point(Eigen::Vector3d(nan, 0, 0)); }),
              HasSubstr("not finite"));
  EXPECT_THAT(testing::error_message([&] { projector.invert(Eigen::Vector3d(0, 0, 0.5), 1e-9); }),
              HasSubstr("is 1.118033988749895 from the curve"));
}

}  // namespace
}  // namespace dnurbs
