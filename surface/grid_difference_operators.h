#pragma once
// Finite-difference operators on a regular (u, v) grid (Wu & de Melo, section 4, "Standard finite
// difference approximation as suggested by Terzopoulos et al."), as sparse node-by-node
// matrices acting on node fields (one column per coordinate). A difference that would reach a
// node outside the grid is not computable: its row is zero (a free edge).

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "dnurbs/surface/grid.h"

namespace dnurbs {

/// Every operator is #nodes by #nodes; applied to #nodes by 3 positions it gives the
/// derivative estimate at each node.
struct GridDifferenceOperators {
  /// Forward differences D+_1 r = (r[i+1,j] - r[i,j]) / h and D+_2 (zero rows at i = nu-1,
  /// resp. j = nv-1).
  Eigen::SparseMatrix<double> d1, d2;
  /// Central second differences D+_11 r = (r[i+1,j] - 2 r[i,j] + r[i-1,j]) / h^2 and D+_22
  /// (zero rows on the border in that direction).
  Eigen::SparseMatrix<double> d11, d22;
  /// Forward cross difference D+_12 r = D+_1 D+_2 r
  /// = (r[i+1,j+1] - r[i+1,j] - r[i,j+1] + r[i,j]) / h^2 (zero rows at i = nu-1 or j = nv-1).
  Eigen::SparseMatrix<double> d12;
  /// Tangent estimates for normals and metric coefficients of the geometry: central first
  /// differences inside, one-sided on the border (no zero rows).
  Eigen::SparseMatrix<double> t1, t2;
};

/// The operators of a grid (nu, nv >= 3).
GridDifferenceOperators grid_difference_operators(const Grid& grid);

}  // namespace dnurbs
