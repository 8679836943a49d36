#include "dnurbs/core/cholmod_factor.h"

#include <gtest/gtest.h>

#include <string>

#include "dnurbs/core/error.h"
#include "tests/core/core_test_helpers.h"

namespace dnurbs {
namespace {

using testing::random_block;
using testing::reference_solve;
using testing::relative_error;
using testing::sheet_matrix;
using testing::SparseMatrix;

// C: r sparse columns with `per_column` random entries each, scaled by `scale`.
SparseMatrix random_columns(int n, int r, int per_column, double scale, unsigned seed) {
  const Eigen::MatrixXd values = random_block(per_column, r, seed);
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < r; ++j) {
    for (int p = 0; p < per_column; ++p) {
      entries.emplace_back((7 * p + 13 * j + 5) % n, j, scale * values(p, j));
    }
  }
  SparseMatrix c(n, r);
  c.setFromTriplets(entries.begin(), entries.end());
  return c;
}

Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic> outer(const SparseMatrix& c) {
  const Eigen::MatrixXd dense = Eigen::MatrixXd(c);
  return (dense * dense.transpose()).cast<long double>();
}

TEST(CholmodFactor, BlasIsLimitedOnceAndReportsOpenBlas) {
  // scripts/install_dependencies.sh installs libopenblas-dev, which makes OpenBLAS the
  // libblas.so.3 that CHOLMOD loads: the thread setting must be found.
  EXPECT_TRUE(limit_blas_to_one_thread());
  EXPECT_TRUE(limit_blas_to_one_thread());  // later calls: same answer, no second call
}

TEST(CholmodFactor, RankUpdateEqualsFactorizationOfTheUpdatedMatrix) {
  const SparseMatrix a = sheet_matrix(12);  // 144 unknowns, cond ~ 7
  const SparseMatrix c = random_columns(144, 3, 16, 5.0, 21);
  const Eigen::MatrixXd b = random_block(144, 3, 22);
  CholmodFactor factor;
  factor.analyze(a);
  factor.factorize(a);
  EXPECT_TRUE(factor.is_supernodal());
  factor.rank_update(c, /*downdate=*/false);
  EXPECT_FALSE(factor.is_supernodal());  // converted to simplicial L D L^T
  Eigen::MatrixXd x = b;
  factor.solve_in_place(x);
  // cond(A + C C^T) stays below 1e3 for these entries (|C| <= 5 against a diagonal ~23): the
  // update is backward stable like a factorization, so 1e-12 is c eps cond with a margin.
  EXPECT_LT(relative_error(x, reference_solve(a, b, outer(c))), 1e-12);
  // Downdating the same C returns to A.
  factor.rank_update(c, /*downdate=*/true);
  x = b;
  factor.solve_in_place(x);
  EXPECT_LT(relative_error(x, reference_solve(a, b)), 1e-12);
  // A new numeric factorization goes back to supernodal (same ordering, new symbolic analysis).
  factor.factorize(a);
  EXPECT_TRUE(factor.is_supernodal());
  x = b;
  factor.solve_in_place(x);
  EXPECT_LT(relative_error(x, reference_solve(a, b)), 1e-12);
}

TEST(CholmodFactor, DowndateBelowPositiveDefiniteThrows) {
  const SparseMatrix a = sheet_matrix(6);
  CholmodFactor factor;
  factor.factorize(a);
  // e_10 e_10^T scaled past a's diagonal entry 10: A - C C^T has a negative diagonal entry.
  SparseMatrix c(36, 1);
  c.insert(10, 0) = 2.0 * std::sqrt(a.coeff(10, 10));
  try {
    factor.rank_update(c, /*downdate=*/true);
    FAIL() << "no error for a downdate below positive definite";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not positive definite"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(factor.is_factored());
  Eigen::MatrixXd b = Eigen::MatrixXd::Ones(36, 1);
  EXPECT_THROW(factor.solve_in_place(b), Error);
}

TEST(CholmodFactor, InputErrorsAreNamed) {
  CholmodFactor factor;
  EXPECT_THROW(factor.analyze(SparseMatrix(3, 4)), Error);
  Eigen::MatrixXd b = Eigen::MatrixXd::Ones(3, 1);
  EXPECT_THROW(factor.solve_in_place(b), Error);  // nothing factored
  factor.factorize(sheet_matrix(3));
  b = Eigen::MatrixXd::Ones(8, 1);
  EXPECT_THROW(factor.solve_in_place(b), Error);  // 8 rows against 9
  EXPECT_THROW(factor.rank_update(SparseMatrix(8, 1), false), Error);
}

}  // namespace
}  // namespace dnurbs
