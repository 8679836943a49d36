#pragma once
// Solves with a factored matrix plus a changing set of rank-one terms: the implicit springs of
// interactive sculpting. A spring at parameter u with stiffness k adds k N(u) N(u)^T to the scalar
// step matrix of a fixed-weight D-NURBS (N(u): the few non-zero basis functions at u), and pulls
// toward its target t with the force k N(u) t^T. Adding, moving or removing a spring must cost
// about one solve, not a new factorization.

#include <Eigen/Core>
#include <Eigen/Dense>
#include <span>
#include <vector>

#include "dnurbs/core/sparse_cholesky.h"

namespace dnurbs {

/// How the terms reach the solution.
enum class LowRankMethod {
  /// Sherman-Morrison-Woodbury on the solve (Hager, Updating the inverse of a matrix, SIAM Review
  /// 31(2) 1989): the factor of A is untouched; W = A^{-1} U is cached and recomputed only for
  /// terms that moved, in the same multi-column solve as the right-hand sides; a dense m by m
  /// capacitance matrix C = K^{-1} + U^T W is factored per solve (m = number of terms).
  kWoodbury,
  /// Rank-one update/downdate of CHOLMOD's factor (Davis & Hager 2001, cholmod_updown): add =
  /// update, move = update with the new term then downdate of the old one, remove = downdate. The
  /// factor becomes simplicial; the backend is forced to kCholmodSupernodal. Measured slower than
  /// kWoodbury (a drag step 1.1-1.6x, its solves being simplicial) and less accurate for stiff
  /// terms (their pull goes into B): kept for comparison and for many long-lived terms.
  kFactorUpdate,
};

struct LowRankSettings {
  LowRankMethod method = LowRankMethod::kWoodbury;
  SparseCholeskySettings cholesky;
  /// kWoodbury: more Woodbury terms than this triggers a refactorization that folds every term
  /// not moved since the previous solve into the factor (cost of a solve grows with m n).
  int max_woodbury_terms = 32;
  /// kWoodbury: if the capacitance matrix's reciprocal condition estimate falls below this (stiff
  /// springs whose N(u) are nearly dependent, e.g. two at one parameter), the unmoved terms are
  /// folded into a refactorization. Off by default: the Woodbury correction loses about
  /// log10(1 / rcond(C)) digits, but a folded term's pull k u t^T in B loses log10(k / diag(A)),
  /// which measured worse (two coincident springs at k = 1e8 diag: 5e-10 against 3e-8).
  double min_capacitance_rcond = 0.0;
};

/// Solves (A + sum_i k_i u_i u_i^T) X = B + sum_i k_i u_i t_i^T for n by k blocks B, where A is a
/// sparse symmetric positive definite n by n matrix (read as in SparseCholesky: lower triangle),
/// u_i sparse n-vectors with a few non-zeros, k_i > 0 stiffnesses and t_i optional targets (rows
/// of k values, zero when not given). Terms are added, moved and removed between solves.
///
/// The target form is the accurate one for stiff terms: with kWoodbury the solution is
/// X = Y + W C^{-1} (T - U^T Y), Y = A^{-1} B, in which no quantity scales with k_i. Any form
/// that puts k_i u_i t_i^T into B (a factorization of the summed matrix, the factor update, a
/// folded term) loses the rounding of that pull, about 1e-16 k / diag(A) relative: measured on a
/// bicubic sheet, Woodbury stays at 4e-15 for k from 1 to 1e8 diag(A) while the others reach
/// 1e-12 at 1e4, 1e-10 at 1e6 and 1e-8 at 1e8 (tests/core/test_low_rank_update.cpp).
///
/// Folding: factorize(a) factors a plus the terms already folded (none unless kFactorUpdate or a
/// fold happened); new and moved terms are Woodbury terms, their A^{-1} u solved together with the
/// next right-hand sides. Moving or removing a folded term, more than max_woodbury_terms Woodbury
/// terms, or (if enabled) an ill-conditioned capacitance matrix trigger one refactorization at the
/// next solve that folds the terms that did not move since the previous solve.
class LowRankUpdate {
 public:
  using SparseMatrix = SparseCholesky::SparseMatrix;

  explicit LowRankUpdate(const LowRankSettings& settings = {});

  /// Keeps a copy of a (n by n) and factors a + the folded terms (all terms with kFactorUpdate).
  /// Throws as SparseCholesky::factorize.
  void factorize(const SparseMatrix& a);

  /// Adds the term k u u^T (u: entries `values` at `rows`, distinct rows in 0..n-1) with target
  /// t (empty: zero). Returns its id (ids of removed terms are reused). Throws Error for k <= 0 or
  /// not finite, a row out of range or repeated, mismatched sizes, or a non-finite value.
  int add_term(std::span<const int> rows, std::span<const double> values, double stiffness,
               std::span<const double> target = {});
  /// Replaces term `term`'s u, k and t (a drag: both its parameter and its target move).
  void move_term(int term, std::span<const int> rows, std::span<const double> values,
                 double stiffness, std::span<const double> target = {});
  void remove_term(int term);
  /// Replaces term `term`'s target only (empty: zero). Its u and k are unchanged, so its column
  /// of W = A^{-1} U stays valid: an implicit spring whose pull changes every step at a fixed
  /// parameter costs no extra solve column. Throws Error for an unknown term or a non-finite
  /// entry.
  void set_target(int term, std::span<const double> target);

  /// Solves in place: b n by k on input (B), X on output. Targets given must have k entries.
  void solve_in_place(Eigen::Ref<Eigen::MatrixXd> b);

  int size() const { return cholesky_.size(); }
  int term_count() const;
  /// Terms currently handled by Woodbury (the rest are folded into the factor).
  int woodbury_term_count() const { return static_cast<int>(woodbury_.size()); }
  /// Factorizations so far (factorize calls plus automatic refactorizations).
  int factorization_count() const { return factorizations_; }
  /// Reciprocal condition estimate of the last capacitance matrix (1 with no Woodbury terms).
  double capacitance_rcond() const { return capacitance_rcond_; }
  const SparseCholesky& cholesky() const { return cholesky_; }

 private:
  enum class Place { kUnused, kFolded, kWoodbury };
  struct Term {
    std::vector<int> rows;
    std::vector<double> values;
    double stiffness = 0.0;
    std::vector<double> target;
    Place place = Place::kUnused;
    bool moved = false;  // since the previous solve: its W column (if any) is stale
  };

  void check_term(std::span<const int> rows, std::span<const double> values, double stiffness,
                  std::span<const double> target) const;
  void refactor(bool fold_woodbury);
  void factor_update(const Term& term, bool downdate);
  void add_folded_targets(Eigen::Ref<Eigen::MatrixXd> b) const;
  void add_woodbury(int term);
  void drop_woodbury(int term);
  void woodbury_solve(Eigen::Ref<Eigen::MatrixXd> b);
  bool capacitance_is_ill_conditioned();
  double u_dot(const Term& term, const double* column) const;

  LowRankSettings settings_;
  SparseCholesky cholesky_;
  SparseMatrix matrix_;  // A as last given to factorize
  bool factored_ = false;
  bool refactor_needed_ = false;
  int factorizations_ = 0;
  std::vector<Term> terms_;
  std::vector<int> woodbury_;  // term ids; position = column of w_ and row/column of gram_
  Eigen::MatrixXd w_;          // n by capacity: A_f^{-1} u_i (A_f: the factored matrix)
  Eigen::MatrixXd gram_;       // capacity by capacity: U^T W
  Eigen::MatrixXd capacitance_, rhs_small_;
  // Computed on the empty matrix so that its status is defined before the first capacitance
  // (Eigen's default constructor leaves it unset, and moving the object reads it).
  Eigen::LLT<Eigen::MatrixXd> capacitance_llt_{Eigen::MatrixXd()};
  std::vector<double> workspace_;  // [B | stale u_i] for the one multi-column solve
  std::vector<int> stale_;
  double capacitance_rcond_ = 1.0;
};

}  // namespace dnurbs
