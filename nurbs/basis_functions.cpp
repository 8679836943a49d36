#include "dnurbs/nurbs/basis_functions.h"

#include <array>

#include "dnurbs/core/error.h"

namespace dnurbs {

void basis_functions(const KnotVector& knots, int span, double u, BasisValues& values) {
  const int p = knots.degree();
  std::array<double, kMaxDegree + 1> left{};
  std::array<double, kMaxDegree + 1> right{};
  values.resize(p + 1);
  values[0] = 1.0;
  // Cox-de Boor triangle, one degree at a time (A2.2).
  for (int j = 1; j <= p; ++j) {
    left[j] = u - knots[span + 1 - j];
    right[j] = knots[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = values[r] / (right[r + 1] + left[j - r]);
      values[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    values[j] = saved;
  }
}

void basis_functions_with_derivatives(const KnotVector& knots, int span, double u, int order,
                                      BasisDerivatives& derivatives) {
  if (order < 0 || order > kMaxDerivativeOrder) {
    throw make_error("derivative order ", order, " is outside 0..", kMaxDerivativeOrder);
  }
  const int p = knots.degree();
  std::array<double, kMaxDegree + 1> left{};
  std::array<double, kMaxDegree + 1> right{};
  // ndu: basis functions (upper triangle) and knot differences (lower triangle), A2.3.
  std::array<std::array<double, kMaxDegree + 1>, kMaxDegree + 1> ndu{};
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - knots[span + 1 - j];
    right[j] = knots[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }

  derivatives.setZero(order + 1, p + 1);
  for (int j = 0; j <= p; ++j) {
    derivatives(0, j) = ndu[j][p];
  }
  const int highest = order < p ? order : p;
  // Derivatives by the recurrence on the coefficients a_{k,j} (A2.3), two alternating rows.
  std::array<std::array<double, kMaxDegree + 1>, 2> a{};
  for (int r = 0; r <= p; ++r) {
    int s1 = 0;
    int s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= highest; ++k) {
      double d = 0.0;
      const int rk = r - k;
      const int pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = r - 1 <= pk ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      derivatives(k, r) = d;
      std::swap(s1, s2);
    }
  }
  // Multiply by p! / (p - k)!.
  double factor = p;
  for (int k = 1; k <= highest; ++k) {
    derivatives.row(k) *= factor;
    factor *= p - k;
  }
}

}  // namespace dnurbs
