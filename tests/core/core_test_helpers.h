#pragma once
// Test matrices for the sparse Cholesky tests and a reference solve accurate far below double
// rounding.

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <random>
#include <unsupported/Eigen/KroneckerProduct>
#include <vector>

namespace dnurbs::testing {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// Toeplitz band of a cardinal cubic B-spline Gram kernel: entries c[|i - j|] for |i - j| <= 3.
inline SparseMatrix banded_toeplitz(int size, const double (&c)[4]) {
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < size; ++i) {
    for (int j = std::max(0, i - 3); j <= std::min(size - 1, i + 3); ++j) {
      entries.emplace_back(i, j, c[std::abs(i - j)]);
    }
  }
  SparseMatrix m(size, size);
  m.setFromTriplets(entries.begin(), entries.end());
  return m;
}

// The scalar matrix of a side by side bicubic sheet on uniform knots (interior kernels of the
// cardinal cubic B-spline, unit spacing): integrals of N_i N_j, N_i' N_j' and N_i'' N_j'', which
// are 151/315, 397/1680, 1/42, 1/5040; 2/3, -1/8, -1/5, -1/120; 8/3, -3/2, 0, 1/6 for
// |i - j| = 0..3. A = mass M(x)M + (K1(x)M + M(x)K1) + bending (K2(x)M + 2 K1(x)K1 + M(x)K2): a
// D-NURBS step matrix M/dt^2 + K with the 49-entry pattern of a bicubic tensor-product basis.
inline SparseMatrix sheet_matrix(int side, double mass = 100.0, double bending = 1e-2) {
  constexpr double kMass[4] = {151.0 / 315.0, 397.0 / 1680.0, 1.0 / 42.0, 1.0 / 5040.0};
  constexpr double kFirst[4] = {2.0 / 3.0, -1.0 / 8.0, -1.0 / 5.0, -1.0 / 120.0};
  constexpr double kSecond[4] = {8.0 / 3.0, -3.0 / 2.0, 0.0, 1.0 / 6.0};
  const SparseMatrix m = banded_toeplitz(side, kMass);
  const SparseMatrix k1 = banded_toeplitz(side, kFirst);
  const SparseMatrix k2 = banded_toeplitz(side, kSecond);
  SparseMatrix a = mass * SparseMatrix(Eigen::kroneckerProduct(m, m)) +
                   SparseMatrix(Eigen::kroneckerProduct(k1, m)) +
                   SparseMatrix(Eigen::kroneckerProduct(m, k1));
  if (bending != 0.0) {
    a += bending * (SparseMatrix(Eigen::kroneckerProduct(k2, m)) +
                    2.0 * SparseMatrix(Eigen::kroneckerProduct(k1, k1)) +
                    SparseMatrix(Eigen::kroneckerProduct(m, k2)));
  }
  a.makeCompressed();
  return a;
}

// A = R^T R + shift I with R n by n sparse random (about `per_column` entries per column): SPD
// with an irregular pattern.
inline SparseMatrix random_spd(int n, int per_column, unsigned seed, double shift = 0.1) {
  std::mt19937 engine(seed);
  std::uniform_int_distribution<int> row(0, n - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < n; ++j) {
    for (int p = 0; p < per_column; ++p) {
      entries.emplace_back(row(engine), j, value(engine));
    }
  }
  SparseMatrix r(n, n);
  r.setFromTriplets(entries.begin(), entries.end());
  SparseMatrix identity(n, n);
  identity.setIdentity();
  SparseMatrix a = SparseMatrix(r.transpose() * r) + shift * identity;
  a.makeCompressed();
  return a;
}

inline Eigen::MatrixXd random_block(Eigen::Index rows, Eigen::Index cols, unsigned seed) {
  std::mt19937 engine(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::MatrixXd b(rows, cols);
  for (Eigen::Index i = 0; i < b.size(); ++i) {
    b.data()[i] = value(engine);
  }
  return b;
}

// The lower triangle of a mirrored into a dense long double matrix.
inline Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic> dense_symmetric(
    const SparseMatrix& a) {
  Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic> d =
      Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>::Zero(a.rows(), a.cols());
  for (Eigen::Index j = 0; j < a.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(a, j); it; ++it) {
      if (it.row() >= j) {
        d(it.row(), j) = it.value();
        d(j, it.row()) = it.value();
      }
    }
  }
  return d;
}

using MatrixL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;

// Reference solution of A X = B (A: the lower triangle of a, plus the dense term `extra`):
// dense LL^T in long double (64-bit mantissa, unit roundoff 5.4e-20) and three steps of iterative
// refinement with long double residuals, so its error is about 1e-19 cond(A) before refinement
// and far below double rounding after it for every matrix here (cond(A) <= 1e12). B is given in
// long double so that a right-hand side with terms of very different size (a stiff spring's
// pull k u t^T) is not rounded to double first.
inline Eigen::MatrixXd reference_solve(const SparseMatrix& a, const MatrixL& b,
                                       const MatrixL& extra = {}) {
  MatrixL dense = dense_symmetric(a);
  if (extra.size() > 0) {
    dense += extra;
  }
  const Eigen::LLT<MatrixL> llt(dense);
  MatrixL x = llt.solve(b);
  for (int step = 0; step < 3; ++step) {
    x += llt.solve(MatrixL(b - dense * x));
  }
  return x.cast<double>();
}

inline Eigen::MatrixXd reference_solve(const SparseMatrix& a, const Eigen::MatrixXd& b,
                                       const MatrixL& extra = {}) {
  return reference_solve(a, MatrixL(b.cast<long double>()), extra);
}

// Reference solution of (A + U K U^T) X = B + U K T for m rank-one terms (U n by m, K = diag(k),
// T m by #columns): the Woodbury identity evaluated in long double,
// X = Y + W C^{-1} (T - U^T Y) with Y = A^{-1} B, W = A^{-1} U, C = K^{-1} + U^T W (exact in exact
// arithmetic; low_rank_update.cpp derives it). Its rounding is about 1e-19 cond(A) cond(C),
// independent of k, whereas the dense solve above loses 1e-19 cond(A + U K U^T) ~ 1e-19 k: with
// k = 1e8 diag(A) that is 1e-10 (both measured in test_low_rank_update.cpp).
inline Eigen::MatrixXd reference_with_terms(const SparseMatrix& a, const MatrixL& b,
                                            const MatrixL& u, const std::vector<long double>& k,
                                            const MatrixL& t) {
  const MatrixL dense = dense_symmetric(a);
  const Eigen::LLT<MatrixL> llt(dense);
  const auto refined = [&](const MatrixL& rhs) {
    MatrixL x = llt.solve(rhs);
    for (int step = 0; step < 3; ++step) {
      x += llt.solve(MatrixL(rhs - dense * x));
    }
    return x;
  };
  const MatrixL y = refined(b);
  const MatrixL w = refined(u);
  MatrixL c = u.transpose() * w;
  for (Eigen::Index i = 0; i < c.rows(); ++i) {
    c(i, i) += 1.0L / k[static_cast<size_t>(i)];
  }
  const MatrixL x = y + w * c.llt().solve(MatrixL(t - u.transpose() * y));
  return x.cast<double>();
}

inline double relative_error(const Eigen::MatrixXd& x, const Eigen::MatrixXd& reference) {
  return (x - reference).norm() / reference.norm();
}

}  // namespace dnurbs::testing
