#include "dnurbs/nurbs/bernstein.h"

#include <cstddef>

namespace dnurbs {

double binomial_coefficient(int n, int k) {
  if (k < 0 || k > n) {
    return 0.0;
  }
  double value = 1.0;
  for (int i = 1; i <= k; ++i) {
    value = value * (n - k + i) / i;
  }
  return value;
}

double bernstein_product_weight(int m, int i, int n, int j) {
  return binomial_coefficient(m, i) * binomial_coefficient(n, j) /
         binomial_coefficient(m + n, i + j);
}

void split_bernstein_half(const double* c, int degree, int stride, double* left, double* right) {
  // de Casteljau's triangle at t = 1/2: the left edge gives [0, 1/2], the right edge [1/2, 1].
  std::array<double, kMaxBernsteinDegree + 1> work{};
  const auto step = static_cast<std::ptrdiff_t>(stride);
  const auto count = static_cast<size_t>(degree) + 1;
  for (size_t i = 0; i < count; ++i) {
    work[i] = c[static_cast<std::ptrdiff_t>(i) * step];
  }
  right[static_cast<std::ptrdiff_t>(degree) * step] = work[count - 1];
  left[0] = work[0];
  for (size_t r = 1; r < count; ++r) {
    for (size_t i = 0; i + r < count; ++i) {
      work[i] = 0.5 * (work[i] + work[i + 1]);
    }
    left[static_cast<std::ptrdiff_t>(r) * step] = work[0];
    right[static_cast<std::ptrdiff_t>(count - 1 - r) * step] = work[count - 1 - r];
  }
}

int bernstein_sign_changes(const double* c, int count, double noise) {
  int changes = 0;
  int previous = 0;
  for (int i = 0; i < count; ++i) {
    const int sign = c[i] > noise ? 1 : (c[i] < -noise ? -1 : 0);
    if (sign != 0) {
      changes += previous != 0 && sign != previous ? 1 : 0;
      previous = sign;
    }
  }
  return changes;
}

void bernstein_values(int degree, double t, double* values) {
  const double s = 1.0 - t;
  values[0] = 1.0;
  for (int k = 1; k <= degree; ++k) {
    values[k] = t * values[k - 1];
    for (int i = k - 1; i > 0; --i) {
      values[i] = s * values[i] + t * values[i - 1];
    }
    values[0] *= s;
  }
}

double bernstein_net_value(const double* c, int m, int n, double s, double t) {
  std::array<double, kMaxBernsteinDegree + 1> along_s{};
  std::array<double, kMaxBernsteinDegree + 1> along_t{};
  bernstein_values(m, s, along_s.data());
  bernstein_values(n, t, along_t.data());
  double value = 0.0;
  for (int i = 0; i <= m; ++i) {
    double row = 0.0;
    for (int j = 0; j <= n; ++j) {
      row += along_t[static_cast<size_t>(j)] * c[i * (n + 1) + j];
    }
    value += along_s[static_cast<size_t>(i)] * row;
  }
  return value;
}

void bernstein_basis(int degree, double t, BernsteinBasis& values) {
  // Bernstein triangle B_{i,k} = (1 - t) B_{i,k-1} + t B_{i-1,k-1}, keeping degrees p - 2, p - 1
  // and p; B'_{i,p} = p (B_{i-1,p-1} - B_{i,p-1}), B''_{i,p} = p (p - 1) (B_{i-2,p-2} -
  // 2 B_{i-1,p-2} + B_{i,p-2}).
  std::array<double, kMaxDegree + 1> basis{};
  std::array<double, kMaxDegree + 1> lower1{};
  std::array<double, kMaxDegree + 1> lower2{};
  basis[0] = 1.0;
  const double s = 1.0 - t;
  for (int k = 1; k <= degree; ++k) {
    if (k == degree - 1) {
      lower2 = basis;
    }
    if (k == degree) {
      lower1 = basis;
    }
    basis[static_cast<size_t>(k)] = t * basis[static_cast<size_t>(k - 1)];
    for (int i = k - 1; i > 0; --i) {
      basis[static_cast<size_t>(i)] =
          s * basis[static_cast<size_t>(i)] + t * basis[static_cast<size_t>(i - 1)];
    }
    basis[0] *= s;
  }
  if (degree == 1) {
    lower2[0] = 0.0;  // no degree -1 basis: the second derivatives vanish
  }
  const auto at = [](const std::array<double, kMaxDegree + 1>& b, int i, int top) {
    return i < 0 || i > top ? 0.0 : b[static_cast<size_t>(i)];
  };
  for (int i = 0; i <= degree; ++i) {
    values[0][static_cast<size_t>(i)] = basis[static_cast<size_t>(i)];
    values[1][static_cast<size_t>(i)] =
        degree * (at(lower1, i - 1, degree - 1) - at(lower1, i, degree - 1));
    values[2][static_cast<size_t>(i)] =
        degree < 2 ? 0.0
                   : degree * (degree - 1) *
                         (at(lower2, i - 2, degree - 2) - 2.0 * at(lower2, i - 1, degree - 2) +
                          at(lower2, i, degree - 2));
  }
}

}  // namespace dnurbs
