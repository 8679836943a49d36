#pragma once
// Baumgarte-stabilized constrained steps (Terzopoulos 2003, eqs. 1.39-1.40; DESIGN.md,
// "Constraints").
//
// Each (Newton) iteration of an integrator step solves, for the acceleration increment da and
// the multipliers lambda,
//
//   [ A    C_q^T ] [ da     ]   [ b ]
//   [ C_q  0     ] [ lambda ] = [ r ],
//
// where A and b are the integrator's effective matrix and residual. The constraint rows are the
// Baumgarte condition Cddot + 2 alpha Cdot + beta^2 C = 0 imposed at the end of the step: with
// q_new = q_iter + c_q da and v_new = v_iter + c_v da (the integrator's coefficients),
//
//   (1 + 2 alpha c_v + beta^2 c_q) C_q da = sigma - 2 alpha Cdot - beta^2 C - C_q a,
//
// all evaluated at the iterate (q_iter, v_iter) of the step's end time, a the acceleration so
// far. Imposing it at the end of the step (instead of the start) keeps the stabilization stable
// for any alpha dt, and for small dt the violation follows C0 (1 + alpha t) exp(-alpha t).
//
// The system is solved by the Schur complement on the constraint rows, reusing the
// integrator's factorization of A: X = A^-1 C_q^T (one back-substitution per row, kept while
// C_q and the factorization do not change), S = C_q X, lambda = S^+ (C_q A^-1 b - r),
// da = A^-1 b - X lambda. S^+ is the pseudo-inverse from S's eigen-decomposition: redundant or
// conflicting constraints make S singular; the singular directions are reported with the
// constraints they involve, and the step is the least-squares (minimum-norm lambda) answer.
//
// Linear constraints on coordinates (fixed control points) are better eliminated: use
// DNurbsModel::fix_control_point (the integrator then solves on the free coordinates only, with
// no multiplier and no drift). ControlPointConstraint exists to pull a control point somewhere
// with Baumgarte's dynamics. Every other type here is non-linear in q and goes through
// multipliers.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "dnurbs/constraints/constraint.h"
#include "dnurbs/dynamics/integrators/integrator.h"

namespace dnurbs {

/// Baumgarte parameters of one constraint (1/time units). beta < 0 means beta = alpha
/// (critical damping of the violation).
struct BaumgarteParameters {
  double alpha = 20.0;
  double beta = -1.0;
};

/// What the last constrained step found about the constraint rows.
struct ConstraintReport {
  int row_count = 0;
  int rank = 0;                 ///< numerical rank of S = C_q A^-1 C_q^T
  bool rank_deficient = false;  ///< rank < row_count: redundant or conflicting rows
  std::vector<int> involved;    ///< constraints with a share in S's null space
  double residual = 0.0;        ///< |C_q da - r| after the least-squares solve
  std::string message;          ///< human-readable summary ("" when all is well)
};

/// A set of constraints on a System and the constrained step.
class ConstraintSolver {
 public:
  /// Adds a constraint after checking it against `system`; returns its index.
  int add(const System& system, std::unique_ptr<Constraint> constraint,
          BaumgarteParameters parameters = {});
  int add(const System& system, const Constraint& constraint, BaumgarteParameters parameters = {});
  int constraint_count() const { return static_cast<int>(constraints_.size()); }
  int row_count() const { return rows_; }
  const Constraint& constraint(int i) const {
    return *constraints_.at(static_cast<size_t>(i)).constraint;
  }

  /// After each step, optionally project the state back onto the constraints: Gauss-Newton
  /// steps dq = -C_q^T (C_q C_q^T)^+ C on the coordinates (through advance_coordinates, so
  /// rotations stay rotations) until max |C| <= tolerance (at most `iterations`), then the
  /// velocities onto C_q qd + C_t = 0. Off by default: Baumgarte alone makes the violation
  /// decay; projection holds non-linear constraints (rotating joints) at the tolerance.
  void set_projection(bool enabled, double tolerance = 1e-12, int iterations = 5);

  /// Advances `system` by dt with `integrator`, every constraint enforced. The integrator's
  /// errors (dt <= 0, a non-finite state) propagate with the state unchanged.
  void step(Integrator& integrator, System& system, double dt);

  /// Multipliers lambda of the last step (row_count()).
  const Eigen::VectorXd& multipliers() const { return multipliers_; }
  /// Generalized constraint force -C_q^T lambda of the last step (System velocity space).
  const Eigen::VectorXd& constraint_force() const { return constraint_force_; }
  /// The report of the last step's final iteration.
  const ConstraintReport& last_report() const { return report_; }
  /// Steps so far whose constraint rows were rank deficient.
  int rank_deficient_steps() const { return rank_deficient_steps_; }

  /// |C_i| (norm of the rows of constraint i) at the system's current state.
  Eigen::VectorXd violations(const System& system) const;
  /// max_i |C_i| at the current state (0 without constraints).
  double max_violation(const System& system) const;

  /// All rows at (q, qd, t): C, Cdot, sigma and C_q (row_count() by system velocities).
  struct Evaluation {
    Eigen::VectorXd value;
    Eigen::VectorXd rate;
    Eigen::VectorXd sigma;
    SparseMatrix jacobian;
  };
  void evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd, double time,
                Evaluation& evaluation) const;

 private:
  struct Entry {
    std::unique_ptr<Constraint> constraint;
    BaumgarteParameters parameters;
    int first_row = 0;
  };
  void solve_iteration(const System& system, const StepSystem& step, Eigen::VectorXd& delta);

  std::vector<Entry> constraints_;
  int rows_ = 0;
  Evaluation evaluation_;
  std::vector<Eigen::Triplet<double>> triplets_;
  // Schur complement cache: valid while C_q and the integrator's factorization are unchanged.
  SparseMatrix cached_jacobian_;
  bool cache_valid_ = false;
  std::uint64_t cached_factorization_ = 0;
  Eigen::MatrixXd solved_jacobian_;  ///< X = A^-1 C_q^T
  Eigen::MatrixXd schur_pseudo_inverse_;
  ConstraintReport cached_report_;
  Eigen::VectorXd multipliers_;
  Eigen::VectorXd constraint_force_;
  ConstraintReport report_;
  int rank_deficient_steps_ = 0;
  bool projection_ = false;
  double projection_tolerance_ = 1e-12;
  int projection_iterations_ = 5;
  void project(System& system) const;
};

}  // namespace dnurbs
