#include "dnurbs/surface/grid_difference_operators.h"

#include <vector>

#include "dnurbs/core/error.h"

namespace dnurbs {

GridDifferenceOperators grid_difference_operators(const Grid& grid) {
  if (grid.nu() < 3 || grid.nv() < 3) {
    throw make_error("finite differences need a grid of at least 3 by 3 nodes, not ", grid.nu(),
                     " by ", grid.nv());
  }
  const int n = grid.node_count();
  const int nu = grid.nu();
  const int nv = grid.nv();
  const double h = grid.spacing();
  using Triplets = std::vector<Eigen::Triplet<double>>;
  Triplets d1, d2, d11, d22, d12, t1, t2;
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const int k = grid.index(i, j);
      if (i + 1 < nu) {
        d1.emplace_back(k, grid.index(i + 1, j), 1.0 / h);
        d1.emplace_back(k, k, -1.0 / h);
      }
      if (j + 1 < nv) {
        d2.emplace_back(k, grid.index(i, j + 1), 1.0 / h);
        d2.emplace_back(k, k, -1.0 / h);
      }
      if (i > 0 && i + 1 < nu) {
        d11.emplace_back(k, grid.index(i - 1, j), 1.0 / (h * h));
        d11.emplace_back(k, k, -2.0 / (h * h));
        d11.emplace_back(k, grid.index(i + 1, j), 1.0 / (h * h));
      }
      if (j > 0 && j + 1 < nv) {
        d22.emplace_back(k, grid.index(i, j - 1), 1.0 / (h * h));
        d22.emplace_back(k, k, -2.0 / (h * h));
        d22.emplace_back(k, grid.index(i, j + 1), 1.0 / (h * h));
      }
      if (i + 1 < nu && j + 1 < nv) {
        d12.emplace_back(k, grid.index(i + 1, j + 1), 1.0 / (h * h));
        d12.emplace_back(k, grid.index(i + 1, j), -1.0 / (h * h));
        d12.emplace_back(k, grid.index(i, j + 1), -1.0 / (h * h));
        d12.emplace_back(k, k, 1.0 / (h * h));
      }
      // Tangents: central inside, one-sided on the border.
      const int i_minus = i > 0 ? i - 1 : i;
      const int i_plus = i + 1 < nu ? i + 1 : i;
      t1.emplace_back(k, grid.index(i_plus, j), 1.0 / ((i_plus - i_minus) * h));
      t1.emplace_back(k, grid.index(i_minus, j), -1.0 / ((i_plus - i_minus) * h));
      const int j_minus = j > 0 ? j - 1 : j;
      const int j_plus = j + 1 < nv ? j + 1 : j;
      t2.emplace_back(k, grid.index(i, j_plus), 1.0 / ((j_plus - j_minus) * h));
      t2.emplace_back(k, grid.index(i, j_minus), -1.0 / ((j_plus - j_minus) * h));
    }
  }
  GridDifferenceOperators operators;
  const auto build = [n](Eigen::SparseMatrix<double>& matrix, const Triplets& triplets) {
    matrix.resize(n, n);
    matrix.setFromTriplets(triplets.begin(), triplets.end());
    matrix.makeCompressed();
  };
  build(operators.d1, d1);
  build(operators.d2, d2);
  build(operators.d11, d11);
  build(operators.d22, d22);
  build(operators.d12, d12);
  build(operators.t1, t1);
  build(operators.t2, t2);
  return operators;
}

}  // namespace dnurbs
