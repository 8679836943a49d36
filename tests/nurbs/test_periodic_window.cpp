#include "dnurbs/nurbs/periodic_window.h"

#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/common/error_message.h"
#include "tests/nurbs/random_shapes.h"

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

// Evaluations of the same spline in two representations (the window repeats the periodic knots
// and control points exactly): de Boor's algorithm on points of size ~1 agrees to a few ulps.
constexpr double kRoundOff = 1e-13;

TEST(PeriodicWindow, UnwrappedWindowIsThePeriodicCurveOverThreePeriods) {
  std::mt19937 generator(4001U);
  for (int trial = 0; trial < 500; ++trial) {
    const int degree = 1 + trial % 7;
    const testing::RandomKnotOptions options = testing::trial_options(2 * trial, degree, false);
    const NurbsCurve curve = testing::random_curve(degree, options, trial % 2 == 0, generator);
    const int n = curve.control_point_count();
    const ControlRows rows = control_rows(curve);
    const KnotsAndRows window = unwrap_periodic(curve.knots(), rows.rows, -n, 3 * n + degree);
    const double period = curve.knots().domain_end() - curve.knots().domain_start();
    EXPECT_EQ(window.knots.domain_start(), curve.knots().domain_start() - period);
    EXPECT_EQ(window.knots.domain_end(), curve.knots().domain_end() + period);
    ControlRows window_rows = rows;
    window_rows.rows = window.rows;
    const NurbsCurve open = curve_from_control_rows(window.knots, window_rows);
    const NurbsCurve clamped_curve = [&] {
      const KnotsAndRows clamped = clamp_window(window);
      window_rows.rows = clamped.rows;
      return curve_from_control_rows(clamped.knots, window_rows);
    }();
    EXPECT_EQ(clamped_curve.knots().multiplicity(open.knots().domain_start()), degree + 1);
    EXPECT_EQ(clamped_curve.knots().multiplicity(open.knots().domain_end()), degree + 1);
    for (const double u : testing::test_parameters(open.knots(), 90)) {
      // The periodic curve wraps u into its period, which moves u by a few ulps of |u| <= 19
      // (~1e-14): that error times the speed |C'| comes on top of the evaluation's round-off.
      const double tolerance = kRoundOff * (1.0 + curve.derivatives(u, 1).row(1).norm());
      EXPECT_LT((open.point(u) - curve.point(u)).norm(), tolerance) << "trial " << trial;
      EXPECT_LT((clamped_curve.point(u) - curve.point(u)).norm(), tolerance) << "trial " << trial;
    }
  }
}

TEST(PeriodicWindow, WrappingTheUnwrappedWindowGivesTheControlPointsBack) {
  std::mt19937 generator(4002U);
  for (int trial = 0; trial < 500; ++trial) {
    const int degree = 1 + trial % 7;
    const testing::RandomKnotOptions options = testing::trial_options(2 * trial, degree, false);
    const NurbsCurve curve = testing::random_curve(degree, options, false, generator);
    const int n = curve.control_point_count();
    const Eigen::MatrixXd points = curve.control_points();
    // Exact: every coefficient is copied from the basis function with the same knots.
    EXPECT_EQ(
        wrap_periodic(unwrap_periodic(curve.knots(), points, -n, 3 * n + degree), curve.knots()),
        points);
  }
}

TEST(PeriodicWindow, BadInputThrowsErrorNamingTheValue) {
  const KnotVector periodic = KnotVector::periodic(3, {0.0, 0.2, 0.5, 0.6, 0.9, 1.0});
  const Eigen::MatrixXd points = Eigen::MatrixXd::Random(5, 3);
  EXPECT_THAT(testing::error_message([&] { unwrap_periodic(periodic, points, 0, 3); }),
              HasSubstr("at least 4 control points, got 3"));
  EXPECT_THAT(testing::error_message(
                  [&] { unwrap_periodic(KnotVector::clamped_uniform(3, 5), points, 0, 5); }),
              HasSubstr("periodic"));
  // A window of one period cannot give every periodic coefficient (those across the seam).
  EXPECT_THAT(testing::error_message(
                  [&] { wrap_periodic(unwrap_periodic(periodic, points, 0, 5), periodic); }),
              HasSubstr("has no match in the open window"));
}

}  // namespace
}  // namespace dnurbs
