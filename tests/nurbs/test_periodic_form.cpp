// The open form of a periodic shape (what STEP, IGES and OBJ carry) is the same shape, and
// reading it back gives the periodic shape again; shapes that only look closed stay open.
#include "dnurbs/nurbs/periodic_form.h"

#include <random>

#include <gtest/gtest.h>

#include "tests/nurbs/random_shapes.h"

namespace dnurbs {
namespace {

using testing::random_curve;
using testing::random_surface;
using testing::test_parameters;
using testing::trial_options;

TEST(PeriodicForm, CurvesOpenAndCloseAgainExactly) {
  std::mt19937 generator(41);
  for (int trial = 0; trial < 80; ++trial) {
    const int degree = 1 + trial % 6;
    testing::RandomKnotOptions options = trial_options(trial, degree, true);
    options.extra_control_points = trial % 3;
    const NurbsCurve curve = random_curve(degree, options, trial % 3 == 0, generator);
    const NurbsCurve open = open_form(curve);
    EXPECT_FALSE(open.is_periodic());
    EXPECT_EQ(open.control_point_count(),
              curve.control_point_count() + (curve.is_periodic() ? degree : 0));
    EXPECT_EQ(open.knots().domain_start(), curve.knots().domain_start());
    EXPECT_EQ(open.knots().domain_end(), curve.knots().domain_end());
    double error = 0.0;
    for (const double u : test_parameters(curve.knots(), 24)) {
      error = std::max(error, (open.point(u) - curve.point(u)).norm());
    }
    // The same basis functions over the same knots: round-off of the wrapped sums only.
    EXPECT_LT(error, 1e-14) << "trial " << trial;
    const NurbsCurve back = periodic_form(open);
    EXPECT_EQ(back.is_periodic(), curve.is_periodic()) << "trial " << trial;
    if (curve.is_periodic()) {
      // The period list comes back as the open knots t_p..t_{p+n}.
      EXPECT_EQ(back.knots().period_knots(), curve.knots().period_knots()) << "trial " << trial;
    }
    EXPECT_EQ(back.control_points(), curve.control_points()) << "trial " << trial;
    EXPECT_EQ(back.weights(), curve.weights()) << "trial " << trial;
  }
}

TEST(PeriodicForm, SurfacesOpenAndCloseAgainExactly) {
  std::mt19937 generator(42);
  for (int trial = 0; trial < 40; ++trial) {
    const int degree_u = 1 + trial % 4;
    const int degree_v = 1 + (trial + 1) % 3;
    testing::RandomKnotOptions options_u = trial_options(trial, degree_u, true);
    testing::RandomKnotOptions options_v = trial_options(trial / 2 + 1, degree_v, true);
    options_u.extra_control_points = 1;
    options_v.extra_control_points = 2;
    const NurbsSurface surface =
        random_surface(degree_u, degree_v, options_u, options_v, trial % 2 == 0, generator);
    const NurbsSurface open = open_form(surface);
    EXPECT_FALSE(open.knots_u().is_periodic() || open.knots_v().is_periodic());
    double error = 0.0;
    for (const double u : test_parameters(surface.knots_u(), 6)) {
      for (const double v : test_parameters(surface.knots_v(), 6)) {
        error = std::max(error, (open.point(u, v) - surface.point(u, v)).norm());
      }
    }
    // Round-off of the rational sums, amplified by weight ratios up to 400.
    EXPECT_LT(error, 1e-13) << "trial " << trial;
    const NurbsSurface back = periodic_form(open);
    EXPECT_EQ(back.knots_u().is_periodic(), surface.knots_u().is_periodic()) << trial;
    EXPECT_EQ(back.knots_v().is_periodic(), surface.knots_v().is_periodic()) << trial;
    EXPECT_EQ(back.control_points(), surface.control_points()) << "trial " << trial;
    EXPECT_EQ(back.weights(), surface.weights()) << "trial " << trial;
  }
}

TEST(PeriodicForm, ClosedButClampedOrUnevenCurvesStayOpen) {
  // A clamped closed cubic (its ends meet): clamped knots are no periodic extension.
  Eigen::MatrixX3d points(7, 3);
  points << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0, -1, 0, 0, 0, 0, 0;
  const NurbsCurve clamped(KnotVector::clamped_uniform(3, 7), points);
  EXPECT_FALSE(periodic_form(clamped).is_periodic());
  // Unclamped uniform knots whose last 3 points do not repeat the first 3.
  const NurbsCurve unclamped(KnotVector::uniform(3, 7), points);
  EXPECT_FALSE(periodic_form(unclamped).is_periodic());
  // Repeated points over knots whose spacing is not periodic.
  Eigen::MatrixX3d wrapped = points;
  wrapped.bottomRows(3) = points.topRows(3);
  std::vector<double> knots = KnotVector::uniform(3, 7).knots();
  knots[5] += 0.5;
  EXPECT_FALSE(periodic_form(NurbsCurve(KnotVector(3, knots), wrapped)).is_periodic());
  // The same points over uniform knots: periodic with 4 distinct points.
  const NurbsCurve closed = periodic_form(NurbsCurve(KnotVector::uniform(3, 7), wrapped));
  ASSERT_TRUE(closed.is_periodic());
  EXPECT_EQ(closed.control_point_count(), 4);
}

}  // namespace
}  // namespace dnurbs
