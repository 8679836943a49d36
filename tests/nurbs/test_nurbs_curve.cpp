#include "dnurbs/nurbs/nurbs_curve.h"

#include <cmath>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "sample_shapes.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

TEST(RationalCircle, RadiusIsOneEverywhere) {
  const NurbsCurve circle = full_circle(1.0);
  double worst = 0.0;
  for (int i = 0; i <= 10000; ++i) {
    const double u = i / 10000.0;
    worst = std::max(worst, std::abs(circle.point(u).norm() - 1.0));
  }
  // Exact in exact arithmetic; a handful of roundings in the quotient.
  EXPECT_LT(worst, 1e-14);
}

TEST(RationalCircle, CurvatureIsInverseRadiusAndNormalPointsToCentre) {
  const Eigen::Vector3d centre(0.5, -1.0, 2.0);
  const NurbsCurve circle = full_circle(2.0, centre);
  for (int i = 0; i < 400; ++i) {
    const double u = (i + 0.5) / 400.0;
    EXPECT_NEAR(circle.curvature(u), 0.5, 1e-13);
    const Eigen::Vector3d inward = (centre - circle.point(u)).normalized();
    EXPECT_NEAR(circle.principal_normal(u).dot(inward), 1.0, 1e-13);
    EXPECT_NEAR(circle.unit_tangent(u).dot(inward), 0.0, 1e-13);
  }
}

// Checks C^(k) against central differences of C^(k-1) at and between repeated knots. At a
// knot, the difference is one-sided into the span the evaluator uses (the right one).
void expect_derivatives_match_differences(const NurbsCurve& curve) {
  const double h = 1e-6;
  for (double u : {0.0, 0.1, 0.2, 0.3, 0.45, 0.5, 0.7, 0.85, 0.999}) {
    const CurveDerivatives at = curve.derivatives(u, 2);
    const bool at_knot = curve.knots().multiplicity(u) > 0;
    for (int k = 1; k <= 2; ++k) {
      Eigen::RowVector3d difference;
      if (at_knot) {
        // Second-order forward difference: error h^2/3 |C^(k+2)|.
        difference = (-3.0 * at.row(k - 1) + 4.0 * curve.derivatives(u + h, 2).row(k - 1) -
                      curve.derivatives(u + 2 * h, 2).row(k - 1)) /
                     (2 * h);
      } else {
        difference =
            (curve.derivatives(u + h, 2).row(k - 1) - curve.derivatives(u - h, 2).row(k - 1)) /
            (2 * h);
      }
      // Truncation h^2 |C^(k+2)| (up to ~1e4 for these rational curves) plus rounding
      // eps |C^(k-1)| / h: about 1e-8 relative to the derivative's scale.
      const double scale = 1.0 + at.row(k).norm();
      EXPECT_LT((at.row(k) - difference).norm(), 1e-6 * scale)
          << "order " << k << " at u = " << u << ": " << at.row(k) << " vs " << difference;
    }
  }
}

TEST(NurbsCurve, DerivativesMatchFiniteDifferences) {
  for (int degree : {2, 3, 5}) {
    expect_derivatives_match_differences(testing::random_rational_curve(degree, 11 + degree));
    expect_derivatives_match_differences(
        testing::random_rational_curve(degree, 21 + degree, false));
  }
  expect_derivatives_match_differences(full_circle(1.5));
}

TEST(NurbsCurve, HigherDerivativesOfAPolynomialCurveVanishAboveTheDegree) {
  const NurbsCurve curve = testing::random_rational_curve(3, 5, false);
  const CurveDerivatives derivatives = curve.derivatives(0.33, 5);
  EXPECT_EQ(derivatives.bottomRows(2).cwiseAbs().maxCoeff(), 0.0);
}

TEST(PeriodicCurve, IsCpMinusOneAcrossTheSeam) {
  std::mt19937 generator(3);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (int degree : {2, 3, 4}) {
    const KnotVector knots = KnotVector::periodic(degree, {0.0, 0.1, 0.25, 0.5, 0.6, 0.8, 1.0});
    Eigen::MatrixX3d points(6, 3);
    Eigen::VectorXd weights(6);
    for (int i = 0; i < 6; ++i) {
      points.row(i) << coordinate(generator), coordinate(generator), coordinate(generator);
      weights[i] = 1.5 + coordinate(generator);
    }
    const NurbsCurve curve(knots, points, weights);
    // u = 1 is evaluated in the last span, u = 0 in the first: the two sides of the seam.
    const CurveDerivatives left = curve.derivatives(1.0, degree - 1);
    const CurveDerivatives right = curve.derivatives(0.0, degree - 1);
    for (int k = 0; k < degree; ++k) {
      EXPECT_LT((left.row(k) - right.row(k)).norm(), 1e-12 * (1.0 + left.row(k).norm()))
          << "degree " << degree << " order " << k;
    }
    // The jump in the p-th derivative is generically non-zero: the seam is a real knot.
    const CurveDerivatives left_p = curve.derivatives(1.0, degree);
    const CurveDerivatives right_p = curve.derivatives(0.0, degree);
    EXPECT_GT((left_p.row(degree) - right_p.row(degree)).norm(), 1e-6);
  }
}

TEST(PeriodicCurve, EqualsTheOpenCurveOnTheWrappedPolygon) {
  const KnotVector periodic = KnotVector::periodic(3, {0.0, 0.2, 0.3, 0.6, 0.8, 1.0});
  Eigen::MatrixX3d points(5, 3);
  points << 1, 0, 0, 0.3, 1, 0.2, -1, 0.4, 0, -0.5, -1, 0.5, 0.6, -0.8, 0;
  Eigen::VectorXd weights(5);
  weights << 1, 2, 0.5, 1, 1.5;
  const NurbsCurve closed(periodic, points, weights);
  // The same curve as an open (unclamped) curve: the polygon with its first p points repeated.
  Eigen::MatrixX3d wrapped(8, 3);
  Eigen::VectorXd wrapped_weights(8);
  for (int i = 0; i < 8; ++i) {
    wrapped.row(i) = points.row(i % 5);
    wrapped_weights[i] = weights[i % 5];
  }
  const NurbsCurve open(KnotVector(3, periodic.knots()), wrapped, wrapped_weights);
  for (int i = 0; i <= 100; ++i) {
    const double u = i / 100.0;
    EXPECT_LT((closed.point(u) - open.point(u)).norm(), 1e-14);
  }
  EXPECT_LT((closed.point(1.3) - closed.point(0.3)).norm(), 1e-15);  // wraps
}

TEST(NurbsCurve, RejectsInvalidControlPointsAndWeights) {
  const KnotVector knots = KnotVector::clamped_uniform(2, 4);
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Random(4, 3);
  const auto message = [&](Eigen::MatrixX3d p, Eigen::VectorXd w) -> std::string {
    try {
      NurbsCurve(knots, p, w);
    } catch (const Error& error) {
      return error.what();
    }
    return "no error";
  };
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(4);
  weights[2] = 0.0;
  EXPECT_THAT(message(points, weights), HasSubstr("weight 2 is 0"));
  weights[2] = -0.5;
  EXPECT_THAT(message(points, weights), HasSubstr("weight 2 is -0.5"));
  weights[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(message(points, weights), HasSubstr("weight 2 is nan"));
  EXPECT_THAT(message(Eigen::MatrixX3d::Random(3, 3), {}),
              HasSubstr("needs 4 control points, got 3"));
  points(1, 2) = std::numeric_limits<double>::infinity();
  EXPECT_THAT(message(points, {}), HasSubstr("control point 1 has a non-finite coordinate 2"));
  EXPECT_THAT(message(Eigen::MatrixX3d::Random(4, 3), Eigen::VectorXd::Ones(3)),
              HasSubstr("expected 4 weights, got 3"));
}

TEST(NurbsCurve, DegreeTooHighForTheControlPointsIsRejected) {
  // Degree 4 with 3 control points: the clamped constructor names both numbers.
  EXPECT_THROW(KnotVector::clamped_uniform(4, 3), Error);
  // A curve on a knot vector for 5 points given 3 points.
  EXPECT_THROW(NurbsCurve(KnotVector::clamped_uniform(4, 5), Eigen::MatrixX3d::Zero(3, 3)), Error);
}

}  // namespace
}  // namespace dnurbs
