#include "dnurbs/nurbs/bernstein.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace dnurbs {
namespace {

// Value of the polynomial with Bernstein coefficients c (degree c.size() - 1) at t, by the
// definition B_{i,n}(t) = C(n, i) t^i (1 - t)^(n - i).
double by_definition(const std::vector<double>& c, double t) {
  const int n = static_cast<int>(c.size()) - 1;
  double value = 0.0;
  for (int i = 0; i <= n; ++i) {
    value += c[static_cast<size_t>(i)] * binomial_coefficient(n, i) * std::pow(t, i) *
             std::pow(1.0 - t, n - i);
  }
  return value;
}

std::vector<double> random_coefficients(int degree, std::mt19937& generator) {
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  std::vector<double> c(static_cast<size_t>(degree + 1));
  for (double& value : c) {
    value = coefficient(generator);
  }
  return c;
}

// Sums of a few dozen products of values of size ~1: a few ulps.
constexpr double kRoundOff = 1e-13;

TEST(Bernstein, ProductWeightsMultiplyPolynomials) {
  std::mt19937 generator(1);
  for (int m = 0; m <= 6; ++m) {
    for (int n = 0; n <= 6; ++n) {
      const std::vector<double> a = random_coefficients(m, generator);
      const std::vector<double> b = random_coefficients(n, generator);
      std::vector<double> product(static_cast<size_t>(m + n + 1), 0.0);
      for (int i = 0; i <= m; ++i) {
        for (int j = 0; j <= n; ++j) {
          product[static_cast<size_t>(i) + static_cast<size_t>(j)] +=
              bernstein_product_weight(m, i, n, j) * a[static_cast<size_t>(i)] *
              b[static_cast<size_t>(j)];
        }
      }
      for (const double t : {0.0, 0.13, 0.5, 0.77, 1.0}) {
        EXPECT_NEAR(by_definition(product, t), by_definition(a, t) * by_definition(b, t),
                    kRoundOff);
      }
    }
  }
}

TEST(Bernstein, HalvesReproduceThePolynomialOnEachHalf) {
  std::mt19937 generator(2);
  for (const int degree : {1, 3, 8, kMaxBernsteinDegree}) {
    const std::vector<double> c = random_coefficients(degree, generator);
    std::vector<double> left(c.size());
    std::vector<double> right(c.size());
    split_bernstein_half(c.data(), degree, 1, left.data(), right.data());
    for (const double t : {0.0, 0.3, 0.61, 1.0}) {
      // Degree 45 sums of binomial-weighted terms lose a few more digits.
      EXPECT_NEAR(by_definition(left, t), by_definition(c, 0.5 * t), 1e-11) << degree;
      EXPECT_NEAR(by_definition(right, t), by_definition(c, 0.5 + 0.5 * t), 1e-11) << degree;
    }
  }
}

TEST(Bernstein, SignChangesBoundTheRootsInTheInterval) {
  // (t - 0.2)(t - 0.5)(t - 0.9) in Bernstein form: 3 roots in (0, 1), so 3 sign changes; its
  // square shifted up by 0.01 has none.
  const auto cubic = [](double t) { return (t - 0.2) * (t - 0.5) * (t - 0.9); };
  // Bernstein coefficients of the cubic: b_0 = f(0), b_1 = f(0) + f'(0)/3, b_2 = f(1) - f'(1)/3,
  // b_3 = f(1).
  const double d0 = (0.2 * 0.5 + 0.2 * 0.9 + 0.5 * 0.9);  // f'(0)
  const double d1 = (0.8 * 0.5 + 0.8 * 0.1 + 0.5 * 0.1);  // f'(1)
  const std::vector<double> c = {cubic(0.0), cubic(0.0) + d0 / 3.0, cubic(1.0) - d1 / 3.0,
                                 cubic(1.0)};
  for (const double t : {0.1, 0.4, 0.95}) {
    EXPECT_NEAR(by_definition(c, t), cubic(t), kRoundOff);
  }
  EXPECT_EQ(bernstein_sign_changes(c.data(), 4, 0.0), 3);
  const std::vector<double> positive = {0.01, 0.02, 0.015, 0.03};
  EXPECT_EQ(bernstein_sign_changes(positive.data(), 4, 0.0), 0);
  // Coefficients within the noise are skipped.
  const std::vector<double> noisy = {1.0, -1e-20, 2.0, -3.0};
  EXPECT_EQ(bernstein_sign_changes(noisy.data(), 4, 1e-15), 1);
  EXPECT_EQ(bernstein_sign_changes(noisy.data(), 4, 0.0), 3);
}

TEST(Bernstein, BasisDerivativesMatchFiniteDifferences) {
  const double h = 1e-6;
  for (int degree = 1; degree <= kMaxDegree; ++degree) {
    for (const double t : {0.05, 0.37, 0.8}) {
      BernsteinBasis at;
      BernsteinBasis plus;
      BernsteinBasis minus;
      bernstein_basis(degree, t, at);
      bernstein_basis(degree, t + h, plus);
      bernstein_basis(degree, t - h, minus);
      double sum = 0.0;
      for (int i = 0; i <= degree; ++i) {
        const auto k = static_cast<size_t>(i);
        sum += at[0][k];
        EXPECT_NEAR(
            at[0][k],
            binomial_coefficient(degree, i) * std::pow(t, i) * std::pow(1.0 - t, degree - i),
            kRoundOff);
        // Central differences: O(h^2) truncation times the third derivative (< 15^3 * C(15, 7)
        // ~ 2e7 for degree 15, so ~2e-5), plus round-off 1e-16 / h^2 = 1e-4 for the second.
        EXPECT_NEAR(at[1][k], (plus[0][k] - minus[0][k]) / (2 * h), 1e-4) << degree;
        EXPECT_NEAR(at[2][k], (plus[1][k] - minus[1][k]) / (2 * h), 1e-2 * (1 + std::abs(at[2][k])))
            << degree;
      }
      EXPECT_NEAR(sum, 1.0, kRoundOff);  // partition of unity
    }
  }
}

TEST(Bernstein, NetValueIsTheTensorProduct) {
  std::mt19937 generator(3);
  const int m = 4;
  const int n = 7;
  const std::vector<double> net = random_coefficients((m + 1) * (n + 1) - 1, generator);
  for (const auto& [s, t] : {std::pair{0.0, 0.0}, std::pair{0.3, 0.9}, std::pair{1.0, 0.45}}) {
    double expected = 0.0;
    for (int i = 0; i <= m; ++i) {
      for (int j = 0; j <= n; ++j) {
        const auto index = static_cast<size_t>(i) * (n + 1) + static_cast<size_t>(j);
        expected += net[index] * binomial_coefficient(m, i) * std::pow(s, i) *
                    std::pow(1 - s, m - i) * binomial_coefficient(n, j) * std::pow(t, j) *
                    std::pow(1 - t, n - j);
      }
    }
    EXPECT_NEAR(bernstein_net_value(net.data(), m, n, s, t), expected, kRoundOff);
  }
}

}  // namespace
}  // namespace dnurbs
