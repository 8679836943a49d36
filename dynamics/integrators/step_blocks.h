#pragma once
// The diagonal blocks of the step matrix A = M + c_D D + c_K K (+ the springs' c_K k L^T L) of
// the integrators (integrator.h): the System's matrices are block diagonal by model, so A^{-1} r
// is the per-block solves stacked. Used by Integrator only; its own header so that the
// integrator's step stays one concern.
//
// Each block eliminates its model's fixed coordinates and factors the free rows and columns with
// SparseCholesky (core/sparse_cholesky.h) under a LowRankUpdate (core/low_rank_update.h) that
// holds the block's spring terms (implicit_springs.h). A constant model with the S (x) I_3
// structure whose fixed coordinates come in node triples is factored as its scalar matrix with
// x, y, z as three right-hand sides (the Kronecker layout: unknowns are nodes, right-hand sides
// node by 3).

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/core/fixed_coordinates.h"
#include "dnurbs/core/free_row_product.h"
#include "dnurbs/core/low_rank_update.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/implicit_springs.h"
#include "dnurbs/dynamics/integrators/lean_step_matrix.h"

namespace dnurbs {

/// One diagonal block of A: the velocities of one model.
struct StepBlock {
  int model = 0;
  int coordinate_offset = 0;
  int coordinate_count = 0;
  int velocity_offset = 0;
  int velocity_count = 0;
  bool constant = false;   ///< the model's M, D, K do not depend on q
  bool kronecker = false;  ///< factored as the scalar matrix (unknowns are nodes)
  /// The coefficients the factorization was built for (constant blocks reuse it).
  bool factored = false;
  double position_coefficient = 0.0;
  double velocity_coefficient = 0.0;
  int factorizations = 0;
  /// The free unknowns of the block (nodes in the Kronecker layout, velocities otherwise).
  FreeCoordinates free;
  /// Factor of the free block plus the spring terms (Woodbury on the solve).
  LowRankUpdate solver;
  BlockSprings springs;
  ModelMatrices matrices;  ///< state-dependent blocks: M, D, K at the current iterate
  /// State-dependent blocks of a lean step (IntegratorSettings::lean_step): `fused` when the
  /// iterate's Model::assemble_step (or add_step_residual) put f_int (and g) into the right-hand
  /// side; `lean_active`
  /// when solve() uses `lean`, the step matrix factored by LeanStepMatrix.
  bool fused = false;
  bool lean_active = false;
  /// The iterate kept the factor of an earlier one (modified Newton): its right-hand side terms
  /// came from Model::add_step_residual and `matrices` are those of the factored iterate.
  bool reused = false;
  LeanStepMatrix lean;
  /// Kronecker blocks: b -= S_K Q + S_D V + S_M A on the free nodes, one pass over the scalar
  /// matrices' shared pattern (matrices in that order; node by 3 arrays).
  FreeRowProduct residual;
  Eigen::MatrixXd rhs_free;

  /// The block of model `index` of `system`; `settings` choose the factorization (state-dependent
  /// blocks hold any number of Woodbury terms: they are refactored every iterate anyway).
  StepBlock(const System& system, int index, const LowRankSettings& settings);

  /// The model's full (velocity-space) matrices: the constant ones, or those last assembled.
  const ModelMatrices& full_matrices(const System& system) const;

  /// What the block looks like to its springs.
  BlockSprings::Layout spring_layout() const;

  /// Factors M + c_D D + c_K K of the block's free unknowns (the scalar matrices in the
  /// Kronecker layout, which constant blocks take from the model; state-dependent blocks from
  /// `matrices`), with the spring terms summed in when `fold_springs` (SpringTreatment::
  /// kRefactor). A block whose factorization throws stays unfactored; the Error names the model.
  void factor(const System& system, double damping_coefficient, double stiffness_coefficient,
              bool fold_springs);

  /// The same factorization by `lean` (state-dependent blocks without springs): analyzes when the
  /// pattern of `matrices` is new; false, leaving the block as it was, when `lean` cannot take
  /// that pattern (then factor() serves). `supernodal`: CHOLMOD factors the lean matrix
  /// (LeanStepMatrix's supernodal mode). The Error of a failed factorization names the model.
  bool factor_lean(double damping_coefficient, double stiffness_coefficient, bool supernodal);

  /// x = A_ff^{-1} r on the block's free unknowns, zero on its fixed ones (block segments of the
  /// stacked vectors r and x, both velocity_count of the System).
  void solve(const Eigen::VectorXd& r, Eigen::VectorXd& x);
};

/// The blocks of one System layout (rebuilt when the System's revision or size changes).
struct StepBlocks {
  bool laid_out = false;
  std::uint64_t revision = 0;
  int velocity_count = 0;
  std::vector<std::unique_ptr<StepBlock>> blocks;

  /// One block per model of `system` (kept while its layout stays).
  void layout(const System& system, const LowRankSettings& settings);

  /// x = A^{-1} r block by block (zero on fixed coordinates).
  void solve(const Eigen::VectorXd& r, Eigen::VectorXd& x);
};

}  // namespace dnurbs
