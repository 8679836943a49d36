#pragma once
// The step matrix of a state-dependent block (step_blocks.h), A = M + c_D D + c_K K on the block's
// free rows and columns, assembled straight from the model's matrices into a permuted pattern
// computed once and factored P A P^T = L D L^T with the symbolic analysis done once: a step
// that re-assembles M, D, K (free-weight D-NURBS) costs one pass over their values and the
// numeric factorization, and allocates nothing.
//
// analyze() (once per pattern): the fill-reducing ordering of the free block (approximate
// minimum degree, Amestoy, Davis & Duff, "An approximate minimum degree ordering algorithm",
// SIAM J. Matrix Anal. Appl. 17(4) 1996, as Eigen's AMDOrdering gives it, the ordering Eigen's
// SimplicialLDLT takes), the upper triangle of P A P^T as a compressed pattern with, for each of
// its entries, the value index of the model matrices that fills it, the elimination tree and the
// column counts of L (Davis, "Algorithm 849: A concise sparse Cholesky factorization package",
// ACM TOMS 31(4) 2005, ldl_symbolic).
// factorize() (every refactorization): the values of P A P^T from M, D, K in one pass, then the
// up-looking numeric factorization of the same paper (ldl_numeric) into the pre-sized L.
// solve(): P^T L^{-T} D^{-1} L^{-1} P r in a kept workspace.
//
// Supernodal mode (analyze with `supernodal`, for blocks above the supernodal threshold,
// core/sparse_cholesky.h): the same one-pass assembly into the lower triangle of A in the free
// unknowns' order, held as a compressed matrix whose pattern is fixed, factored and solved by
// CHOLMOD (core/cholmod_factor.h: its own ordering and symbolic analysis, done at the first
// factorization and kept).

#include <vector>

#include <Eigen/Core>

#include "dnurbs/core/cholmod_factor.h"
#include "dnurbs/core/fixed_coordinates.h"
#include "dnurbs/dynamics/core/model.h"

namespace dnurbs {

class LeanStepMatrix {
 public:
  /// Prepares for model matrices with the pattern of `matrices.mass` (n by n, compressed, both
  /// triangles stored, n = free.count()): false, and nothing prepared, unless the stiffness (and
  /// a non-empty damping) share that pattern exactly. `supernodal`: factor with CHOLMOD (see the
  /// file comment) instead of the up-looking L D L^T. Allocates; call when fits() is false.
  bool analyze(const ModelMatrices& matrices, const FreeCoordinates& free, bool supernodal);
  /// True if analyze() succeeded for matrices of exactly this pattern and mode (O(nnz)
  /// comparison).
  bool fits(const ModelMatrices& matrices, bool supernodal) const;

  /// A = M + c_D D + c_K K (D skipped when empty or c_D = 0) on the free rows, factored. Throws
  /// Error naming the free unknown if a pivot is not positive and finite (A must be symmetric
  /// positive definite); the factorization is then unusable until the next success. No
  /// allocation.
  void factorize(const ModelMatrices& matrices, double damping_coefficient,
                 double stiffness_coefficient);

  /// x[free] = A^{-1} r[free], r and x the block's vectors (n = free.count() entries each, from
  /// `r` and into `x`); x's fixed entries are left as they are. No allocation.
  void solve(const double* r, double* x);

  bool is_factored() const { return factored_; }
  bool is_supernodal() const { return supernodal_; }
  /// Symbolic analyses and numeric factorizations so far (tests check the reuse).
  int analysis_count() const { return analyses_; }
  int factorization_count() const { return factorizations_; }

 private:
  // Supernodal mode's analysis: lower_, source_ and unknown_of_ from the kept pattern.
  void analyze_lower(const FreeCoordinates& free);
  // The analyzed pattern of the model matrices (compared by fits()).
  std::vector<int> outer_;
  std::vector<int> inner_;
  // Free unknowns: the block index of permuted unknown k.
  std::vector<int> unknown_of_;
  // Upper triangle of P A P^T (compressed columns) and the model value index of each entry.
  std::vector<int> upper_start_;
  std::vector<int> upper_row_;
  std::vector<int> source_;
  std::vector<double> upper_value_;
  // L (strictly lower, compressed columns), D and 1 / D, the elimination tree and workspaces.
  std::vector<int> l_start_;
  std::vector<int> l_row_;
  std::vector<double> l_value_;
  std::vector<double> d_;
  std::vector<double> inverse_d_;
  std::vector<int> parent_;
  std::vector<int> l_count_;
  std::vector<int> flag_;
  std::vector<int> stack_;
  std::vector<double> work_;
  // Supernodal mode: the lower triangle of A on the free unknowns (values filled from source_),
  // CHOLMOD's factor and a solve column.
  SparseMatrix lower_;
  CholmodFactor cholmod_;
  Eigen::VectorXd column_;
  bool supernodal_ = false;
  bool analyzed_ = false;
  bool factored_ = false;
  int analyses_ = 0;
  int factorizations_ = 0;
};

}  // namespace dnurbs
