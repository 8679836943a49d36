#include "dnurbs/nurbs/gauss_legendre.h"

#include <cmath>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

TEST(GaussLegendre, IntegratesPolynomialsOfDegreeTwoNMinusOneExactly) {
  for (int n = 1; n <= kMaxGaussPoints; ++n) {
    const GaussLegendreRule& rule = gauss_legendre_rule(n);
    ASSERT_EQ(rule.nodes.size(), n);
    for (int degree = 0; degree <= 2 * n - 1; ++degree) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) {
        sum += rule.weights[i] * std::pow(rule.nodes[i], degree);
      }
      if (degree % 2 == 1) {
        // Odd monomials integrate to zero; nodes are exactly symmetric so only rounding remains.
        EXPECT_NEAR(sum, 0.0, 1e-15) << "n " << n << " degree " << degree;
      } else {
        const double exact = 2.0 / (degree + 1);
        EXPECT_NEAR(sum / exact, 1.0, 1e-14) << "n " << n << " degree " << degree;
      }
    }
  }
}

TEST(GaussLegendre, IsNotExactBeyondDegreeTwoN) {
  // The rule's order is sharp: x^(2n) is not integrated exactly (checks the nodes are the
  // Legendre roots, not some other symmetric set).
  for (int n = 1; n <= 10; ++n) {
    const GaussLegendreRule& rule = gauss_legendre_rule(n);
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      sum += rule.weights[i] * std::pow(rule.nodes[i], 2 * n);
    }
    EXPECT_GT(std::abs(sum - 2.0 / (2 * n + 1)), 1e-6) << n;
  }
}

TEST(GaussLegendre, MappedRuleIntegratesOnAnInterval) {
  // integral_{0.5}^{2} (3x^5 - x^2 + 4) dx = [x^6/2 - x^3/3 + 4x] = 43.96875 - ... exactly:
  const auto antiderivative = [](double x) {
    return std::pow(x, 6) / 2 - std::pow(x, 3) / 3 + 4 * x;
  };
  const GaussLegendreRule rule = gauss_legendre_rule_on(3, 0.5, 2.0);
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double x = rule.nodes[i];
    sum += rule.weights[i] * (3 * std::pow(x, 5) - x * x + 4);
  }
  const double exact = antiderivative(2.0) - antiderivative(0.5);
  EXPECT_NEAR(sum / exact, 1.0, 1e-14);
}

TEST(GaussLegendre, RejectsPointCountsOutsideTheTable) {
  EXPECT_THROW(gauss_legendre_rule(0), Error);
  EXPECT_THROW(gauss_legendre_rule(kMaxGaussPoints + 1), Error);
}

}  // namespace
}  // namespace dnurbs
