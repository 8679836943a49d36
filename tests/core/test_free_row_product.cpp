// Tests of core/free_row_product.h: r -= K X + D V + M A on the free rows in one pass over the
// merged pattern equals three separate sparse products restricted to the free rows, leaves the
// fixed rows untouched, takes rows (not columns) of an unsymmetric matrix, and rejects bad input.

#include "dnurbs/core/free_row_product.h"

#include <array>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

using NodeMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// A random n by n sparse matrix with the pattern of a banded stencil (|i - j| <= band, every
// `skip`-th off-diagonal left out so that patterns differ), symmetric when `symmetric`.
SparseMatrix random_matrix(int n, int band, int skip, bool symmetric, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> triplets;
  for (int j = 0; j < n; ++j) {
    for (int i = std::max(0, j - band); i <= std::min(n - 1, j + band); ++i) {
      if (i != j && skip > 0 && (i + j) % skip == 0) {
        continue;
      }
      if (symmetric && i < j) {
        continue;
      }
      const double value = uniform(random);
      triplets.emplace_back(i, j, value);
      if (symmetric && i != j) {
        triplets.emplace_back(j, i, value);
      }
    }
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(triplets.begin(), triplets.end());
  return a;
}

NodeMatrix random_nodes(int n, int columns, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  return NodeMatrix::NullaryExpr(n, columns,
                                 [&](Eigen::Index, Eigen::Index) { return uniform(random); });
}

// Every third row fixed.
std::vector<int> free_rows(int n) {
  std::vector<int> rows;
  for (int i = 0; i < n; ++i) {
    if (i % 3 != 1) {
      rows.push_back(i);
    }
  }
  return rows;
}

struct Case {
  int n = 40;
  int columns = 3;
  SparseMatrix k, d, m;
  NodeMatrix x, v, a, r;
};

Case make_case(int columns, bool symmetric) {
  Case c;
  c.columns = columns;
  c.k = random_matrix(c.n, 4, 0, symmetric, 1);
  c.d = random_matrix(c.n, 3, 5, symmetric, 2);  // a sub-pattern of K's
  c.m = random_matrix(c.n, 5, 7, symmetric, 3);  // wider than K's
  c.x = random_nodes(c.n, columns, 4);
  c.v = random_nodes(c.n, columns, 5);
  c.a = random_nodes(c.n, columns, 6);
  c.r = random_nodes(c.n, columns, 7);
  return c;
}

// Largest |difference| on the free rows relative to the largest |term|, and whether the fixed
// rows kept their values exactly.
void expect_matches(const Case& c, const NodeMatrix& result, const NodeMatrix& reference) {
  const std::vector<int> rows = free_rows(c.n);
  double difference = 0.0;
  for (const int i : rows) {
    difference = std::max(difference, (result.row(i) - reference.row(i)).cwiseAbs().maxCoeff());
  }
  // Each entry sums about 3 x 11 products of numbers in [-1, 1]: the one-pass sum and the three
  // separate products round differently, by a few 1e-16 times the sum's magnitude (<= 33).
  EXPECT_LT(difference / 33.0, 1e-15);
  for (int i = 0; i < c.n; ++i) {
    if (i % 3 == 1) {
      EXPECT_EQ(result.row(i), c.r.row(i)) << "fixed row " << i << " was written";
    }
  }
}

TEST(FreeRowProduct, EqualsThreeSeparateProductsOnTheFreeRows) {
  const Case c = make_case(3, true);
  const FreeRowProduct product({&c.k, &c.d, &c.m}, free_rows(c.n), 3);
  EXPECT_EQ(product.free_row_count(), static_cast<int>(free_rows(c.n).size()));
  NodeMatrix result = c.r;
  product.subtract({c.x.data(), c.v.data(), c.a.data()}, result.data());
  const NodeMatrix reference = c.r - c.k * c.x - c.d * c.v - c.m * c.a;
  expect_matches(c, result, reference);
}

TEST(FreeRowProduct, VectorizedAndScalarPassesAgreeToRounding) {
  // Both kernels for each combination of matrices, against the separate products; the last node
  // (row and column n - 1) is free, so the vectorized pass's masked load of it is exercised.
  const Case c = make_case(3, true);
  const FreeRowProduct scalar({&c.k, &c.d, &c.m}, free_rows(c.n), 3, /*vectorize=*/false);
  const FreeRowProduct fast({&c.k, &c.d, &c.m}, free_rows(c.n), 3);
  EXPECT_FALSE(scalar.vectorized());
  if (!fast.vectorized()) {
    GTEST_SKIP() << "this processor has no AVX2 and FMA: only the scalar pass runs";
  }
  const std::array<std::array<const double*, 3>, 3> inputs{{{c.x.data(), nullptr, nullptr},
                                                            {c.x.data(), c.v.data(), nullptr},
                                                            {c.x.data(), c.v.data(), c.a.data()}}};
  const std::array<NodeMatrix, 3> references{c.r - c.k * c.x, c.r - c.k * c.x - c.d * c.v,
                                             c.r - c.k * c.x - c.d * c.v - c.m * c.a};
  for (size_t k = 0; k < inputs.size(); ++k) {
    NodeMatrix from_scalar = c.r;
    NodeMatrix from_fast = c.r;
    scalar.subtract(inputs[k], from_scalar.data());
    fast.subtract(inputs[k], from_fast.data());
    expect_matches(c, from_fast, references[k]);
    expect_matches(c, from_scalar, references[k]);
  }
}

TEST(FreeRowProduct, SkippedMatricesAddNothing) {
  const Case c = make_case(3, true);
  const FreeRowProduct product({&c.k, &c.d, &c.m}, free_rows(c.n), 3);
  NodeMatrix without_mass = c.r;
  product.subtract({c.x.data(), c.v.data(), nullptr}, without_mass.data());
  expect_matches(c, without_mass, c.r - c.k * c.x - c.d * c.v);
  NodeMatrix stiffness_only = c.r;
  product.subtract({c.x.data(), nullptr, nullptr}, stiffness_only.data());
  expect_matches(c, stiffness_only, c.r - c.k * c.x);
  // An empty damping matrix (no non-zeros) is skipped even with a vector given
  const SparseMatrix empty(c.n, c.n);
  const FreeRowProduct no_damping({&c.k, &empty, nullptr}, free_rows(c.n), 3);
  NodeMatrix result = c.r;
  no_damping.subtract({c.x.data(), c.v.data(), c.a.data()}, result.data());
  expect_matches(c, result, c.r - c.k * c.x);
}

TEST(FreeRowProduct, UnsymmetricMatricesUseTheirRowsAndAnyColumnCount) {
  for (const int columns : {1, 2, 5}) {
    const Case c = make_case(columns, false);
    const FreeRowProduct product({&c.k, &c.d, &c.m}, free_rows(c.n), columns);
    NodeMatrix result = c.r;
    product.subtract({c.x.data(), c.v.data(), c.a.data()}, result.data());
    expect_matches(c, result, c.r - c.k * c.x - c.d * c.v - c.m * c.a);
  }
}

TEST(FreeRowProduct, MergedPatternHasOneEntryPerFreeRowAndColumn) {
  const Case c = make_case(3, true);
  const std::vector<int> rows = free_rows(c.n);
  const FreeRowProduct product({&c.k, &c.d, &c.m}, rows, 3);
  const SparseMatrix sum = (c.k.cwiseAbs() + c.d.cwiseAbs() + c.m.cwiseAbs()).pruned();
  int expected = 0;
  for (const int i : rows) {
    expected += static_cast<int>(sum.col(i).nonZeros());  // symmetric: column i = row i
  }
  EXPECT_EQ(product.entry_count(), expected);
}

TEST(FreeRowProduct, BadInputThrows) {
  const Case c = make_case(3, true);
  const SparseMatrix rectangular(c.n, c.n + 1);
  const SparseMatrix smaller(c.n - 1, c.n - 1);
  EXPECT_THROW(FreeRowProduct({&rectangular, nullptr, nullptr}, {0}, 3), Error);
  EXPECT_THROW(FreeRowProduct({&c.k, &smaller, nullptr}, {0}, 3), Error);
  EXPECT_THROW(FreeRowProduct({&c.k, nullptr, nullptr}, {2, 1}, 3), Error);
  EXPECT_THROW(FreeRowProduct({&c.k, nullptr, nullptr}, {0, c.n}, 3), Error);
  EXPECT_THROW(FreeRowProduct({&c.k, nullptr, nullptr}, {0}, 0), Error);
}

}  // namespace
}  // namespace dnurbs
