#include "dnurbs/nurbs/degree_elevation.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/common/error_message.h"
#include "tests/nurbs/knot_operation_shapes.h"
#include "tests/nurbs/random_shapes.h"

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/primitive_shapes.h"

namespace dnurbs {
namespace {

using testing::error_message;
using testing::max_deviation;
using testing::random_control_points;
using testing::random_open_curve;
using testing::random_periodic_curve;

using ::testing::HasSubstr;

// Each new point is a mean of blossoms made of convex combinations of points of size ~1: a few
// ulps. The periodic path runs the same on a clamped window of three periods. 1e-12 leaves a
// wide margin.
constexpr double kRoundOff = 1e-12;

NurbsSurface random_surface(int degree_u, int degree_v, unsigned seed, bool rational,
                            bool periodic_u) {
  std::mt19937 generator(seed);
  KnotVector knots_u = periodic_u
                           ? KnotVector::periodic(degree_u, {0.0, 0.2, 0.3, 0.55, 0.6, 0.8, 1.0})
                           : KnotVector::clamped_from_breakpoints(degree_u, {0.0, 0.35, 0.6, 1.0});
  KnotVector knots_v = KnotVector::clamped_from_breakpoints(degree_v, {-1.0, -0.2, 0.5, 1.0});
  Eigen::MatrixX3d points;
  Eigen::VectorXd weights;
  random_control_points(knots_u.control_point_count() * knots_v.control_point_count(), generator,
                        rational, points, weights);
  return {std::move(knots_u), std::move(knots_v), std::move(points), std::move(weights)};
}

// Every distinct knot value of `before` appears degree_increase more times in `after`.
void expect_multiplicities_raised(const KnotVector& before, const KnotVector& after,
                                  int degree_increase) {
  for (const double knot : before.knots()) {
    if (knot >= before.domain_start() && knot <= before.domain_end()) {
      EXPECT_EQ(after.multiplicity(knot), before.multiplicity(knot) + degree_increase)
          << "knot " << knot;
    }
  }
}

TEST(DegreeElevation, LeavesRationalCircleUnchanged) {
  const NurbsCurve circle = full_circle(1.0);
  for (const int t : {1, 2, 3}) {
    const NurbsCurve elevated = elevate_degree(circle, t);
    EXPECT_EQ(elevated.degree(), 2 + t);
    expect_multiplicities_raised(circle.knots(), elevated.knots(), t);
    EXPECT_LT(max_deviation(circle, elevated), kRoundOff) << "t = " << t;
  }
}

TEST(DegreeElevation, LeavesRandomCurvesUnchanged) {
  for (const int degree : {2, 3, 5}) {
    for (const bool rational : {false, true}) {
      const NurbsCurve curve = random_open_curve(degree, 201U + degree, rational);
      for (const int t : {1, 2, 3}) {
        const NurbsCurve elevated = elevate_degree(curve, t);
        EXPECT_EQ(elevated.degree(), degree + t);
        EXPECT_EQ(elevated.is_rational(), rational);
        // n + t (number of spans + 1): 4 spans here.
        EXPECT_EQ(elevated.control_point_count(), curve.control_point_count() + t * 4);
        expect_multiplicities_raised(curve.knots(), elevated.knots(), t);
        EXPECT_LT(max_deviation(curve, elevated), kRoundOff)
            << "degree " << degree << " rational " << rational << " t " << t;
      }
    }
  }
}

TEST(DegreeElevation, QuadraticBezierGivesTheKnownCubicPoints) {
  // Q_0 = P_0, Q_1 = (P_0 + 2 P_1)/3, Q_2 = (2 P_1 + P_2)/3, Q_3 = P_2 (P&T eq. 5.36).
  Eigen::MatrixX3d points(3, 3);
  points << 0.0, 0.0, 0.0, 1.0, 2.0, 0.0, 3.0, 0.0, 1.0;
  const NurbsCurve bezier(KnotVector::clamped_uniform(2, 3), points);
  const NurbsCurve cubic = elevate_degree(bezier, 1);
  Eigen::MatrixX3d expected(4, 3);
  expected << points.row(0), (points.row(0) + 2.0 * points.row(1)) / 3.0,
      (2.0 * points.row(1) + points.row(2)) / 3.0, points.row(2);
  EXPECT_EQ(cubic.knots(), KnotVector::clamped_uniform(3, 4));
  EXPECT_LT((cubic.control_points() - expected).cwiseAbs().maxCoeff(), 1e-15);  // one rounding
}

TEST(DegreeElevation, LeavesPeriodicCurvesUnchanged) {
  for (const int degree : {2, 3, 5}) {
    for (const bool rational : {false, true}) {
      const NurbsCurve curve = random_periodic_curve(degree, 211U + degree, rational);
      for (const int t : {1, 2, 3}) {
        const NurbsCurve elevated = elevate_degree(curve, t);
        ASSERT_TRUE(elevated.is_periodic());
        EXPECT_EQ(elevated.degree(), degree + t);
        EXPECT_EQ(elevated.knots().domain_start(), curve.knots().domain_start());
        EXPECT_EQ(elevated.knots().domain_end(), curve.knots().domain_end());
        // 8 distinct knots per period.
        EXPECT_EQ(elevated.control_point_count(), curve.control_point_count() + 8 * t);
        expect_multiplicities_raised(curve.knots(), elevated.knots(), t);
        EXPECT_LT(max_deviation(curve, elevated), kRoundOff)
            << "degree " << degree << " rational " << rational << " t " << t;
      }
    }
  }
}

TEST(DegreeElevation, LeavesSurfacesUnchangedInUAndV) {
  for (const bool rational : {false, true}) {
    for (const bool periodic_u : {false, true}) {
      const NurbsSurface surface = random_surface(3, 2, 221U, rational, periodic_u);
      for (const int t : {1, 2, 3}) {
        const NurbsSurface in_u = elevate_degree(surface, SurfaceDirection::kU, t);
        EXPECT_EQ(in_u.degree_u(), 3 + t);
        EXPECT_EQ(in_u.knots_v(), surface.knots_v());
        EXPECT_LT(max_deviation(surface, in_u), kRoundOff)
            << "rational " << rational << " periodic " << periodic_u << " t " << t;
        const NurbsSurface in_v = elevate_degree(surface, SurfaceDirection::kV, t);
        EXPECT_EQ(in_v.degree_v(), 2 + t);
        EXPECT_EQ(in_v.knots_u(), surface.knots_u());
        EXPECT_LT(max_deviation(surface, in_v), kRoundOff)
            << "rational " << rational << " periodic " << periodic_u << " t " << t;
      }
    }
  }
  const NurbsSurface sphere_surface = sphere(1.0);
  const NurbsSurface both = elevate_degree(elevate_degree(sphere_surface, SurfaceDirection::kU, 1),
                                           SurfaceDirection::kV, 2);
  EXPECT_LT(max_deviation(sphere_surface, both), kRoundOff);
}

TEST(DegreeElevation, InvalidInputThrowsErrorNamingTheValue) {
  const NurbsCurve curve = random_open_curve(3, 231U, false);
  EXPECT_THAT(error_message([&] { elevate_degree(curve, -1); }), HasSubstr("-1"));
  EXPECT_THAT(error_message([&] { elevate_degree(curve, kMaxDegree); }),
              HasSubstr("degree " + std::to_string(kMaxDegree + 3)));
  const NurbsCurve unclamped(KnotVector::uniform(3, 6), Eigen::MatrixX3d::Random(6, 3));
  EXPECT_THAT(error_message([&] { elevate_degree(unclamped, 1); }), HasSubstr("clamped"));
  const NurbsSurface surface = random_surface(3, 2, 232U, true, false);
  EXPECT_THAT(error_message([&] { elevate_degree(surface, SurfaceDirection::kV, 14); }),
              HasSubstr("degree 16"));
  // Elevation by 0 is the identity.
  EXPECT_EQ(elevate_degree(curve, 0).control_points(), curve.control_points());
}

// Property tests: the shape before and after, compared at 65 parameters and every knot,
// relative to the control net's size. Every elevated point is a mean of blossoms made of convex
// combinations (homogeneous, weights 0.05..20): the measured worst case over degrees up to 10
// is ~2e-15, so 1e-12 leaves a wide margin (A5.9 reached 1e-9 here on nearly coincident knots).
constexpr double kShapeTolerance = 1e-12;

TEST(DegreeElevation, PeriodicSeamCopiesAtTheEndOfThePeriodList) {
  // Regression: with seam copies at the end of the list, the collocation it replaced gave the
  // seam degree_increase copies too many (and a wrong curve); with round-off there it threw.
  const std::vector<double> period = {0.2, 0.5, 0.9, 1.4, 1.7, 2.2, 2.2, 2.2};
  std::mt19937 generator(77U);
  Eigen::MatrixX3d points;
  Eigen::VectorXd weights;
  testing::random_net(7, true, generator, points, weights);
  const NurbsCurve curve(KnotVector::periodic(3, period), points, weights);
  ASSERT_EQ(curve.knots().multiplicity(0.2), 3);
  const NurbsCurve elevated = elevate_degree(curve, 2);
  EXPECT_EQ(elevated.knots().multiplicity(0.2), 5);
  EXPECT_EQ(elevated.control_point_count(), 7 + 2 * 5);  // 5 distinct knots per period
  EXPECT_LT(testing::relative_deviation(curve, elevated), kShapeTolerance);
}

TEST(DegreeElevation, KeepsThreeThousandRandomCurves) {
  std::mt19937 generator(2001U);
  double worst = 0.0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int degree = 1 + trial % 7;
    const testing::RandomKnotOptions options = testing::trial_options(trial, degree, false);
    const NurbsCurve curve =
        testing::random_curve(degree, options, (trial / 7) % 2 == 1, generator);
    const int t = 1 + (trial / 14) % 3;
    const NurbsCurve elevated = elevate_degree(curve, t);
    ASSERT_EQ(elevated.degree(), degree + t);
    ASSERT_EQ(elevated.is_periodic(), curve.is_periodic());
    expect_multiplicities_raised(curve.knots(), elevated.knots(), t);
    const double deviation = testing::relative_deviation(curve, elevated);
    worst = std::max(worst, deviation);
    EXPECT_LT(deviation, kShapeTolerance) << "trial " << trial;
  }
  std::cout << "[ measured ] worst relative deviation " << worst << "\n";
}

TEST(DegreeElevation, KeepsTwoThousandRandomSurfacesInEitherDirection) {
  std::mt19937 generator(2002U);
  double worst = 0.0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int degree_u = 1 + trial % 7;
    const int degree_v = 1 + (trial / 7) % 4;
    const NurbsSurface surface = testing::random_surface(
        degree_u, degree_v, testing::trial_options(trial, degree_u, false),
        testing::trial_options(trial / 2, degree_v, false), trial % 3 != 0, generator);
    const SurfaceDirection direction = trial % 5 < 3 ? SurfaceDirection::kU : SurfaceDirection::kV;
    const int t = 1 + trial % 2;
    const NurbsSurface elevated = elevate_degree(surface, direction, t);
    const double deviation = testing::relative_deviation(surface, elevated);
    worst = std::max(worst, deviation);
    EXPECT_LT(deviation, kShapeTolerance) << "trial " << trial;
  }
  std::cout << "[ measured ] worst relative deviation " << worst << "\n";
}

}  // namespace
}  // namespace dnurbs
