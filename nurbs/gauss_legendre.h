#pragma once
// Gauss-Legendre quadrature rules, the integrator of every mass, damping and stiffness matrix.

#include <Eigen/Core>

namespace dnurbs {

/// Largest number of points of a rule.
inline constexpr int kMaxGaussPoints = 32;

/// An n-point Gauss-Legendre rule on [-1, 1]: exact for polynomials of degree 2n - 1.
struct GaussLegendreRule {
  Eigen::VectorXd nodes;    ///< n nodes in increasing order
  Eigen::VectorXd weights;  ///< n positive weights that sum to 2
};

/// The n-point rule (n in 1..kMaxGaussPoints) with nodes and weights accurate to about 1e-16,
/// computed by Newton's method on the Legendre recurrence in long double. Throws Error otherwise.
/// Rules are computed once per n and cached (thread-safe).
const GaussLegendreRule& gauss_legendre_rule(int point_count);

/// The rule mapped onto [a, b]: nodes a + (b - a)(x + 1)/2 and weights scaled by (b - a)/2.
GaussLegendreRule gauss_legendre_rule_on(int point_count, double a, double b);

}  // namespace dnurbs
