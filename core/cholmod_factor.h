#pragma once
// CHOLMOD's sparse Cholesky factorization of one symmetric positive definite matrix: supernodal
// LL^T with BLAS-3 on dense supernodes (Chen, Davis, Hager & Rajamanickam, Algorithm 887: CHOLMOD,
// Supernodal Sparse Cholesky Factorization and Update/Downdate, ACM TOMS 35(3) 2008), the symbolic
// analysis reused while the pattern stays, multi-column solves, and rank-r update/downdate of the
// factor (Davis & Hager, Multiple-rank modifications of a sparse Cholesky factorization, SIAM J.
// Matrix Anal. Appl. 22(4) 2001).

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

#include "dnurbs/core/supernodal_solve.h"

namespace dnurbs {

/// Limits the BLAS under CHOLMOD to one thread, once per process (later calls do nothing).
/// Debian's libcholmod calls whichever libblas.so.3 the alternatives system selects; with
/// libopenblas0-pthread that is OpenBLAS, which by default starts one thread per core for every
/// dense supernode and contends with the caller's own threads. The function looks up
/// openblas_set_num_threads (and goto_set_num_threads) in the loaded libraries and calls it with 1;
/// with the reference BLAS (single-threaded) it finds neither and does nothing. Every CholmodFactor
/// calls it on construction. Returns true if an OpenBLAS thread setting was found.
bool limit_blas_to_one_thread();

/// How a supernodal factor solves: kPanels by supernodal_solve (core/supernodal_solve.h, reading
/// L once per substitution, for 1 to 4 right-hand sides; wider ones go to CHOLMOD); kBlas by
/// CHOLMOD's cholmod_super_lsolve / ltsolve (dtrsm and dgemm per supernode), kept for comparison
/// (bench/floor measures the step against it).
enum class TriangularSolve { kPanels, kBlas };

/// CHOLMOD factorization P A P^T = L L^T (supernodal; L L^T or L D L^T simplicial after a rank
/// update) of a symmetric positive definite n by n matrix A.
///
/// Input matrices are Eigen column-major with int indices; only their LOWER triangle (row >= col)
/// is read, so a matrix may hold its lower triangle or both. The matrix is wrapped, not copied.
/// Not thread-safe: one factor per thread (solves reuse internal workspace).
///
/// Threads: besides limit_blas_to_one_thread, every CHOLMOD analysis, factorization and rank
/// update runs with libgomp's max-active-levels set to 0 (restored after the call): Debian's
/// libcholmod asks for 4 OpenMP threads in loops of its supernodal factorization, which made it
/// 2.4-6x slower on the 2-core machine (bench/solver/README.md). The setting is process-wide in
/// libgomp, so the caller's own OpenMP regions run serially while a CHOLMOD call is under way.
class CholmodFactor {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  explicit CholmodFactor(TriangularSolve solve = TriangularSolve::kPanels);
  ~CholmodFactor();
  CholmodFactor(CholmodFactor&& other) noexcept;
  CholmodFactor& operator=(CholmodFactor&& other) noexcept;
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;

  /// Symbolic analysis of the pattern of a (n by n): fill-reducing ordering (CHOLMOD's default
  /// strategy: AMD, and METIS nested dissection when AMD's fill is high), elimination tree,
  /// supernodes. Values are not read. Throws Error if a is not square.
  void analyze(const SparseMatrix& a);

  /// Numeric factorization of a, whose pattern must be the analyzed one (not checked here:
  /// SparseCholesky checks it). Throws Error naming the column of a (and the pivot in elimination
  /// order) where a is found not positive definite; the factor is then unusable until the next
  /// successful factorize.
  void factorize(const SparseMatrix& a);

  /// Solves A X = B in place: b n by k (any k; k = 3 for x, y, z). The workspace grows to the
  /// largest k seen and is reused, so solves allocate nothing after the first of each width.
  /// A supernodal factor solves as the constructor's TriangularSolve says; a simplicial one
  /// (after a rank update) by cholmod_solve2.
  void solve_in_place(Eigen::Ref<Eigen::MatrixXd> b);

  /// Rank-r modification of the factor: afterwards it factors A + C C^T (downdate = false) or
  /// A - C C^T (downdate = true); c n by r sparse in A's row order (r <= 8 per call is fastest).
  /// The first modification converts a supernodal factor into a simplicial L D L^T one (cost of
  /// about one copy of L; its solves are then simplicial) and the next factorize re-analyzes with
  /// the same ordering to return to supernodal. Throws Error if the downdate leaves A - C C^T not
  /// positive definite (numerically), naming the column.
  void rank_update(const SparseMatrix& c, bool downdate);

  /// The supernodal factor's arrays (views into CHOLMOD's, valid until the next analyze,
  /// factorize or rank_update), in L's row order. Throws Error unless is_factored() and
  /// is_supernodal().
  SupernodalFactor supernodal_factor() const;

  int size() const;
  bool is_factored() const;
  bool is_supernodal() const;
  /// Number of stored entries of L (including the explicit zeros of supernodes).
  double factor_nonzeros() const;
  /// CHOLMOD's cheap estimate (min_j L_jj / max_j L_jj)^2 of the reciprocal condition number.
  double reciprocal_condition_estimate() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace dnurbs
