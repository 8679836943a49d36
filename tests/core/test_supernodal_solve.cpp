// Tests of core/supernodal_solve.h: forward and backward substitution with a supernodal factor,
// node-major, for 1 to 4 right-hand sides: on hand-made factors against Eigen's dense Cholesky,
// and through CholmodFactor against CHOLMOD's own BLAS solve on the factors of grid matrices
// (supernodes of one to hundreds of columns, rows below them scattered), generic and AVX2 code.

#include "dnurbs/core/supernodal_solve.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "dnurbs/core/cholmod_factor.h"
#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

RowMajor random_rows(Eigen::Index n, Eigen::Index k, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  return RowMajor::NullaryExpr(n, k, [&](Eigen::Index, Eigen::Index) { return uniform(random); });
}

// A hand-made supernodal layout of a dense lower-triangular L (n = 7) with two supernodes:
// columns 0..4 with rows {0, 1, 2, 3, 4, 6} (row 5 of those columns is zero in L), and columns
// 5..6 with rows {5, 6}. The first has a group of four columns and one left over, and a row below
// its diagonal block that is not the next one.
struct HandMadeFactor {
  Eigen::MatrixXd l = Eigen::MatrixXd::Zero(7, 7);
  std::vector<int> first_column{0, 5, 7};
  std::vector<int> row_start{0, 6, 8};
  std::vector<int> value_start{0, 30};
  std::vector<int> rows{0, 1, 2, 3, 4, 6, 5, 6};
  std::vector<double> values;

  HandMadeFactor() {
    std::mt19937 random(3);
    std::uniform_real_distribution<double> uniform(-0.5, 0.5);
    for (int j = 0; j < 7; ++j) {
      l(j, j) = 1.0 + j * 0.25;
      for (int i = j + 1; i < 7; ++i) {
        if (!(j < 5 && i == 5)) {
          l(i, j) = uniform(random);
        }
      }
    }
    for (int s = 0; s < 2; ++s) {
      for (int j = first_column[s]; j < first_column[s + 1]; ++j) {
        for (int p = row_start[s]; p < row_start[s + 1]; ++p) {
          // the strict upper triangle of the diagonal block is stored but never read
          values.push_back(rows[p] >= j ? l(rows[p], j) : std::nan(""));
        }
      }
    }
  }

  SupernodalFactor view() const {
    return SupernodalFactor{
        2, first_column.data(), row_start.data(), value_start.data(), rows.data(), values.data(),
        6};
  }
};

TEST(SupernodalSolve, HandMadeFactorSolvesLLTransposeLikeDenseCholesky) {
  const HandMadeFactor factor;
  const Eigen::MatrixXd a = factor.l * factor.l.transpose();
  for (const bool vectorize : {false, true}) {
    for (int k = 1; k <= kSupernodalSolveMaxColumns; ++k) {
      const RowMajor b = random_rows(7, k, 10 + k);
      RowMajor y = b;
      std::vector<double> workspace;
      supernodal_solve(factor.view(), k, y.data(), workspace, vectorize);
      const Eigen::MatrixXd expected = a.llt().solve(Eigen::MatrixXd(b));
      EXPECT_LT((Eigen::MatrixXd(y) - expected).cwiseAbs().maxCoeff(),
                1e-13 * expected.cwiseAbs().maxCoeff())
          << k << " columns, vectorize " << vectorize;
      EXPECT_LT((a * Eigen::MatrixXd(y) - Eigen::MatrixXd(b)).norm(), 1e-13 * b.norm());
    }
  }
}

TEST(SupernodalSolve, ColumnsOutsideOneToFourThrow) {
  const HandMadeFactor factor;
  RowMajor y = random_rows(7, 5, 1);
  std::vector<double> workspace;
  EXPECT_THROW(supernodal_solve(factor.view(), 0, y.data(), workspace), Error);
  EXPECT_THROW(supernodal_solve(factor.view(), 5, y.data(), workspace), Error);
}

// The scalar matrix of a side x side grid with a 7 x 7 stencil (the pattern of a bicubic sheet's
// step matrix), diagonally dominant: well conditioned, so both solves agree to rounding.
CholmodFactor::SparseMatrix grid_matrix(int side, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const int n = side * side;
  std::vector<Eigen::Triplet<double>> triplets;
  for (int p = 0; p < n; ++p) {
    for (int q = 0; q <= p; ++q) {
      if (std::abs(p / side - q / side) > 3 || std::abs(p % side - q % side) > 3) {
        continue;
      }
      const double value = p == q ? 60.0 : 0.5 * uniform(random);
      triplets.emplace_back(p, q, value);
      if (p != q) {
        triplets.emplace_back(q, p, value);
      }
    }
  }
  CholmodFactor::SparseMatrix a(n, n);
  a.setFromTriplets(triplets.begin(), triplets.end());
  return a;
}

TEST(SupernodalSolve, PanelSolveEqualsCholmodsBlasSolveOnGridMatrices) {
  for (const int side : {3, 12, 40}) {
    const CholmodFactor::SparseMatrix a = grid_matrix(side, 7);
    CholmodFactor panels(TriangularSolve::kPanels);
    CholmodFactor blas(TriangularSolve::kBlas);
    panels.factorize(a);
    blas.factorize(a);
    ASSERT_TRUE(panels.is_supernodal());
    for (const int k : {1, 2, 3, 4, 6}) {  // 6: wider than the panels take, CHOLMOD's solve
      const Eigen::MatrixXd b = random_rows(a.rows(), k, 20 + k);
      Eigen::MatrixXd from_panels = b;
      Eigen::MatrixXd from_blas = b;
      panels.solve_in_place(from_panels);
      blas.solve_in_place(from_blas);
      // cond(A) is below 2 (Gershgorin: 60 +- 24): the two orders of the same sums differ by a
      // few rounding units of the solution
      EXPECT_LT((from_panels - from_blas).cwiseAbs().maxCoeff(),
                1e-14 * from_blas.cwiseAbs().maxCoeff())
          << "side " << side << ", " << k << " columns";
      EXPECT_LT((a * from_panels - b).norm(), 1e-14 * b.norm());
    }
  }
}

TEST(SupernodalSolve, GenericAndVectorizedCodeAgreeOnCholmodsFactor) {
  if (!supernodal_solve_vectorized()) {
    GTEST_SKIP() << "this processor has no AVX2 and FMA: only the generic code runs";
  }
  // Supernodes of up to hundreds of columns (the separators of a 30 x 30 grid), solved in L's
  // row order by both codes
  CholmodFactor factor;
  factor.factorize(grid_matrix(30, 5));
  const SupernodalFactor view = factor.supernodal_factor();
  EXPECT_GT(view.largest_row_count, 60);
  for (int k = 1; k <= kSupernodalSolveMaxColumns; ++k) {
    RowMajor generic = random_rows(factor.size(), k, 30 + k);
    RowMajor vectorized = generic;
    std::vector<double> workspace;
    supernodal_solve(view, k, generic.data(), workspace, /*vectorize=*/false);
    supernodal_solve(view, k, vectorized.data(), workspace, /*vectorize=*/true);
    EXPECT_LT((generic - vectorized).cwiseAbs().maxCoeff(), 1e-14 * generic.cwiseAbs().maxCoeff())
        << k << " columns";
  }
}

TEST(SupernodalSolve, FactorViewNeedsASupernodalFactor) {
  CholmodFactor factor;
  EXPECT_THROW(static_cast<void>(factor.supernodal_factor()), Error);
}

}  // namespace
}  // namespace dnurbs
