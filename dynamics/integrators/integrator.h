#pragma once
// Time integration of M qdd + D qd - f_int(q) = f + g (Terzopoulos 2003, eq. 1.24; DESIGN.md, "Time
// integration"). Every scheme is written for one unknown, the acceleration a of the step:
//
//   q_new = q_pred "+" position_coefficient a      (Model::advance_coordinates)
//   v_eq  = v_pred + velocity_coefficient a        (velocity in the damping term)
//   A a = b,   A = M + velocity_coefficient D + position_coefficient K_T,
//   b = f + g + f_int(q_pred) - D v_pred           (the residual at a = 0)
//
//   central         Terzopoulos 2003, eq. 1.13, (M/dt^2 + D/(2dt) + K) q(t+dt) = (2M/dt^2) q(t)
//                   - (M/dt^2 - D/(2dt)) q(t-dt) + f(t): with v = (q(t) - q(t-dt))/dt stored as
//                   the velocity, q_pred = q + dt v, position_coefficient dt^2, velocity
//                   coefficient dt/2, forces at time t and state (q, v).
//   implicit-euler  q_pred = q + dt v, coefficients dt^2 and dt, forces at t + dt.
//   newmark         q_pred = q + dt v + dt^2 (1/2 - beta) a_old, v_pred = v + dt (1 - gamma)
//                   a_old, coefficients beta dt^2 and gamma dt (beta = 1/4, gamma = 1/2:
//                   average acceleration), forces at t + dt.
//
// Springs (System::add_spring) are implicit: their stiffness c_K k L^T L is part of A, as low-rank
// terms on the factor, and their pull k L^T (target - x) part of b, evaluated at the iterate with
// the target at the force time (implicit_springs.h); IntegratorSettings::springs chooses how.
//
// A is block diagonal by model (the System stacks the models' M, D, K), so it is factored and
// solved block by block, one block per model (step_blocks.h), each with SparseCholesky
// (IntegratorSettings::cholesky; SimplicialLDLT for small blocks, CHOLMOD supernodal for large):
//   constant blocks (fixed-weight D-NURBS, grid surfaces, snakes) are factored once per
//   (dt, scheme) and every later solve only back-substitutes; a constant model with the
//   S (x) I_3 structure is factored as its scalar matrix with x, y, z as three right-hand sides;
//   state-dependent blocks (superquadrics, free-weight D-NURBS) make the step linearly implicit
//   (the block and its part of b at the predictor) with optional Newton iterations on a (the
//   block re-assembled and re-factored at each iterate, tangent stiffness K_T = -d f_int/dq as
//   the model gives it; under the lean step, modified Newton: a factor is kept while the
//   corrections contract, and for free weights from one step to the next); constant blocks of
//   the same system are not touched by those.
// The initial guess of a is the last acceleration under Newmark when some block is
// state-dependent, zero otherwise (for every block alike, as when A was factored whole, so
// results are those of the whole-system factorization up to rounding). The StepSystem solve hook
// (constraints) solves block by block too.
//
// Fixed coordinates are eliminated: their acceleration and velocity are zero and only the free
// rows and columns of each block are solved.

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/core/sparse_cholesky.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/implicit_springs.h"
#include "dnurbs/dynamics/integrators/integrator_scheme.h"

namespace dnurbs {

struct IntegratorSettings {
  IntegratorScheme scheme = IntegratorScheme::kNewmark;
  double newmark_beta = 0.25;  ///< average acceleration
  double newmark_gamma = 0.5;
  /// Newton iterations after the linearly implicit solve where matrices depend on q (or
  /// applied forces depend on the state); 0 = linearly implicit (but see automatic_newton).
  int newton_iterations = 0;
  /// Iterations stop when the error left in a is <= newton_tolerance * max(|a|, 1e-300): |delta
  /// a| after a new factor, rho / (1 - rho) |delta a| while a kept factor contracts at the rate
  /// rho (modified Newton; integrator.cpp).
  double newton_tolerance = 1e-12;
  /// With newton_iterations = 0: a system with a model that needs_newton_iterations()
  /// (free-weight D-NURBS) iterates anyway, up to kAutomaticNewtonIterations times, until
  /// |delta a| <= kAutomaticNewtonTolerance |a| (with the lean step, modified Newton: one
  /// residual pass and one solve per iteration while the kept factor contracts). Measured on the
  /// curve_sculpting rod with free weights (tests/hardcase/test_free_weights.cpp): linearly
  /// implicit, its step matrix is refused at step 16, with one iteration at step 66, with two
  /// its force-free damped energy rises to 1.44 E_0; iterated to convergence it stays below
  /// 1.075 E_0 and decays. false: newton_iterations = 0 is linearly implicit for every model.
  bool automatic_newton = true;
  /// The lean step of state-dependent blocks (the default): one Model::assemble_step pass per
  /// iterate (M, D, K, f_int and g together) and, for blocks without springs, the step matrix
  /// assembled into a pattern analyzed once and factored numerically only (lean_step_matrix.h;
  /// by its own L D L^T below the supernodal threshold, without allocation, by CHOLMOD from it
  /// on). Newton iterations then keep the step's factor while the
  /// corrections contract (modified Newton), their residual from Model::add_step_residual
  /// without assembling: a correction that shrinks by less than kNewtonStallRatio against the
  /// previous one is discarded and solved again with A factored at its iterate. false: separate
  /// assembly and force calls, sparse sums and SparseCholesky at every iterate (the reference
  /// the tests compare the lean step with).
  bool lean_step = true;
  /// Modified Newton across steps, under the automatic Newton iterations (automatic_newton): a
  /// lean block of a model that needs_newton_iterations() (free weights) starts each step from
  /// the factor its last step ended with, when dt and the scheme's coefficients are the same,
  /// and refactors only when a correction stalls (kNewtonStallRatio). The step still iterates to
  /// kAutomaticNewtonTolerance, so it lands on the same implicit solution within it; a step that
  /// does not converge within kAutomaticNewtonIterations that way (or whose factorization at an
  /// iterate fails) is solved again from its predictor with the factor there. What a step saves
  /// is the assembly and factorization, about 10 to 20 residual passes on the sheets of
  /// bench/free_weights. Linearly implicit steps and a fixed newton_iterations count always
  /// factor at the predictor. false: every step factors at its predictor.
  bool keep_factor_across_steps = true;
  /// How springs enter the step (implicit_springs.h): low-rank terms on the factor by default.
  SpringTreatment springs = SpringTreatment::kLowRank;
  /// The factorization of each block: kAutomatic by default, SimplicialLDLT below
  /// kDefaultSupernodalThreshold free unknowns (scalar unknowns, i.e. free nodes, for a
  /// Kronecker block; kDefaultConstantSupernodalThreshold for a block with constant matrices,
  /// factored once) and CHOLMOD's supernodal factorization (OpenBLAS held to one thread,
  /// core/cholmod_factor.h) from it on, where it factors and solves faster (bench/solver,
  /// bench/floor). The two backends give the same solution up to rounding (about 1e-15 relative
  /// per solve).
  SparseCholeskySettings cholesky{CholeskyBackend::kAutomatic, kDefaultSupernodalThreshold};
};

/// True when `settings` leave the Newton iterations to IntegratorSettings::automatic_newton
/// (newton_iterations = 0, automatic_newton set) and some model of `system`
/// needs_newton_iterations(): its steps then iterate up to kAutomaticNewtonIterations times.
bool automatic_newton_applies(const IntegratorSettings& settings, const System& system);

/// The linear system of one step, handed to a solve hook (a constraint layer adds its rows
/// C_q a = ... around it). Vectors are velocity-space (System::velocity_count()).
struct StepSystem {
  double time = 0.0;  ///< time of the applied forces
  double dt = 0.0;
  double position_coefficient = 0.0;  ///< q_new = q_pred "+" position_coefficient a
  double velocity_coefficient = 0.0;  ///< v_eq = v_pred + velocity_coefficient a
  const Eigen::VectorXd* predicted_coordinates = nullptr;  ///< q of the current iterate
  const Eigen::VectorXd* predicted_velocities = nullptr;   ///< v of the current iterate
  double state_time = 0.0;                                 ///< time of the iterate's state (t + dt)
  const Eigen::VectorXd* acceleration = nullptr;           ///< acceleration a of the iterate so far
  /// Changes whenever `solve` uses a new factorization (of A or, for the initial acceleration,
  /// of M) or a spring term of A was added, moved or removed, so that a hook may keep work done
  /// with the previous one.
  std::uint64_t factorization_serial = 0;
  const std::vector<int>* fixed_coordinates = nullptr;
  const Eigen::VectorXd* rhs = nullptr;  ///< b (the residual at the current iterate)
  /// x = A^{-1} r on the free coordinates (x zero on fixed ones); reuses the factorization. A
  /// includes the springs' stiffness and `rhs` their pull (linear in r: no spring target in it).
  std::function<void(const Eigen::VectorXd& r, Eigen::VectorXd& x)> solve;
};

/// Replaces the default solve a = A^{-1} b of each (Newton) iteration.
using SolveHook = std::function<void(const StepSystem& step, Eigen::VectorXd& a)>;

/// IntegratorSettings::automatic_newton: the iteration cap and the relative tolerance on |delta a|.
inline constexpr int kAutomaticNewtonIterations = 10;
inline constexpr double kAutomaticNewtonTolerance = 1e-8;

/// Modified Newton (IntegratorSettings::lean_step): a correction from a kept factor of A is
/// accepted while |delta a_k| <= kNewtonStallRatio |delta a_{k-1}|.
inline constexpr double kNewtonStallRatio = 0.25;

class Integrator {
 public:
  explicit Integrator(IntegratorSettings settings = {});
  Integrator(const Integrator& other);
  Integrator& operator=(const Integrator& other);
  Integrator(Integrator&&) noexcept;
  Integrator& operator=(Integrator&&) noexcept;
  ~Integrator();

  const IntegratorSettings& settings() const { return settings_; }

  /// Advances `system` by dt. Throws Error naming dt if dt <= 0 or not finite, and Error (state
  /// untouched) if the step produces a non-finite coordinate, velocity or acceleration or the
  /// effective matrix cannot be factored. A constant model whose mass matrix has no entries (the
  /// massless flow D qd + K q = f of Terzopoulos 2003, section 2.6) is stepped by implicit-euler
  /// alone, as exactly backward Euler; central and newmark throw Error naming the scheme.
  void step(System& system, double dt);

  /// Installs a hook that solves each step's linear system (nullptr restores the default).
  void set_solve_hook(SolveHook hook) { hook_ = std::move(hook); }

  /// Newton iterations done by the last step (0 for a linearly implicit step).
  int last_newton_iterations() const { return last_iterations_; }
  /// Number of block factorizations of A so far, summed over the models' blocks: a constant
  /// block counts one per dt and scheme (a system of one constant model: one in all), a
  /// state-dependent block one per factorization (at most one per Newton iterate; modified Newton
  /// keeps a factor while its corrections contract). The mass-matrix factorization of
  /// Newmark's initial acceleration is not counted.
  int factorization_count() const { return factorization_count_; }
  /// Factorizations of model `model`'s block of A (counted as in factorization_count()) since
  /// the last stepped system's layout (its models) was set up; throws Error naming the index if
  /// that system has no such model.
  int block_factorization_count(int model) const;
  /// The factorization backend of model `model`'s block (kAutomatic resolved by the block's
  /// size: free nodes for a Kronecker block, free coordinates otherwise; kAutomatic itself
  /// before the block is first factored; a block factored by the lean step reports its
  /// LeanStepMatrix's mode: kSimplicialLdlt for the up-looking L D L^T, kCholmodSupernodal for
  /// CHOLMOD); throws Error as block_factorization_count.
  CholeskyBackend block_backend(int model) const;

  /// Opaque caches (factorizations and work vectors).
  struct Workspace;

 private:
  void initial_acceleration(System& system);
  // Factors the constant blocks whose coefficients changed; true if some block is
  // state-dependent.
  bool factor_constant_blocks(const System& system);
  // Which state-dependent blocks may keep an earlier factor at an iterate: none (factored at
  // the iterate), lean blocks (later iterates of a step), or also a step's first iterate
  // (IntegratorSettings::keep_factor_across_steps: lean blocks of models that iterate, with the
  // same coefficients).
  enum class FactorReuse { kNone, kWithinStep, kAcrossSteps };
  // The step's solves from the initial guess (the last acceleration with `warm_start`, else
  // zero) at the predictor: up to 1 + `iterations`, until the error left in a is <= `tolerance`
  // |a| (true) or the cap is reached (false). `first_reuse`: whether the first solve may keep the
  // factors of the last step.
  bool iterate(const System& system, double dt, bool warm_start, int iterations, double tolerance,
               FactorReuse first_reuse);
  // One solve of A delta = b at the current iterate, then a += delta; `with_acceleration`: b
  // subtracts M a (after the first solve or a warm start). `reuse` says which blocks keep their
  // factor; a kept factor whose correction does not contract to kNewtonStallRatio *
  // `previous_correction` (>= 0; < 0 before the step's first correction) is replaced by one at
  // the iterate and the correction solved again (modified Newton).
  void solve_iteration(const System& system, double dt, bool with_acceleration,
                       double previous_correction, FactorReuse reuse);
  // delta = A^{-1} b at the iterate (the hook's solve, if any).
  void solve_step_system(const System& system, double dt);
  // Assembles and factors the blocks that kept an earlier factor at this iterate; true if any.
  bool refactor_reused_blocks(const System& system);
  // Assembles the state-dependent blocks at the iterate (the fused pass adds their f_int and g
  // to the right-hand side) and factors them; true if some block was factored.
  bool assemble_state_dependent_blocks(const System& system, FactorReuse reuse);
  // Brings every block's spring terms to the iterate; refactors constant blocks whose folded
  // springs changed (kRefactor). Returns true if A changed.
  bool update_springs(const System& system);

  IntegratorSettings settings_;
  SolveHook hook_;
  std::unique_ptr<Workspace> work_;
  int last_iterations_ = 0;
  int factorization_count_ = 0;
  std::uint64_t factorization_serial_ = 0;
};

}  // namespace dnurbs
