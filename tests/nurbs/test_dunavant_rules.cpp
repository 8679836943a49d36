// Tests of nurbs/dunavant_rules.h: every rule integrates every monomial of its degree exactly
// (after polishing, to round-off), is not exact one degree higher, and the composite form keeps
// the exactness.

#include "dnurbs/nurbs/dunavant_rules.h"

#include <cmath>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// Exact mean of u^i v^j over the reference triangle (0, 0), (1, 0), (0, 1):
// 2 i! j! / (i + j + 2)!.
double exact_mean(int i, int j) {
  double value = 2.0;
  for (int k = 1; k <= i; ++k) {
    value *= static_cast<double>(k) / (j + k);
  }
  return value / ((i + j + 1.0) * (i + j + 2.0));
}

// Largest error over the monomials of total degree exactly `degree` (or <= if cumulative).
double monomial_error(const TriangleRule& rule, int degree, bool cumulative) {
  double worst = 0.0;
  for (int total = cumulative ? 0 : degree; total <= degree; ++total) {
    for (int i = 0; i <= total; ++i) {
      const int j = total - i;
      double sum = 0.0;
      for (int g = 0; g < rule.point_count(); ++g) {
        sum += rule.weights[g] * std::pow(rule.barycentric(g, 1), i) *
               std::pow(rule.barycentric(g, 2), j);
      }
      worst = std::max(worst, std::abs(sum - exact_mean(i, j)));
    }
  }
  return worst;
}

TEST(DunavantRules, IntegrateEveryMonomialOfTheirDegreeExactly) {
  for (int degree = 1; degree <= kMaxDunavantDegree; ++degree) {
    const TriangleRule& rule = dunavant_rule(degree);
    EXPECT_EQ(rule.degree, degree);
    EXPECT_NEAR(rule.weights.sum(), 1.0, 1e-15);
    EXPECT_LT((rule.barycentric.rowwise().sum().array() - 1.0).abs().maxCoeff(), 1e-15);
    // Polished to long-double accuracy; what remains is the double rounding of the points and
    // of the sum (means of monomials are <= 1).
    EXPECT_LT(monomial_error(rule, degree, true), 1e-14) << "degree " << degree;
    // Sharp: some monomial of degree + 1 is not integrated exactly (errors from 1e-10 for
    // degree 14, whose next moments are small, to 1e-2; far above round-off).
    EXPECT_GT(monomial_error(rule, degree + 1, false), 1e-12) << "degree " << degree;
  }
}

TEST(DunavantRules, PointCountsAndSignsAreDunavantsTable) {
  const std::array<int, 14> counts = {1, 3, 4, 6, 7, 12, 13, 16, 19, 25, 27, 33, 37, 42};
  for (int degree = 1; degree <= kMaxDunavantDegree; ++degree) {
    const TriangleRule& rule = dunavant_rule(degree);
    EXPECT_EQ(rule.point_count(), counts[static_cast<size_t>(degree - 1)]);
    // Degrees 3 and 7 have a negative centroid weight, degree 11 points outside.
    const bool expected = degree != 3 && degree != 7 && degree != 11;
    EXPECT_EQ(rule.interior_and_positive, expected) << "degree " << degree;
  }
  EXPECT_EQ(interior_positive_dunavant_rule(3).degree, 4);
  EXPECT_EQ(interior_positive_dunavant_rule(7).degree, 8);
  EXPECT_EQ(interior_positive_dunavant_rule(11).degree, 12);
  EXPECT_EQ(interior_positive_dunavant_rule(6).degree, 6);
  EXPECT_THROW(dunavant_rule(0), Error);
  EXPECT_THROW(dunavant_rule(kMaxDunavantDegree + 1), Error);
  EXPECT_THROW(interior_positive_dunavant_rule(15), Error);
}

TEST(DunavantRules, SubdividedRuleKeepsExactnessAndConvergesOnAKink) {
  for (const int s : {1, 2, 5}) {
    const TriangleRule rule = subdivided_rule(dunavant_rule(5), s);
    EXPECT_EQ(rule.point_count(), 7 * s * s);
    EXPECT_NEAR(rule.weights.sum(), 1.0, 1e-15);
    EXPECT_LT(monomial_error(rule, 5, true), 1e-14) << "subdivisions " << s;
  }
  // |u - 1/3| has a kink: the composite error falls by about 4 per halving (second order).
  auto kink_error = [](int s) {
    const TriangleRule rule = subdivided_rule(dunavant_rule(2), s);
    double sum = 0.0;
    for (int g = 0; g < rule.point_count(); ++g) {
      sum += rule.weights[g] * std::abs(rule.barycentric(g, 1) - 1.0 / 3.0);
    }
    // Exact mean: 2 integral_0^1 |u - c| (1 - u) du = 2 (c^2/2 - c^3/6 + (1 - c)^3/6) = 16/81
    // for c = 1/3.
    const double exact = 16.0 / 81.0;
    return std::abs(sum - exact);
  };
  EXPECT_LT(kink_error(40), kink_error(10) / 8.0);
  EXPECT_THROW(subdivided_rule(dunavant_rule(2), 0), Error);
}

}  // namespace
}  // namespace dnurbs
