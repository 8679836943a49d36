#include "dnurbs/nurbs/knot_insertion.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <string>
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

// Insertion is a chain of convex combinations of control points of size ~1 (and a division by
// the weight for rational shapes): the points it moves are off by a few ulps, so 1e-12 leaves
// a margin of ~100x over the measured round-off.
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

TEST(KnotInsertion, LeavesRationalCircleUnchanged) {
  const NurbsCurve circle = full_circle(1.0);
  for (const double u : {0.1, 0.3, 0.6, 0.999}) {  // 0.25, 0.5, 0.75 are already double
    const NurbsCurve refined = insert_knot(circle, u);
    EXPECT_EQ(refined.control_point_count(), circle.control_point_count() + 1);
    EXPECT_EQ(refined.knots().multiplicity(u), circle.knots().multiplicity(u) + 1);
    EXPECT_LT(max_deviation(circle, refined), kRoundOff) << "u = " << u;
  }
  // Twice where the multiplicity is 0 gives a double knot.
  EXPECT_LT(max_deviation(circle, insert_knot(circle, 0.4, 2)), kRoundOff);
}

TEST(KnotInsertion, LeavesRandomCubicAndQuinticUnchanged) {
  for (const int degree : {3, 5}) {
    for (const bool rational : {false, true}) {
      const NurbsCurve curve = random_open_curve(degree, 11U + degree, rational);
      for (const double u : {-0.3, 0.25, 1.0, 1.7}) {
        for (int times = 1; times <= degree; ++times) {
          const NurbsCurve refined = insert_knot(curve, u, times);
          EXPECT_EQ(refined.knots().multiplicity(u), times);
          EXPECT_EQ(refined.control_point_count(), curve.control_point_count() + times);
          EXPECT_EQ(refined.is_rational(), rational);
          EXPECT_LT(max_deviation(curve, refined), kRoundOff)
              << "degree " << degree << " rational " << rational << " u " << u << " x" << times;
        }
      }
    }
  }
}

TEST(KnotInsertion, RaisesAnExistingKnotUpToTheDegree) {
  for (const int degree : {3, 5}) {
    const NurbsCurve curve = random_open_curve(degree, 5U, true);
    // 0.4 is a double knot, 1.3 a single one.
    for (const double u : {0.4, 1.3}) {
      const int existing = curve.knots().multiplicity(u);
      const NurbsCurve refined = insert_knot(curve, u, degree - existing);
      EXPECT_EQ(refined.knots().multiplicity(u), degree);
      EXPECT_LT(max_deviation(curve, refined), kRoundOff);
    }
  }
}

TEST(KnotInsertion, NearTheEndsLeavesCurveUnchanged) {
  for (const int degree : {2, 3, 5}) {
    const NurbsCurve curve = random_open_curve(degree, 21U, true);
    for (const double u : {-0.5 + 1e-9, -0.5 + 1e-3, 2.0 - 1e-3, 2.0 - 1e-9}) {
      const NurbsCurve refined = insert_knot(curve, u, degree);
      EXPECT_LT(max_deviation(curve, refined), kRoundOff) << "degree " << degree << " u " << u;
      EXPECT_EQ(refined.point(-0.5), curve.point(-0.5));  // clamped ends are untouched
      EXPECT_EQ(refined.point(2.0), curve.point(2.0));
    }
  }
}

TEST(KnotInsertion, AtTheEndOfAnUnclampedCurveLeavesItUnchanged) {
  // Uniform (unclamped) knots: the domain ends are single knots that may be raised to p.
  std::mt19937 generator(3U);
  Eigen::MatrixX3d points;
  Eigen::VectorXd weights;
  random_control_points(8, generator, true, points, weights);
  const NurbsCurve curve(KnotVector::uniform(3, 8), points, weights);
  for (const double u : {3.0, 8.0}) {
    EXPECT_LT(max_deviation(curve, insert_knot(curve, u, 2)), kRoundOff) << "u = " << u;
    EXPECT_LT(max_deviation(curve, refine_knots(curve, {u, u})), kRoundOff) << "u = " << u;
  }
}

TEST(KnotInsertion, LeavesPeriodicCurvesUnchanged) {
  for (const int degree : {2, 3, 5}) {
    for (const bool rational : {false, true}) {
      const NurbsCurve curve = random_periodic_curve(degree, 31U + degree, rational);
      // Inside a span, at the period start, at an existing (double) knot, near both ends, and
      // beyond the period (wraps to 0.55).
      for (const double u : {0.65, 0.3, 1.1, 0.3 + 1e-9, 2.3 - 1e-9, 2.55}) {
        const int existing = curve.knots().multiplicity(curve.knots().to_domain(u));
        for (int times = 1; existing + times <= degree; ++times) {
          const NurbsCurve refined = insert_knot(curve, u, times);
          ASSERT_TRUE(refined.is_periodic());
          EXPECT_EQ(refined.control_point_count(), curve.control_point_count() + times);
          EXPECT_EQ(refined.knots().domain_start(), curve.knots().domain_start());
          EXPECT_EQ(refined.knots().domain_end(), curve.knots().domain_end());
          // The period knots with u inserted, as KnotVector::periodic builds them.
          std::vector<double> period = curve.knots().period_knots();
          const double wrapped = curve.knots().to_domain(u);
          period.insert(std::upper_bound(period.begin(), period.end(), wrapped),
                        static_cast<size_t>(times), wrapped);
          EXPECT_EQ(refined.knots(), KnotVector::periodic(degree, period));
          EXPECT_LT(max_deviation(curve, refined), kRoundOff)
              << "degree " << degree << " rational " << rational << " u " << u << " x" << times;
        }
      }
    }
  }
}

TEST(KnotInsertion, PeriodicInsertionReplacesPMinusOneCyclicPoints) {
  // One insertion into span k replaces P_{k-p+1}..P_{k-1} (mod n) by p new points; the other
  // n - p + 1 points keep their cyclic order, starting at P_k.
  const int degree = 3;
  const NurbsCurve curve = random_periodic_curve(degree, 41U, true);
  const int n = curve.control_point_count();
  for (const double u : {0.35, 1.2, 2.2}) {
    const int k = curve.knots().find_span(u);
    const NurbsCurve refined = insert_knot(curve, u);
    // Position of the new knot is k + 1, so new cyclic points k+1.. are old points k..
    for (int i = 0; i <= n - degree; ++i) {
      const int old_index = (k + i) % n;
      const int new_index = (k + 1 + i) % (n + 1);
      EXPECT_LT(
          (refined.control_points().row(new_index) - curve.control_points().row(old_index)).norm(),
          kRoundOff)
          << "u " << u << " i " << i;
      EXPECT_NEAR(refined.weights()[new_index], curve.weights()[old_index], kRoundOff);
    }
  }
}

TEST(KnotInsertion, InvalidInputThrowsErrorNamingTheValue) {
  const NurbsCurve circle = full_circle(1.0);
  EXPECT_THAT(error_message([&] { insert_knot(circle, 1.5); }), HasSubstr("1.5"));
  EXPECT_THAT(error_message([&] { insert_knot(circle, -0.125); }), HasSubstr("-0.125"));
  EXPECT_THAT(error_message([&] { insert_knot(circle, std::nan("")); }), HasSubstr("nan"));
  EXPECT_THAT(error_message([&] { insert_knot(circle, 0.3, 0); }), HasSubstr("times = 0"));
  EXPECT_THAT(error_message([&] { insert_knot(circle, 0.3, -2); }), HasSubstr("times = -2"));
  // 0.25 is already a double knot of the quadratic circle.
  EXPECT_THAT(error_message([&] { insert_knot(circle, 0.25); }), HasSubstr("knot 0.25"));
  EXPECT_THAT(error_message([&] { insert_knot(circle, 0.375, 3); }), HasSubstr("knot 0.375"));
  // Clamped ends already have multiplicity p + 1.
  EXPECT_THAT(error_message([&] { insert_knot(circle, 1.0); }), HasSubstr("knot 1 "));
  const NurbsCurve periodic = random_periodic_curve(3, 1U, false);
  EXPECT_THAT(error_message([&] { insert_knot(periodic, 1.1, 2); }), HasSubstr("knot 1.1"));
}

TEST(KnotRefinement, LeavesCurvesUnchangedAndMatchesRepeatedInsertion) {
  const std::vector<double> new_knots = {-0.45, -0.45, 0.0, 0.1, 0.4, 0.41, 1.0, 1.3, 1.3, 1.99};
  for (const int degree : {3, 5}) {
    for (const bool rational : {false, true}) {
      const NurbsCurve curve = random_open_curve(degree, 51U + degree, rational);
      const NurbsCurve refined = refine_knots(curve, new_knots);
      EXPECT_LT(max_deviation(curve, refined), kRoundOff)
          << "degree " << degree << " rational " << rational;
      NurbsCurve one_by_one = curve;
      for (const double u : new_knots) {
        one_by_one = insert_knot(one_by_one, u);
      }
      EXPECT_EQ(refined.knots(), one_by_one.knots());
      EXPECT_LT((refined.control_points() - one_by_one.control_points()).cwiseAbs().maxCoeff(),
                kRoundOff);
      EXPECT_LT((refined.weights() - one_by_one.weights()).cwiseAbs().maxCoeff(), kRoundOff);
    }
  }
}

TEST(KnotRefinement, LeavesRationalCircleUnchanged) {
  const NurbsCurve circle = full_circle(2.0);
  std::vector<double> new_knots;
  for (int i = 1; i < 40; ++i) {
    if (i % 10 != 0) {  // 0.25, 0.5 and 0.75 are already double knots
      new_knots.push_back(i / 40.0);
    }
  }
  const NurbsCurve refined = refine_knots(circle, new_knots);
  EXPECT_EQ(refined.control_point_count(), circle.control_point_count() + 36);
  EXPECT_LT(max_deviation(circle, refined), kRoundOff);
  EXPECT_EQ(refine_knots(circle, {}).knots(), circle.knots());
}

TEST(KnotRefinement, LeavesPeriodicCurvesUnchanged) {
  for (const int degree : {3, 5}) {
    const NurbsCurve curve = random_periodic_curve(degree, 61U + degree, true);
    const std::vector<double> new_knots = {0.3, 0.31, 0.9, 1.1, 1.7, 1.7, 2.29};
    const NurbsCurve refined = refine_knots(curve, new_knots);
    EXPECT_TRUE(refined.is_periodic());
    EXPECT_EQ(refined.control_point_count(),
              curve.control_point_count() + static_cast<int>(new_knots.size()));
    EXPECT_LT(max_deviation(curve, refined), kRoundOff) << "degree " << degree;
  }
}

TEST(KnotRefinement, InvalidListThrowsErrorNamingTheValue) {
  const NurbsCurve circle = full_circle(1.0);
  EXPECT_THAT(error_message([&] { refine_knots(circle, {0.1, 0.7, 0.6}); }), HasSubstr("0.6"));
  EXPECT_THAT(error_message([&] { refine_knots(circle, {0.1, 1.25}); }), HasSubstr("1.25"));
  EXPECT_THAT(error_message([&] { refine_knots(circle, {0.1, 0.5}); }), HasSubstr("knot 0.5"));
  EXPECT_THAT(error_message([&] { refine_knots(circle, {0.3, 0.3, 0.3}); }), HasSubstr("knot 0.3"));
  EXPECT_THAT(error_message([&] {
                refine_knots(circle, {0.1, std::numeric_limits<double>::infinity()});
              }),
              HasSubstr("inf"));
}

TEST(SurfaceKnotInsertion, LeavesSurfacesUnchangedInUAndV) {
  for (const bool rational : {false, true}) {
    const NurbsSurface surface = random_surface(3, 2, 71U, rational, false);
    const NurbsSurface in_u = insert_knot(surface, SurfaceDirection::kU, 0.45, 2);
    EXPECT_EQ(in_u.control_point_count_u(), surface.control_point_count_u() + 2);
    EXPECT_EQ(in_u.knots_v(), surface.knots_v());
    EXPECT_LT(max_deviation(surface, in_u), kRoundOff) << "rational " << rational;
    const NurbsSurface in_v = insert_knot(surface, SurfaceDirection::kV, -0.2, 1);
    EXPECT_EQ(in_v.control_point_count_v(), surface.control_point_count_v() + 1);
    EXPECT_EQ(in_v.knots_u(), surface.knots_u());
    EXPECT_LT(max_deviation(surface, in_v), kRoundOff) << "rational " << rational;
  }
  const NurbsSurface torus_surface = torus(2.0, 0.5);
  EXPECT_LT(max_deviation(torus_surface, insert_knot(torus_surface, SurfaceDirection::kU, 0.1)),
            kRoundOff);
  EXPECT_LT(max_deviation(torus_surface, insert_knot(torus_surface, SurfaceDirection::kV, 0.7)),
            kRoundOff);
}

TEST(SurfaceKnotInsertion, LeavesPeriodicSurfaceUnchanged) {
  for (const int degree : {3, 5}) {
    const NurbsSurface surface = random_surface(degree, 3, 81U + degree, true, true);
    for (const double u : {0.0, 0.25, 0.55, 0.999}) {
      const NurbsSurface refined = insert_knot(surface, SurfaceDirection::kU, u, 2);
      EXPECT_TRUE(refined.knots_u().is_periodic());
      EXPECT_LT(max_deviation(surface, refined), kRoundOff) << "degree " << degree << " u " << u;
    }
    EXPECT_LT(max_deviation(surface, insert_knot(surface, SurfaceDirection::kV, 0.1, 3)),
              kRoundOff);
  }
}

TEST(SurfaceKnotRefinement, LeavesSurfacesUnchangedInUAndV) {
  for (const bool periodic_u : {false, true}) {
    const NurbsSurface surface = random_surface(3, 3, 91U, true, periodic_u);
    const NurbsSurface in_u =
        refine_knots(surface, SurfaceDirection::kU, {0.1, 0.2, 0.2, 0.6, 0.9});
    EXPECT_LT(max_deviation(surface, in_u), kRoundOff) << "periodic " << periodic_u;
    const NurbsSurface in_v =
        refine_knots(surface, SurfaceDirection::kV, {-0.9, -0.2, -0.2, 0.0, 0.75});
    EXPECT_LT(max_deviation(surface, in_v), kRoundOff) << "periodic " << periodic_u;
  }
  const NurbsSurface surface = random_surface(2, 2, 92U, false, false);
  EXPECT_THAT(error_message([&] { refine_knots(surface, SurfaceDirection::kV, {2.5}); }),
              HasSubstr("2.5"));
  EXPECT_THAT(error_message([&] { insert_knot(surface, SurfaceDirection::kU, -0.75); }),
              HasSubstr("-0.75"));
}

// Property tests: the shape before and after, compared at 65 parameters and every knot,
// relative to the control net's size. Insertion is a chain of convex combinations of the
// homogeneous points (weights 0.05..20, so w P up to 20): the measured worst case is ~1e-15.
constexpr double kShapeTolerance = 1e-12;

TEST(KnotInsertion, SeamGivenAsThePeriodEndKeepsTheCurve) {
  // Regression: inserting t_{p+n} into a curve whose seam has multiplicity 2 threw
  // vector::_M_range_insert (the index past the period list), multiplicity 1 gave a list that
  // "decreases".
  for (int seam = 1; seam <= 3; ++seam) {
    std::mt19937 generator(500U + seam);
    testing::RandomKnotOptions options;
    options.periodic = true;
    options.seam_multiplicity = seam;
    const NurbsCurve curve = testing::random_curve(4, options, true, generator);
    const double end = curve.knots().domain_end();
    const NurbsCurve refined = insert_knot(curve, end, 4 - seam);
    EXPECT_EQ(refined.knots().multiplicity(curve.knots().domain_start()), 4);
    EXPECT_EQ(refined.knots().domain_start(), curve.knots().domain_start());
    EXPECT_EQ(refined.knots().domain_end(), end);
    EXPECT_LT(testing::relative_deviation(curve, refined), kShapeTolerance) << "seam " << seam;
  }
}

TEST(KnotInsertion, KeepsThreeThousandRandomCurves) {
  std::mt19937 generator(1001U);
  double worst = 0.0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int degree = 1 + trial % 7;
    const testing::RandomKnotOptions options = testing::trial_options(trial, degree, true);
    const NurbsCurve curve =
        testing::random_curve(degree, options, (trial / 7) % 2 == 1, generator);
    const double u = testing::random_knot_to_insert(curve.knots(), generator);
    const int existing = curve.knots().multiplicity(curve.knots().wrap_to_period(u));
    const int times = testing::random_int(generator, 1, degree - existing);
    const NurbsCurve refined = insert_knot(curve, u, times);
    ASSERT_EQ(refined.control_point_count(), curve.control_point_count() + times);
    EXPECT_EQ(refined.knots().multiplicity(refined.knots().wrap_to_period(u)), existing + times);
    const double deviation = testing::relative_deviation(curve, refined);
    worst = std::max(worst, deviation);
    EXPECT_LT(deviation, kShapeTolerance) << "trial " << trial << " u " << u;
  }
  std::cout << "[ measured ] worst relative deviation " << worst << "\n";
}

TEST(KnotRefinement, KeepsThreeThousandRandomCurves) {
  std::mt19937 generator(1002U);
  double worst = 0.0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int degree = 1 + trial % 7;
    const testing::RandomKnotOptions options = testing::trial_options(trial, degree, true);
    const NurbsCurve curve =
        testing::random_curve(degree, options, (trial / 7) % 2 == 1, generator);
    // Up to 6 knots, each kept only while the multiplicities stay within the degree.
    std::vector<double> new_knots;
    for (int k = testing::random_int(generator, 1, 6); k > 0; --k) {
      const double u =
          curve.knots().wrap_to_period(testing::random_knot_to_insert(curve.knots(), generator));
      const int added = static_cast<int>(std::count(new_knots.begin(), new_knots.end(), u));
      if (curve.knots().multiplicity(u) + added < degree) {
        new_knots.push_back(u);
      }
    }
    std::sort(new_knots.begin(), new_knots.end());
    const NurbsCurve refined = refine_knots(curve, new_knots);
    ASSERT_EQ(refined.control_point_count(),
              curve.control_point_count() + static_cast<int>(new_knots.size()));
    const double deviation = testing::relative_deviation(curve, refined);
    worst = std::max(worst, deviation);
    EXPECT_LT(deviation, kShapeTolerance) << "trial " << trial;
  }
  std::cout << "[ measured ] worst relative deviation " << worst << "\n";
}

TEST(SurfaceKnotInsertion, KeepsTwoThousandRandomSurfacesInEitherDirection) {
  std::mt19937 generator(1003U);
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
    const int times = testing::random_int(
        generator, 1, knots.degree() - knots.multiplicity(knots.wrap_to_period(u)));
    const NurbsSurface refined = insert_knot(surface, direction, u, times);
    const double deviation = testing::relative_deviation(surface, refined);
    worst = std::max(worst, deviation);
    EXPECT_LT(deviation, kShapeTolerance) << "trial " << trial << " u " << u;
  }
  std::cout << "[ measured ] worst relative deviation " << worst << "\n";
}

TEST(SurfaceKnotRefinement, KeepsOneThousandRandomSurfacesInEitherDirection) {
  std::mt19937 generator(1004U);
  double worst = 0.0;
  for (int trial = 0; trial < 1000; ++trial) {
    const int degree_u = 1 + trial % 7;
    const int degree_v = 1 + (trial / 7) % 4;
    const NurbsSurface surface = testing::random_surface(
        degree_u, degree_v, testing::trial_options(trial, degree_u, true),
        testing::trial_options(trial / 2, degree_v, true), trial % 3 != 0, generator);
    const SurfaceDirection direction = trial % 5 < 3 ? SurfaceDirection::kU : SurfaceDirection::kV;
    const KnotVector& knots =
        direction == SurfaceDirection::kU ? surface.knots_u() : surface.knots_v();
    // Up to 4 knots (the seam among them), each kept while multiplicities stay within degree.
    std::vector<double> new_knots;
    for (int k = testing::random_int(generator, 1, 4); k > 0; --k) {
      const double u = knots.wrap_to_period(testing::random_knot_to_insert(knots, generator));
      const int added = static_cast<int>(std::count(new_knots.begin(), new_knots.end(), u));
      if (knots.multiplicity(u) + added < knots.degree()) {
        new_knots.push_back(u);
      }
    }
    std::sort(new_knots.begin(), new_knots.end());
    const NurbsSurface refined = refine_knots(surface, direction, new_knots);
    const double deviation = testing::relative_deviation(surface, refined);
    worst = std::max(worst, deviation);
    EXPECT_LT(deviation, kShapeTolerance) << "trial " << trial;
  }
  std::cout << "[ measured ] worst relative deviation " << worst << "\n";
}

}  // namespace
}  // namespace dnurbs
