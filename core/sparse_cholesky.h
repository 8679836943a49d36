#pragma once
// Sparse Cholesky factorization of the step matrices of dnurbs: one interface over two backends,
// Eigen's simplicial L D L^T for small matrices and CHOLMOD's supernodal L L^T for large ones,
// chosen by size with a threshold measured by bench/solver.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

#include "dnurbs/core/cholmod_factor.h"

namespace dnurbs {

/// Which factorization does the work.
enum class CholeskyBackend {
  kAutomatic,          ///< kSimplicialLdlt below SparseCholeskySettings::supernodal_threshold rows,
                       ///< kCholmodSupernodal from it on
  kSimplicialLdlt,     ///< Eigen::SimplicialLDLT (AMD ordering, up-looking, one column at a time)
  kCholmodSupernodal,  ///< CHOLMOD supernodal L L^T (AMD or METIS ordering, BLAS-3 supernodes)
};

/// Rows from which kAutomatic uses CHOLMOD. Measured by bench/solver (three runs on the shared
/// 2-core development machine, OpenBLAS and libgomp held to one thread) on the step matrices of
/// clamped bicubic sheets, SimplicialLDLT time over CHOLMOD time: at 100 rows factor 0.87-0.89
/// (SimplicialLDLT faster) and 3-column solve 1.05-1.51, so factor + solve break even; at 225
/// rows 1.14-1.20 and 1.68-1.93; at 1024 3.7-5.2 and 1.6-2.0; at 1e4 5.7-6.3 and 1.5-2.5; at
/// 1e5 23-25 and 2.6-5.5. CHOLMOD wins every measure from 225 rows on; below about 100 the
/// simplicial factorization's lower overhead wins. bench/solver/README.md has the table.
inline constexpr int kDefaultSupernodalThreshold = 200;

/// Rows from which kAutomatic uses CHOLMOD for a matrix factored once and then only solved with
/// (the integrator's constant step matrices: fixed-weight D-NURBS, grid surfaces, snakes), where
/// the solve alone decides. Measured on the step of a clamped bicubic sheet (bench/floor's
/// scene, three runs on the shared 2-core machine, 2026-11-29), SimplicialLDLT step over the step
/// with CHOLMOD and its panel solves (core/supernodal_solve.h): 0.97-0.98 at 4 free nodes,
/// 0.97-0.98 at 9, 1.03-1.11 at 16, 1.06-1.12 at 25, 1.16-1.21 at 36, 1.33-1.35 at 49, 1.46 at 64
/// and 1.76 at 100: CHOLMOD wins from 16 rows (with CHOLMOD's BLAS solve it won from about 50).
inline constexpr int kDefaultConstantSupernodalThreshold = 16;

struct SparseCholeskySettings {
  CholeskyBackend backend = CholeskyBackend::kAutomatic;
  int supernodal_threshold = kDefaultSupernodalThreshold;  ///< rows; used by kAutomatic only
  /// kAutomatic's threshold for callers that factor a matrix once and solve with it many times
  /// (StepBlock of a constant model); SparseCholesky itself reads supernodal_threshold only.
  int constant_supernodal_threshold = kDefaultConstantSupernodalThreshold;
  /// The CHOLMOD backend's triangular solves (cholmod_factor.h): kPanels reads L once per
  /// substitution (0.55-0.8 of CHOLMOD's BLAS solve's time for 3 columns, bench/floor).
  TriangularSolve triangular_solve = TriangularSolve::kPanels;
};

/// The backend that `settings` choose for a matrix of `rows` rows (kAutomatic resolved by
/// supernodal_threshold; an explicit backend as it is). Never kAutomatic.
CholeskyBackend resolve_backend(const SparseCholeskySettings& settings, Eigen::Index rows);

/// The factorization P A P^T = L D L^T (or L L^T) of a symmetric positive definite n by n matrix
/// A, with its symbolic analysis (ordering, elimination tree, pattern of L) kept while the pattern
/// of A stays: the integrators refactor state-dependent matrices every step with one pattern.
///
/// Input: Eigen column-major sparse matrices with int indices, of which only the LOWER triangle
/// (row >= column) is read: a matrix may store its lower triangle or both (the upper is ignored,
/// so an unsymmetric input is taken as its lower triangle mirrored).
///
/// Positive definiteness: a pivot <= 0 throws Error naming the column of A (and the pivot's place
/// in elimination order). A singular positive semidefinite A (a free coordinate without mass, a
/// stiffness without boundary conditions) throws when rounding makes a pivot exactly zero or
/// negative; when rounding leaves it tiny and positive instead the factorization succeeds and the
/// solution's null-space component is amplified by 1 / pivot: reciprocal_condition_estimate() is
/// then at rounding level (about 1e-16) and tells the caller. Non-finite entries of A or of a
/// right-hand side throw Error naming the entry.
///
/// Not thread-safe (solves reuse workspace); move-only.
class SparseCholesky {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  explicit SparseCholesky(const SparseCholeskySettings& settings = {});
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&& other) noexcept;
  SparseCholesky& operator=(SparseCholesky&& other) noexcept;
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  /// Symbolic analysis of the pattern of a (n by n, values not read); picks the backend.
  void analyze(const SparseMatrix& a);
  /// Numeric factorization of a. Analyzes first if a's stored pattern differs from the analyzed
  /// one (compared entry by entry, O(nnz)), so a caller may simply call factorize every step.
  /// Throws Error for a non-square a, a non-finite entry, or a non-positive pivot.
  void factorize(const SparseMatrix& a);

  /// Solves A X = B in place: b n by k (k = 3 for the x, y, z columns of a Kronecker-structured
  /// D-NURBS step; any k). Allocates only on the first solve of a given width. Throws Error if
  /// nothing is factored, the rows do not match, or b has a non-finite entry.
  void solve_in_place(Eigen::Ref<Eigen::MatrixXd> b);
  /// Convenience: returns A^{-1} b (allocates the result).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b);

  /// Rank-r modification of the factor: afterwards it factors A + C C^T (downdate = false) or
  /// A - C C^T (downdate = true); c n by r sparse. CHOLMOD backend only (throws Error otherwise):
  /// see CholmodFactor::rank_update for the cost (the factor becomes simplicial until the next
  /// factorize). A later factorize(a) discards the modification.
  void rank_update(const SparseMatrix& c, bool downdate);

  int size() const;
  bool is_factored() const;
  /// The backend in use (never kAutomatic once analyzed; kAutomatic before).
  CholeskyBackend backend() const;
  /// Number of symbolic analyses so far (tests use it to check reuse).
  int analysis_count() const;
  /// Stored entries of L (CHOLMOD: including the explicit zeros of supernodes).
  double factor_nonzeros() const;
  /// min pivot / max pivot of D (simplicial) or (min L_jj / max L_jj)^2 (CHOLMOD): a cheap
  /// indicator of 1 / cond(A), not a bound (rounding level, ~1e-16, flags a singular A); 0 before
  /// a successful factorization.
  double reciprocal_condition_estimate() const;

 private:
  class Simplicial;
  struct Backends;
  SparseCholeskySettings settings_;
  std::unique_ptr<Backends> backends_;
};

}  // namespace dnurbs
