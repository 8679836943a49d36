#include "dnurbs/core/sparse_cholesky.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <new>
#include <string>

#include "dnurbs/core/error.h"
#include "tests/common/allocation_counter.h"
#include "tests/core/core_test_helpers.h"

namespace dnurbs {
namespace {

using testing::random_block;
using testing::random_spd;
using testing::reference_solve;
using testing::relative_error;
using testing::sheet_matrix;
using testing::SparseMatrix;

std::string backend_name(const ::testing::TestParamInfo<CholeskyBackend>& info) {
  return info.param == CholeskyBackend::kSimplicialLdlt ? "SimplicialLdlt" : "CholmodSupernodal";
}

class SparseCholeskyBackend : public ::testing::TestWithParam<CholeskyBackend> {
 protected:
  SparseCholesky make() const { return SparseCholesky({GetParam(), 0}); }
};

// The largest and smallest eigenvalue ratio, to put each tolerance next to eps cond(A).
double condition_number(const SparseMatrix& a) {
  const Eigen::MatrixXd dense = testing::dense_symmetric(a).cast<double>();
  const Eigen::VectorXd eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense).eigenvalues();
  return eigenvalues.maxCoeff() / eigenvalues.minCoeff();
}

TEST_P(SparseCholeskyBackend, SolvesBicubicSheetToDenseReference) {
  // 20 x 20 bicubic sheet: 400 unknowns, 49 entries per inner column; mass dominated (a step
  // matrix M/dt^2 + K) and stiffness dominated.
  for (const double mass : {100.0, 1e-3}) {
    const SparseMatrix a = sheet_matrix(20, mass);
    const Eigen::MatrixXd b = random_block(a.rows(), 3, 11);
    SparseCholesky cholesky = make();
    cholesky.factorize(a);
    const Eigen::MatrixXd x = cholesky.solve(b);
    const double error = relative_error(x, reference_solve(a, b));
    std::printf("mass %g: cond %.1e, relative error %.1e\n", mass, condition_number(a), error);
    // Backward-stable Cholesky: forward error <= c n eps cond(A) with cond 2.4e2 and 26 here;
    // measured 4.2e-15 and 9.0e-16 (SimplicialLDLT), 1.8e-15 and 4.7e-16 (CHOLMOD).
    EXPECT_LT(error, 1e-12);
    EXPECT_EQ(cholesky.backend(), GetParam());
  }
}

TEST_P(SparseCholeskyBackend, SolvesRandomSparseSpdToDenseReference) {
  // Irregular pattern (R^T R, 4 random entries per column of R): fill-reducing orderings differ
  // from the banded case. The shift sets the conditioning.
  for (const double shift : {0.1, 1e-5}) {
    const SparseMatrix a = random_spd(300, 4, 5, shift);
    const Eigen::MatrixXd b = random_block(a.rows(), 2, 12);
    SparseCholesky cholesky = make();
    cholesky.factorize(a);
    const double error = relative_error(cholesky.solve(b), reference_solve(a, b));
    const double cond = condition_number(a);
    std::printf("shift %g: cond %.1e, relative error %.1e\n", shift, cond, error);
    // Forward error <= c n eps cond(A): cond 72 and 7.1e5, measured 1.6e-15 and 6.6e-12
    // (SimplicialLDLT), 1.1e-15 and 5.1e-12 (CHOLMOD); the bound is 1e-15 cond, at least 1e-12.
    EXPECT_LT(error, std::max(1e-12, 1e-15 * cond));
  }
}

TEST_P(SparseCholeskyBackend, ReadsOnlyTheLowerTriangle) {
  // Upper triangle replaced by garbage: the solution must not change at all.
  const SparseMatrix full = sheet_matrix(8);
  SparseMatrix garbled(full.rows(), full.cols());
  garbled = full;
  for (Eigen::Index j = 0; j < garbled.outerSize(); ++j) {
    for (int p = garbled.outerIndexPtr()[j]; p < garbled.outerIndexPtr()[j + 1]; ++p) {
      if (garbled.innerIndexPtr()[p] < j) {
        garbled.valuePtr()[p] = -1e3;
      }
    }
  }
  const SparseMatrix lower = full.triangularView<Eigen::Lower>();
  const Eigen::MatrixXd b = random_block(full.rows(), 3, 13);
  SparseCholesky from_full = make(), from_garbled = make(), from_lower = make();
  from_full.factorize(full);
  from_garbled.factorize(garbled);
  from_lower.factorize(lower);
  const Eigen::MatrixXd x = from_full.solve(b);
  EXPECT_EQ((from_garbled.solve(b) - x).norm(), 0.0);
  // The lower-only matrix has another pattern (so maybe another ordering): equal to rounding,
  // a few eps times cond(A) ~ 7.
  EXPECT_LT(relative_error(from_lower.solve(b), x), 1e-14);
}

TEST_P(SparseCholeskyBackend, MultipleRightHandSidesEqualColumnByColumn) {
  const SparseMatrix a = sheet_matrix(15);
  const Eigen::MatrixXd b = random_block(a.rows(), 5, 14);
  SparseCholesky cholesky = make();
  cholesky.factorize(a);
  Eigen::MatrixXd together = b;
  cholesky.solve_in_place(together);
  for (Eigen::Index c = 0; c < b.cols(); ++c) {
    Eigen::MatrixXd column = b.col(c);
    cholesky.solve_in_place(column);
    // Multi-column kernels (CHOLMOD's dtrsm, the simplicial interleaved loop) add the same
    // products per column; only BLAS blocking may reorder sums: rounding, ~1e-16 relative.
    EXPECT_LT((together.col(c) - column).norm() / column.norm(), 1e-14) << "column " << c;
  }
}

TEST_P(SparseCholeskyBackend, ReusesAnalysisAcrossNumericRefactorizations) {
  const SparseMatrix a = sheet_matrix(12, 100.0);
  const SparseMatrix a2 = sheet_matrix(12, 3.0, 0.5);  // same pattern, other values
  const Eigen::MatrixXd b = random_block(a.rows(), 3, 15);
  SparseCholesky cholesky = make();
  cholesky.factorize(a);
  EXPECT_EQ(cholesky.analysis_count(), 1);
  EXPECT_LT(relative_error(cholesky.solve(b), reference_solve(a, b)), 1e-12);
  cholesky.factorize(a2);
  EXPECT_EQ(cholesky.analysis_count(), 1);
  // cond(a2) ~ 1e3: 1e-12 keeps a margin of 1e2 over eps cond.
  EXPECT_LT(relative_error(cholesky.solve(b), reference_solve(a2, b)), 1e-12);
  // Another pattern (a lower triangle only) is detected and analyzed anew.
  const SparseMatrix lower = a.triangularView<Eigen::Lower>();
  cholesky.factorize(lower);
  EXPECT_EQ(cholesky.analysis_count(), 2);
  EXPECT_LT(relative_error(cholesky.solve(b), reference_solve(a, b)), 1e-12);
}

TEST_P(SparseCholeskyBackend, NotPositiveDefiniteNamesTheColumn) {
  // Diagonal matrix with a negative entry in column 7: whatever the ordering, column 7 fails.
  SparseMatrix d(12, 12);
  for (int i = 0; i < 12; ++i) {
    d.insert(i, i) = i == 7 ? -2.0 : 1.0 + i;
  }
  SparseCholesky cholesky = make();
  try {
    cholesky.factorize(d);
    FAIL() << "no error for a negative diagonal";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not positive definite"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("column 7 "), std::string::npos) << e.what();
  }
  EXPECT_FALSE(cholesky.is_factored());
  EXPECT_THROW(cholesky.solve(Eigen::MatrixXd::Ones(12, 1)), Error);
  // Coupling columns 4 and 5 of an SPD sheet by 2 sqrt(a44 a55) makes their 2 x 2 block
  // indefinite and leaves every block without both positive definite: the failing pivot is the
  // later of the two in elimination order, column 4 or 5.
  SparseMatrix indefinite = sheet_matrix(4);
  const double coupling = 2.0 * std::sqrt(indefinite.coeff(4, 4) * indefinite.coeff(5, 5));
  indefinite.coeffRef(5, 4) = coupling;
  indefinite.coeffRef(4, 5) = coupling;
  try {
    cholesky.factorize(indefinite);
    FAIL() << "no error for an indefinite matrix";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_TRUE(message.find("column 4 ") != std::string::npos ||
                message.find("column 5 ") != std::string::npos)
        << message;
  }
}

TEST_P(SparseCholeskyBackend, NonFiniteEntriesAreNamed) {
  SparseMatrix a = sheet_matrix(5);
  a.coeffRef(3, 2) = std::numeric_limits<double>::quiet_NaN();
  SparseCholesky cholesky = make();
  try {
    cholesky.factorize(a);
    FAIL() << "no error for NaN";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("entry (3, 2) of the matrix is nan"), std::string::npos)
        << e.what();
  }
  cholesky.factorize(sheet_matrix(5));
  Eigen::MatrixXd b = Eigen::MatrixXd::Ones(25, 3);
  b(9, 1) = std::numeric_limits<double>::infinity();
  try {
    cholesky.solve_in_place(b);
    FAIL() << "no error for an infinite right-hand side";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("entry (9, 1) of the right-hand side is inf"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(cholesky.solve(Eigen::MatrixXd::Ones(24, 3)), Error);  // rows do not match
  EXPECT_THROW(cholesky.factorize(SparseMatrix(4, 5)), Error);        // not square
}

// The first-derivative Gram kernel of the cardinal cubic B-spline with the diagonal of its
// boundary rows set so that every row sums to zero (as the stiffness of clamped knots does): a
// weighted graph Laplacian, positive semidefinite, null space the constants.
SparseMatrix derivative_laplacian(int size) {
  constexpr double kFirst[4] = {2.0 / 3.0, -1.0 / 8.0, -1.0 / 5.0, -1.0 / 120.0};
  SparseMatrix k1 = testing::banded_toeplitz(size, kFirst);
  for (int i = 0; i < size; ++i) {
    k1.coeffRef(i, i) -= Eigen::VectorXd(k1.col(i)).sum();
  }
  return k1;
}

TEST_P(SparseCholeskyBackend, SingularSemidefiniteIsRejectedOrFlagged) {
  // Pure stiffness without mass: L (x) M + M (x) L annihilates the constant vector (a free sheet
  // translates). The documented outcome: an Error, or a factorization whose reciprocal condition
  // estimate sits at rounding level.
  constexpr double kMass[4] = {151.0 / 315.0, 397.0 / 1680.0, 1.0 / 42.0, 1.0 / 5040.0};
  const SparseMatrix m = testing::banded_toeplitz(10, kMass);
  const SparseMatrix l = derivative_laplacian(10);
  const SparseMatrix k =
      SparseMatrix(Eigen::kroneckerProduct(l, m)) + SparseMatrix(Eigen::kroneckerProduct(m, l));
  ASSERT_LT((k * Eigen::VectorXd::Ones(100)).norm(), 1e-14);  // singular indeed
  SparseCholesky cholesky = make();
  bool threw = false;
  try {
    cholesky.factorize(k);
  } catch (const Error& e) {
    threw = true;
    EXPECT_NE(std::string(e.what()).find("not positive definite"), std::string::npos);
  }
  // Measured: both backends factor it, with estimates 1.5e-14 (SimplicialLDLT) and 8.7e-15
  // (CHOLMOD): rounding leaves the last pivot about 100 eps times the largest, 7x below 1e-13.
  if (!threw) {
    std::printf("singular matrix factored; reciprocal condition estimate %.2e\n",
                cholesky.reciprocal_condition_estimate());
    EXPECT_LT(cholesky.reciprocal_condition_estimate(), 1e-13);
  }
  // The same stiffness plus a small mass is fine and its estimate is far from rounding level.
  cholesky.factorize(k + 1e-2 * SparseMatrix(Eigen::kroneckerProduct(m, m)));
  EXPECT_GT(cholesky.reciprocal_condition_estimate(), 1e-6);
}

TEST_P(SparseCholeskyBackend, SolveAllocatesNothingAfterTheFirst) {
  const SparseMatrix a = sheet_matrix(12);
  SparseCholesky cholesky = make();
  cholesky.factorize(a);
  Eigen::MatrixXd b = random_block(a.rows(), 3, 16);
  cholesky.solve_in_place(b);  // first solve of width 3: workspace
  testing::allocations = 0;
  testing::count_allocations = true;
  cholesky.solve_in_place(b);
  cholesky.solve_in_place(b.leftCols(2));  // narrower: fits the workspace
  testing::count_allocations = false;
  // operator new only (CHOLMOD's own malloc is not seen here: its supernodal triangular solves
  // take caller workspace and allocate nothing, "workspace: none" in cholmod_super_solve.c).
  EXPECT_EQ(testing::allocations.load(), 0);
}

INSTANTIATE_TEST_SUITE_P(Backends, SparseCholeskyBackend,
                         ::testing::Values(CholeskyBackend::kSimplicialLdlt,
                                           CholeskyBackend::kCholmodSupernodal),
                         backend_name);

TEST(SparseCholesky, AutomaticBackendFollowsTheThreshold) {
  const SparseMatrix a = sheet_matrix(10);  // 100 rows
  SparseCholesky below({CholeskyBackend::kAutomatic, 101});
  below.factorize(a);
  EXPECT_EQ(below.backend(), CholeskyBackend::kSimplicialLdlt);
  SparseCholesky at({CholeskyBackend::kAutomatic, 100});
  at.factorize(a);
  EXPECT_EQ(at.backend(), CholeskyBackend::kCholmodSupernodal);
  const Eigen::MatrixXd b = random_block(100, 3, 17);
  // Both backends solve the same system: equal to rounding (cond ~ 7).
  EXPECT_LT(relative_error(below.solve(b), at.solve(b)), 1e-14);
  EXPECT_THROW(SparseCholesky({CholeskyBackend::kAutomatic, -1}), Error);
}

TEST(SparseCholesky, RankUpdateNeedsCholmod) {
  const SparseMatrix a = sheet_matrix(4);
  SparseCholesky cholesky({CholeskyBackend::kSimplicialLdlt, 0});
  cholesky.factorize(a);
  SparseMatrix c(16, 1);
  c.insert(3, 0) = 1.0;
  EXPECT_THROW(cholesky.rank_update(c, false), Error);
}

}  // namespace
}  // namespace dnurbs
