#include "dnurbs/nurbs/knot_removal.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
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
#include "dnurbs/nurbs/knot_insertion.h"
#include "dnurbs/nurbs/periodic_window.h"
#include "dnurbs/nurbs/primitive_shapes.h"

namespace dnurbs {
namespace {

using testing::error_message;
using testing::max_deviation;
using testing::random_control_points;
using testing::random_open_curve;
using testing::random_periodic_curve;

using ::testing::HasSubstr;

// Insertion then removal recomputes each control point from a few convex combinations and their
// inverses (divisions by alpha and 1 - alpha, which stay >= ~0.05 for these knots): the points
// come back within a few hundred ulps of values of size ~1, well inside 1e-12.
constexpr double kRoundOff = 1e-12;
// Tolerance for removing a knot that was just inserted: the two estimates A5.8 compares differ
// only by round-off (~1e-15), so any tolerance far above that and far below the shape size works.
constexpr double kExactRemoval = 1e-9;

NurbsSurface random_surface(int degree_u, int degree_v, unsigned seed, bool rational) {
  std::mt19937 generator(seed);
  KnotVector knots_u = KnotVector::clamped_from_breakpoints(degree_u, {0.0, 0.35, 0.6, 1.0});
  KnotVector knots_v = KnotVector::clamped_from_breakpoints(degree_v, {-1.0, -0.2, 0.5, 1.0});
  Eigen::MatrixX3d points;
  Eigen::VectorXd weights;
  random_control_points(knots_u.control_point_count() * knots_v.control_point_count(), generator,
                        rational, points, weights);
  return {std::move(knots_u), std::move(knots_v), std::move(points), std::move(weights)};
}

double max_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

TEST(KnotRemoval, UndoesInsertionOfCurves) {
  for (const int degree : {2, 3, 5}) {
    for (const bool rational : {false, true}) {
      const NurbsCurve curve = random_open_curve(degree, 101U + degree, rational);
      // A new knot, the double knot, a single knot and knots 0.05 from the ends, each inserted
      // up to the degree.
      for (const double u : {0.25, 0.4, 1.3, -0.45, 1.95}) {
        const int existing = curve.knots().multiplicity(u);
        for (int times = 1; existing + times <= degree; ++times) {
          const NurbsCurve refined = insert_knot(curve, u, times);
          const CurveKnotRemoval removal = remove_knot(refined, u, times, kExactRemoval);
          ASSERT_TRUE(removal.succeeded) << "degree " << degree << " u " << u << " x" << times;
          EXPECT_EQ(removal.removed_count, times);
          EXPECT_EQ(removal.curve.knots(), curve.knots());
          EXPECT_LT(max_difference(removal.curve.control_points(), curve.control_points()),
                    kRoundOff);
          EXPECT_LT(max_difference(removal.curve.weights(), curve.weights()), kRoundOff);
        }
      }
    }
  }
}

TEST(KnotRemoval, NearAnEndUndoesInsertionUpToItsConditioning) {
  // 1e-3 from a clamped end, A5.8 divides by alpha_i = (u - t_i) / (t_{i+p+1} - t_i) ~ 4e-4 in
  // the recursion from that end, so the round-off of ~1e-16 grows by ~1e3 per removal: 1e-9
  // bounds one or two removals with a wide margin. (Removing p copies 1e-3 from an end, or one
  // copy 1e-9 from it, grows the round-off beyond a 1e-9 removal tolerance and the removal is
  // refused: that is the conditioning of A5.8, not a loss of exactness of the curve.)
  constexpr double kConditionedRoundOff = 1e-9;
  for (const int degree : {3, 5}) {
    const NurbsCurve curve = random_open_curve(degree, 171U + degree, true);
    for (const double u : {-0.499, 1.999}) {
      for (const int times : {1, 2}) {
        const NurbsCurve refined = insert_knot(curve, u, times);
        const CurveKnotRemoval removal = remove_knot(refined, u, times, kExactRemoval);
        ASSERT_TRUE(removal.succeeded) << "degree " << degree << " u " << u << " x" << times;
        EXPECT_EQ(removal.curve.knots(), curve.knots());
        EXPECT_LT(max_difference(removal.curve.control_points(), curve.control_points()),
                  kConditionedRoundOff);
        EXPECT_LT(max_difference(removal.curve.weights(), curve.weights()), kConditionedRoundOff);
      }
    }
  }
}

TEST(KnotRemoval, UndoesInsertionOnRationalCircle) {
  const NurbsCurve circle = full_circle(1.5);
  for (const double u : {0.1, 0.6}) {
    for (const int times : {1, 2}) {
      const CurveKnotRemoval removal =
          remove_knot(insert_knot(circle, u, times), u, times, kExactRemoval);
      ASSERT_TRUE(removal.succeeded);
      EXPECT_EQ(removal.curve.knots(), circle.knots());
      EXPECT_LT(max_difference(removal.curve.control_points(), circle.control_points()), kRoundOff);
      EXPECT_LT(max_difference(removal.curve.weights(), circle.weights()), kRoundOff);
    }
  }
}

TEST(KnotRemoval, EssentialKnotReportsFailureAndKeepsCurve) {
  // A random cubic is not C^3 at its knots, and the circle's double knots carry its corners:
  // removing them would move the curve by ~0.1, far above the tolerance.
  const NurbsCurve cubic = random_open_curve(3, 111U, true);
  const NurbsCurve circle = full_circle(1.0);
  for (const auto& [curve, u] : {std::pair{cubic, 1.3}, std::pair{cubic, 0.4},
                                 std::pair{circle, 0.25}, std::pair{circle, 0.5}}) {
    const CurveKnotRemoval removal = remove_knot(curve, u, 1, 1e-6);
    EXPECT_FALSE(removal.succeeded) << "u " << u;
    EXPECT_EQ(removal.removed_count, 0);
    EXPECT_EQ(removal.curve.knots(), curve.knots());
    EXPECT_EQ(removal.curve.control_points(), curve.control_points());
    EXPECT_EQ(removal.curve.weights(), curve.weights());
  }
}

TEST(KnotRemoval, StopsAtTheFirstStepThatFails) {
  // 1.3 inserted once more: the inserted copy goes, the original one stays.
  const NurbsCurve curve = random_open_curve(3, 121U, true);
  const CurveKnotRemoval removal = remove_knot(insert_knot(curve, 1.3), 1.3, 2, kExactRemoval);
  EXPECT_FALSE(removal.succeeded);
  EXPECT_EQ(removal.removed_count, 1);
  EXPECT_EQ(removal.curve.knots(), curve.knots());
  EXPECT_LT(max_difference(removal.curve.control_points(), curve.control_points()), kRoundOff);
}

TEST(KnotRemoval, MovesTheCurveByAtMostTheTolerance) {
  std::mt19937 generator(131U);
  std::normal_distribution<double> noise(0.0, 1e-5);
  for (const bool rational : {false, true}) {
    // A removable knot made slightly non-removable by 1e-5 noise on the control points.
    const NurbsCurve refined = insert_knot(random_open_curve(3, 131U, rational), 0.9);
    Eigen::MatrixX3d points = refined.control_points();
    for (Eigen::Index i = 0; i < points.size(); ++i) {
      points.data()[i] += noise(generator);
    }
    const NurbsCurve noisy(refined.knots(), points, refined.weights());
    // The bound A5.8 checks (P&T eq. 5.30) guarantees a deviation below the tolerance.
    const double tolerance = 1e-3;
    const CurveKnotRemoval removal = remove_knot(noisy, 0.9, 1, tolerance);
    ASSERT_TRUE(removal.succeeded) << "rational " << rational;
    const double deviation = max_deviation(noisy, removal.curve);
    EXPECT_GT(deviation, 0.0);
    EXPECT_LE(deviation, tolerance) << "rational " << rational;
    // A tolerance below the noise refuses.
    EXPECT_FALSE(remove_knot(noisy, 0.9, 1, 1e-9).succeeded);
  }
}

TEST(KnotRemoval, InvalidInputThrowsErrorNamingTheValue) {
  const NurbsCurve curve = random_open_curve(3, 141U, false);
  EXPECT_THAT(error_message([&] { remove_knot(curve, 0.3, 1, 1e-6); }), HasSubstr("knot 0.3"));
  EXPECT_THAT(error_message([&] { remove_knot(curve, 2.0, 1, 1e-6); }), HasSubstr("knot 2 "));
  EXPECT_THAT(error_message([&] { remove_knot(curve, -0.75, 1, 1e-6); }), HasSubstr("-0.75"));
  EXPECT_THAT(error_message([&] { remove_knot(curve, 0.4, 3, 1e-6); }),
              HasSubstr("removed 3 times"));
  EXPECT_THAT(error_message([&] { remove_knot(curve, 0.4, 0, 1e-6); }),
              HasSubstr("removed 0 times"));
  EXPECT_THAT(error_message([&] { remove_knot(curve, 0.4, 1, -0.5); }), HasSubstr("-0.5"));
  EXPECT_THAT(
      error_message([&] { remove_knot(curve, 0.4, 1, std::numeric_limits<double>::quiet_NaN()); }),
      HasSubstr("nan"));
  // Periodic curves: u must be a knot (after wrapping), and p + 1 control points must remain.
  const NurbsCurve periodic(KnotVector::periodic_uniform(3, 6), Eigen::MatrixX3d::Random(6, 3));
  EXPECT_THAT(error_message([&] { remove_knot(periodic, 0.55, 1, 1e-6); }), HasSubstr("knot 0.55"));
  EXPECT_THAT(error_message([&] { remove_knot(periodic, 1.5, 2, 1e-6); }),
              HasSubstr("knot 0.5 has multiplicity 1"));
  const NurbsCurve smallest(KnotVector::periodic_uniform(3, 4), Eigen::MatrixX3d::Random(4, 3));
  EXPECT_THAT(error_message([&] { remove_knot(smallest, 0.5, 1, 1e-6); }),
              HasSubstr("would leave 3 control points"));
}

TEST(SurfaceKnotRemoval, UndoesInsertionInUAndV) {
  for (const bool rational : {false, true}) {
    const NurbsSurface surface = random_surface(3, 4, 151U, rational);
    for (const auto& [direction, u] :
         {std::pair{SurfaceDirection::kU, 0.35}, std::pair{SurfaceDirection::kU, 0.8},
          std::pair{SurfaceDirection::kV, -0.2}, std::pair{SurfaceDirection::kV, 0.9}}) {
      const NurbsSurface refined = insert_knot(surface, direction, u, 2);
      const SurfaceKnotRemoval removal = remove_knot(refined, direction, u, 2, kExactRemoval);
      ASSERT_TRUE(removal.succeeded) << "rational " << rational << " u " << u;
      EXPECT_EQ(removal.removed_count, 2);
      EXPECT_EQ(removal.surface.knots_u(), surface.knots_u());
      EXPECT_EQ(removal.surface.knots_v(), surface.knots_v());
      EXPECT_LT(max_difference(removal.surface.control_points(), surface.control_points()),
                kRoundOff);
      EXPECT_LT(max_difference(removal.surface.weights(), surface.weights()), kRoundOff);
    }
  }
}

TEST(SurfaceKnotRemoval, FailsUnlessEveryRowSucceeds) {
  const NurbsSurface surface = random_surface(3, 3, 161U, true);
  const double u = 0.8;
  const NurbsSurface refined = insert_knot(surface, SurfaceDirection::kU, u);
  // Move one of the new control points (u index k - 1 of span k) of the curve with v index 2.
  const int k = surface.knots_u().find_span(u);
  Eigen::MatrixX3d points = refined.control_points();
  points.row(refined.control_point_index(k - 1, 2)) += Eigen::RowVector3d(0.0, 1e-3, 0.0);
  const NurbsSurface bumped(refined.knots_u(), refined.knots_v(), points, refined.weights());
  const SurfaceKnotRemoval removal = remove_knot(bumped, SurfaceDirection::kU, u, 1, 1e-6);
  EXPECT_FALSE(removal.succeeded);
  EXPECT_EQ(removal.removed_count, 0);
  EXPECT_EQ(removal.surface.knots_u(), bumped.knots_u());
  EXPECT_EQ(removal.surface.control_points(), bumped.control_points());
  EXPECT_EQ(removal.surface.weights(), bumped.weights());
  // Without the bump every row succeeds.
  EXPECT_TRUE(remove_knot(refined, SurfaceDirection::kU, u, 1, 1e-6).succeeded);
  EXPECT_THAT(error_message([&] { remove_knot(refined, SurfaceDirection::kV, 0.125, 1, 1e-6); }),
              HasSubstr("knot 0.125"));
}

// Property tests: insertion then removal, the shape compared with the original at 65 parameters
// and every knot, relative to the control net's size. Both steps are backward stable (convex
// combinations; Householder QR): the measured worst case over weights 0.05..20, degrees 1..7 and
// knots as close as 1e-4 is ~1e-15.
constexpr double kShapeTolerance = 1e-12;

TEST(KnotRemoval, UndoesInsertionOnThreeThousandRandomCurves) {
  std::mt19937 generator(3001U);
  double worst = 0.0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int degree = 1 + trial % 7;
    const testing::RandomKnotOptions options = testing::trial_options(trial, degree, true);
    const NurbsCurve curve =
        testing::random_curve(degree, options, (trial / 7) % 2 == 1, generator);
    const double u = testing::random_knot_to_insert(curve.knots(), generator);
    const double wrapped = curve.knots().wrap_to_period(u);
    // The ends of an open domain are not interior knots: only periodic seams are removed there.
    if (!curve.is_periodic() &&
        (wrapped == curve.knots().domain_start() || wrapped == curve.knots().domain_end())) {
      continue;
    }
    const int existing = curve.knots().multiplicity(wrapped);
    const int times = testing::random_int(generator, 1, degree - existing);
    const CurveKnotRemoval removal =
        remove_knot(insert_knot(curve, u, times), u, times, kExactRemoval);
    ASSERT_TRUE(removal.succeeded) << "trial " << trial << " u " << u;
    EXPECT_EQ(removal.curve.control_point_count(), curve.control_point_count());
    EXPECT_EQ(removal.curve.knots().multiplicity(wrapped), existing);
    EXPECT_EQ(removal.curve.knots().domain_start(), curve.knots().domain_start());
    const double deviation = testing::relative_deviation(curve, removal.curve);
    worst = std::max(worst, deviation);
    EXPECT_LT(deviation, kShapeTolerance) << "trial " << trial << " u " << u;
  }
  std::cout << "[ measured ] worst relative deviation " << worst << "\n";
}

TEST(KnotRemoval, PeriodicCurvesMoveByAtMostTheToleranceOrStay) {
  // Removing an existing knot of a random periodic curve with a coarse tolerance: either the
  // curve stays (and the removal is refused) or it moves by at most removed_count * tolerance.
  std::mt19937 generator(3002U);
  int succeeded = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const int degree = 1 + trial % 7;
    testing::RandomKnotOptions options = testing::trial_options(2 * trial, degree, false);
    const NurbsCurve curve = testing::random_curve(degree, options, trial % 3 == 0, generator);
    const KnotVector& knots = curve.knots();
    const double u = knots[testing::random_int(generator, degree, knots.basis_count() - 1)];
    const int times = testing::random_int(generator, 1, knots.multiplicity(u));
    if (curve.control_point_count() - times < degree + 1) {
      continue;
    }
    const double tolerance = 1.0;
    const CurveKnotRemoval removal = remove_knot(curve, u, times, tolerance);
    succeeded += removal.succeeded ? 1 : 0;
    // max_deviation compares at 401 parameters in model units; the bound is per removal step.
    EXPECT_LE(max_deviation(curve, removal.curve), removal.removed_count * tolerance)
        << "trial " << trial;
    if (removal.removed_count == 0) {
      EXPECT_EQ(removal.curve.control_points(), curve.control_points());
    }
  }
  std::cout << "[ measured ] " << succeeded << " of 1000 removals within the tolerance\n";
  EXPECT_GT(succeeded, 50);  // the tolerance is coarse enough that many removals happen
}

TEST(KnotRemoval, RemovingTheSeamsOnlyCopyMovesThePeriodStart) {
  // A periodic curve whose seam knot c is not needed: a random periodic curve with c inserted,
  // written over the period [c, c + T] (wrap_periodic). Removing c leaves the same curve with
  // the period starting at the next knot.
  std::mt19937 generator(3003U);
  for (int trial = 0; trial < 300; ++trial) {
    const int degree = 1 + trial % 7;
    testing::RandomKnotOptions options = testing::trial_options(0, degree, false);
    const NurbsCurve curve = testing::random_curve(degree, options, trial % 2 == 0, generator);
    const KnotVector& knots = curve.knots();
    const double start = knots.domain_start();
    const double period = knots.domain_end() - start;
    const double seam = start + period * testing::random_real(generator, 0.1, 0.9);
    if (knots.multiplicity(seam) > 0) {
      continue;
    }
    const NurbsCurve refined = insert_knot(curve, seam);
    std::vector<double> rotated = {seam};
    for (int i = 0; i < refined.control_point_count(); ++i) {
      const double knot = refined.knots().extended_knot(refined.knots().find_span(seam) + 1 + i);
      rotated.push_back(knot);
    }
    rotated.back() = seam + period;
    const KnotVector seam_knots = KnotVector::periodic(degree, rotated);
    ControlRows rows = control_rows(refined);
    const int n = refined.control_point_count();
    rows.rows = wrap_periodic(unwrap_periodic(refined.knots(), rows.rows, -2 * n, 5 * n + degree),
                              seam_knots);
    const NurbsCurve at_seam = curve_from_control_rows(seam_knots, rows);
    ASSERT_LT(testing::relative_deviation(curve, at_seam), kShapeTolerance);
    ASSERT_EQ(at_seam.knots().multiplicity(seam), 1);
    const CurveKnotRemoval removal = remove_knot(at_seam, seam, 1, kExactRemoval);
    ASSERT_TRUE(removal.succeeded) << "trial " << trial;
    EXPECT_EQ(removal.curve.control_point_count(), n - 1);
    EXPECT_EQ(removal.curve.knots().domain_start(), rotated[1]);
    EXPECT_LT(testing::relative_deviation(curve, removal.curve), kShapeTolerance)
        << "trial " << trial;
  }
}

TEST(SurfaceKnotRemoval, UndoesInsertionOnTwoThousandRandomSurfaces) {
  std::mt19937 generator(3004U);
  double worst = 0.0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int degree_u = 1 + trial % 7;
    const int degree_v = 1 + (trial / 7) % 4;
    const NurbsSurface surface = testing::random_surface(
        degree_u, degree_v, testing::trial_options(trial, degree_u, true),
        testing::trial_options(trial / 2, degree_v, true), trial % 3 != 0, generator);
    const SurfaceDirection direction = trial % 5 < 3 ? SurfaceDirection::kU : SurfaceDirection::kV;
    const KnotVector& knots =
        direction == SurfaceDirection::kU ? surface.knots_u() : surface.knots_v();
    const double u = testing::random_knot_to_insert(knots, generator);
    const double wrapped = knots.wrap_to_period(u);
    if (!knots.is_periodic() &&
        (wrapped == knots.domain_start() || wrapped == knots.domain_end())) {
      continue;
    }
    const int times =
        testing::random_int(generator, 1, knots.degree() - knots.multiplicity(wrapped));
    const SurfaceKnotRemoval removal =
        remove_knot(insert_knot(surface, direction, u, times), direction, u, times, kExactRemoval);
    ASSERT_TRUE(removal.succeeded) << "trial " << trial;
    const double deviation = testing::relative_deviation(surface, removal.surface);
    worst = std::max(worst, deviation);
    EXPECT_LT(deviation, kShapeTolerance) << "trial " << trial;
  }
  std::cout << "[ measured ] worst relative deviation " << worst << "\n";
}

TEST(KnotRemoval, PeriodicKnotsComeOutAgainNotRefused) {
  // Regression: removal refused every periodic shape ("supports open shapes"). A knot inserted
  // into the periodic circle is removed again and the circle stays a circle.
  const NurbsCurve circle = periodic_circle(1.5);
  const CurveKnotRemoval removal = remove_knot(insert_knot(circle, 0.4), 0.4, 1, kExactRemoval);
  ASSERT_TRUE(removal.succeeded);
  EXPECT_EQ(removal.curve.control_point_count(), circle.control_point_count());
  for (int i = 0; i <= 64; ++i) {
    // The rational circle evaluates to radius 1.5 to a few ulps.
    EXPECT_NEAR(removal.curve.point(i / 64.0).norm(), 1.5, 1e-14);
  }
  // The circle's own double knots carry its shape: removing one moves it by ~0.1.
  EXPECT_FALSE(remove_knot(circle, 0.25, 1, 1e-6).succeeded);
  // The seam, given as the period end 2.3 (the period start 0.3), inserted and removed.
  const NurbsCurve curve = random_periodic_curve(3, 251U, true);
  const CurveKnotRemoval seam = remove_knot(insert_knot(curve, 2.3), 2.3, 1, kExactRemoval);
  ASSERT_TRUE(seam.succeeded);
  EXPECT_EQ(seam.curve.knots().domain_start(), 0.3);
  EXPECT_EQ(seam.curve.knots().multiplicity(0.3), 1);
  EXPECT_LT(max_deviation(curve, seam.curve), kRoundOff);
}

}  // namespace
}  // namespace dnurbs
