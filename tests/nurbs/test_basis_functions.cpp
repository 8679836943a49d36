#include "dnurbs/nurbs/basis_functions.h"

#include <random>

#include <gtest/gtest.h>

namespace dnurbs {
namespace {

// Knot vectors with repeated interior knots for degrees 1..5.
KnotVector test_knots(int degree) {
  std::vector<double> knots(static_cast<size_t>(degree + 1), 0.0);
  for (double interior : {0.15, 0.3, 0.3, 0.55, 0.7, 0.7, 0.9}) {
    knots.push_back(interior);
  }
  knots.insert(knots.end(), static_cast<size_t>(degree + 1), 1.0);
  return KnotVector(degree, knots);
}

TEST(BasisFunctions, PartitionOfUnity) {
  std::mt19937 generator(1);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int degree = 2; degree <= 7; ++degree) {  // interior multiplicity 2 needs p >= 2
    const KnotVector knots = test_knots(degree);
    for (int trial = 0; trial < 500; ++trial) {
      const double u = trial == 0 ? 1.0 : (trial == 1 ? 0.3 : uniform(generator));
      const int span = knots.find_span(u);
      BasisValues values;
      basis_functions(knots, span, u, values);
      // Each value is a convex combination; the sum is 1 up to a few roundings.
      EXPECT_NEAR(values.sum(), 1.0, 1e-14) << "degree " << degree << " u " << u;
      EXPECT_GE(values.minCoeff(), 0.0);
      BasisDerivatives derivatives;
      basis_functions_with_derivatives(knots, span, u, degree, derivatives);
      EXPECT_NEAR((derivatives.row(0).transpose() - values).norm(), 0.0, 1e-15);
      // Derivatives of a partition of unity sum to zero (relative to their size).
      for (int k = 1; k <= degree; ++k) {
        EXPECT_NEAR(derivatives.row(k).sum(), 0.0,
                    1e-10 * (1.0 + derivatives.row(k).cwiseAbs().sum()));
      }
    }
  }
}

TEST(BasisFunctions, DerivativesMatchCentralDifferences) {
  const double h = 1e-6;
  for (int degree = 2; degree <= 5; ++degree) {
    const KnotVector knots = test_knots(degree);
    for (double u : {0.05, 0.2, 0.42, 0.62, 0.8, 0.95}) {
      const int span = knots.find_span(u);
      BasisDerivatives at;
      BasisDerivatives plus;
      BasisDerivatives minus;
      basis_functions_with_derivatives(knots, span, u, 3, at);
      basis_functions_with_derivatives(knots, span, u + h, 3, plus);
      basis_functions_with_derivatives(knots, span, u - h, 3, minus);
      for (int k = 1; k <= 3; ++k) {
        for (int j = 0; j <= degree; ++j) {
          const double difference = (plus(k - 1, j) - minus(k - 1, j)) / (2 * h);
          // Central differences: error h^2/6 |N^(k+2)| (basis derivatives reach ~1e4 on spans
          // of width 0.1) plus rounding eps |N^(k-1)| / h.
          EXPECT_NEAR(at(k, j), difference, 1e-6 * (1.0 + std::abs(at(k, j))))
              << "degree " << degree << " order " << k << " j " << j << " u " << u;
        }
      }
    }
  }
}

TEST(BasisFunctions, DerivativesAboveTheDegreeAreZero) {
  const KnotVector knots = test_knots(2);
  BasisDerivatives derivatives;
  basis_functions_with_derivatives(knots, knots.find_span(0.4), 0.4, 5, derivatives);
  EXPECT_EQ(derivatives.rows(), 6);
  EXPECT_EQ(derivatives.bottomRows(3).cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace
}  // namespace dnurbs
