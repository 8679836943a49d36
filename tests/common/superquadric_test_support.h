#pragma once
// Shared pieces of the superquadric geometry tests: the exponents every derivative is checked
// for, the parameter values where cos or sin vanish, and central finite differences.

#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/Core>

namespace dnurbs::testing {

/// The squareness exponents of the issue: both ends of [0.1, 4], 1 (the sphere) and two between.
inline constexpr std::array<double, 5> kExponents = {0.1, 0.5, 1.0, 2.0, 4.0};

/// Parameters where cos or sin vanish (or both are +-1): 0, +-pi/2, +-pi.
inline constexpr std::array<double, 5> kSpecialAngles = {
    0.0, std::numbers::pi / 2, -std::numbers::pi / 2, std::numbers::pi, -std::numbers::pi};

/// Generic (u, v): away from every zero of cos and sin (|cos|, |sin| >= 0.2), in all quadrants.
inline constexpr std::array<std::array<double, 2>, 6> kGenericParameters = {{
    {0.37, 0.81},
    {-0.93, 2.31},
    {1.21, -2.67},
    {-0.45, -0.62},
    {0.74, 1.93},
    {-1.27, -1.38},
}};

/// Central difference (f(x + h) - f(x - h)) / (2h) of a vector-valued f of one scalar.
template <typename Function>
auto central_difference(const Function& f, double x, double step) {
  return ((f(x + step) - f(x - step)) / (2.0 * step)).eval();
}

/// True when every entry of the matrix is finite.
template <typename Derived>
bool all_finite(const Eigen::MatrixBase<Derived>& matrix) {
  return matrix.array().isFinite().all();
}

}  // namespace dnurbs::testing
