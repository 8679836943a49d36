#include "dnurbs/nurbs/gauss_legendre.h"

#include <array>
#include <cmath>
#include <numbers>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

GaussLegendreRule compute_rule(int n) {
  GaussLegendreRule rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  const long double pi = std::numbers::pi_v<long double>;
  // Roots are symmetric: compute the upper half by Newton's method from Tricomi's estimate.
  for (int i = 0; i < (n + 1) / 2; ++i) {
    long double x = std::cos(pi * (i + 0.75L) / (n + 0.5L));
    long double derivative = 0.0L;
    for (int iteration = 0; iteration < 100; ++iteration) {
      // Legendre recurrence: (k + 1) P_{k+1} = (2k + 1) x P_k - k P_{k-1}.
      long double p0 = 1.0L;
      long double p1 = x;
      for (int k = 1; k < n; ++k) {
        const long double p2 = ((2 * k + 1) * x * p1 - k * p0) / (k + 1);
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1.0L);
      const long double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-19L) {
        break;
      }
    }
    const long double weight = 2.0L / ((1.0L - x * x) * derivative * derivative);
    rule.nodes[n - 1 - i] = static_cast<double>(x);
    rule.nodes[i] = static_cast<double>(-x);
    rule.weights[i] = rule.weights[n - 1 - i] = static_cast<double>(weight);
  }
  return rule;
}

}  // namespace

const GaussLegendreRule& gauss_legendre_rule(int point_count) {
  if (point_count < 1 || point_count > kMaxGaussPoints) {
    throw make_error("Gauss-Legendre rule with ", point_count, " points: must be in 1..",
                     kMaxGaussPoints);
  }
  // Function-local statics are initialized once, thread-safely.
  static const std::array<GaussLegendreRule, kMaxGaussPoints> rules = [] {
    std::array<GaussLegendreRule, kMaxGaussPoints> all;
    for (int n = 1; n <= kMaxGaussPoints; ++n) {
      all[static_cast<size_t>(n - 1)] = compute_rule(n);
    }
    return all;
  }();
  return rules[static_cast<size_t>(point_count - 1)];
}

GaussLegendreRule gauss_legendre_rule_on(int point_count, double a, double b) {
  const GaussLegendreRule& reference = gauss_legendre_rule(point_count);
  const double half = 0.5 * (b - a);
  GaussLegendreRule mapped;
  mapped.nodes = (reference.nodes.array() + 1.0) * half + a;
  mapped.weights = reference.weights * half;
  return mapped;
}

}  // namespace dnurbs
