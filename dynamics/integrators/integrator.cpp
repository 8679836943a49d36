#include "dnurbs/dynamics/integrators/integrator.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/integrators/step_blocks.h"

namespace dnurbs {

namespace {

// The blocks' factorization: the integrator's Cholesky backend under the spring terms.
LowRankSettings low_rank_settings(const IntegratorSettings& settings) {
  LowRankSettings result;
  result.cholesky = settings.cholesky;
  return result;
}

int first_non_finite(const Eigen::VectorXd& x) {
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i])) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

// The massless limit (Terzopoulos 2003, section 2.6: mu = 0, D qd + K q = f) has no acceleration
// to solve for: implicit Euler with M = 0 is exactly backward Euler of the first-order flow
// (A = dt D + dt^2 K, q_new = q + dt v_new), while Newmark needs M^-1 for its initial acceleration
// and the central scheme degenerates to two interleaved implicit-Euler sequences of step 2 dt.
// A constant mass matrix without entries marks a massless model.
bool is_massless(const Model& model) {
  const ModelMatrices* matrices =
      model.matrices_are_constant() ? model.constant_matrices() : nullptr;
  return matrices != nullptr && matrices->mass.nonZeros() == 0;
}

void refuse_massless_models(const System& system, IntegratorScheme scheme) {
  for (int i = 0; i < system.model_count(); ++i) {
    if (is_massless(system.model(i))) {
      throw make_error("the ", to_string(scheme), " integrator cannot step model ", i,
                       ": its mass matrix is zero (mass density mu = 0, the first-order flow ",
                       "D qd + K q = f); step it with implicit-euler");
    }
  }
}

}  // namespace

bool automatic_newton_applies(const IntegratorSettings& settings, const System& system) {
  if (settings.newton_iterations != 0 || !settings.automatic_newton) {
    return false;
  }
  for (int i = 0; i < system.model_count(); ++i) {
    if (system.model(i).needs_newton_iterations()) {
      return true;
    }
  }
  return false;
}

// The blocks of A and the work vectors of a step, kept between steps.
struct Integrator::Workspace {
  StepBlocks blocks;
  StepCoefficients coefficients;
  Eigen::VectorXd q_pred, v_pred, v_store, a, delta, rhs, q_iter, v_iter, external, increment;
  Eigen::VectorXd q_new, v_new;
  Eigen::VectorXd displacement;  // q - q_r of Kronecker blocks with a rest shape
};

namespace {

// The predictor (q_pred, v_pred, v_store) from the state at t, fixed coordinates held.
void predict(const System& system, bool newmark, double dt, Integrator::Workspace& w) {
  const std::vector<int>& fixed = system.fixed_coordinates();
  const StepCoefficients& c = w.coefficients;
  w.v_pred = system.velocities();
  for (const int index : fixed) {
    w.v_pred[index] = 0.0;
  }
  // A massless model's velocity carries no state (D v_new + K (q + dt v_new) = f does not involve
  // v): its predictor stays at q, where the explicit forces are evaluated. Extrapolating with the
  // last velocity would evaluate them at q + dt v, which makes the flow settle off its
  // equilibrium, in a two-step cycle.
  for (int i = 0; i < system.model_count(); ++i) {
    if (is_massless(system.model(i))) {
      w.v_pred.segment(system.velocity_offset(i), system.model(i).velocity_count()).setZero();
    }
  }
  w.increment = dt * w.v_pred;
  if (newmark) {
    const Eigen::VectorXd& a_old = system.accelerations();
    w.increment += c.predictor_acceleration_q * a_old;
    w.v_pred += c.predictor_acceleration_v * a_old;
    for (const int index : fixed) {
      w.increment[index] = 0.0;
      w.v_pred[index] = 0.0;
    }
  }
  // Central stores v + dt a but damps with v + dt a / 2; the others store what they damp with.
  w.v_store = w.v_pred;
  w.q_pred.resize(system.coordinate_count());
  system.advance_coordinates(system.coordinates(), w.increment, w.q_pred);
}

// b -= K q + D v (+ M a after the first solve) block by block, at the iterate: the residual of
// A a = b (integrator.h) with the internal forces of the models.
void subtract_block_terms(const System& system, bool with_acceleration, Integrator::Workspace& w) {
  for (const auto& block : w.blocks.blocks) {
    const Eigen::Index vo = block->velocity_offset;
    const Eigen::Index vc = block->velocity_count;
    if (block->kronecker) {
      // S_K (Q - Q_r) + S_D V (+ S_M A) in one pass over the free nodes (fixed rows are not
      // solved); f_int = -K (q - q_r) (Model::linear_rest_coordinates)
      const double* position = w.q_iter.data() + block->coordinate_offset;
      if (const Eigen::VectorXd* rest = system.model(block->model).linear_rest_coordinates()) {
        w.displacement.resize(system.coordinate_count());
        auto displacement = w.displacement.segment(block->coordinate_offset, rest->size());
        displacement = w.q_iter.segment(block->coordinate_offset, rest->size()) - *rest;
        position = displacement.data();
      }
      block->residual.subtract(
          {position, w.v_iter.data() + vo, with_acceleration ? w.a.data() + vo : nullptr},
          w.rhs.data() + vo);
    } else {
      if (!block->fused) {
        system.model(block->model)
            .add_internal_force(w.q_iter.segment(block->coordinate_offset, block->coordinate_count),
                                w.rhs.segment(vo, vc));
      }
      if (block->reused) {
        continue;  // add_step_residual subtracted D v and M a
      }
      const ModelMatrices& matrices = block->full_matrices(system);
      if (matrices.damping.nonZeros() > 0) {
        w.rhs.segment(vo, vc).noalias() -= matrices.damping * w.v_iter.segment(vo, vc);
      }
      if (with_acceleration) {
        w.rhs.segment(vo, vc).noalias() -= matrices.mass * w.a.segment(vo, vc);
      }
    }
  }
}

}  // namespace

Integrator::Integrator(IntegratorSettings settings)
    : settings_(settings), work_(std::make_unique<Workspace>()) {
  if (!(settings_.newmark_beta > 0.0) || !(settings_.newmark_gamma > 0.0)) {
    throw make_error("Newmark parameters beta = ", settings_.newmark_beta,
                     " and gamma = ", settings_.newmark_gamma, " must be positive");
  }
  if (settings_.newton_iterations < 0) {
    throw make_error("Newton iteration count ", settings_.newton_iterations, " is negative");
  }
  if (!(settings_.newton_tolerance >= 0.0)) {
    throw make_error("Newton tolerance ", settings_.newton_tolerance, " is not >= 0");
  }
}

Integrator::Integrator(const Integrator& other)
    : settings_(other.settings_), hook_(other.hook_), work_(std::make_unique<Workspace>()) {}

Integrator& Integrator::operator=(const Integrator& other) {
  if (this != &other) {
    settings_ = other.settings_;
    hook_ = other.hook_;
    work_ = std::make_unique<Workspace>();
  }
  return *this;
}

Integrator::Integrator(Integrator&&) noexcept = default;
Integrator& Integrator::operator=(Integrator&&) noexcept = default;
Integrator::~Integrator() = default;

int Integrator::block_factorization_count(int model) const {
  const StepBlocks& blocks = work_->blocks;
  if (model < 0 || model >= static_cast<int>(blocks.blocks.size())) {
    throw make_error("model index ", model, " is outside the ", blocks.blocks.size(),
                     " blocks of the last stepped system");
  }
  return blocks.blocks[static_cast<size_t>(model)]->factorizations;
}

CholeskyBackend Integrator::block_backend(int model) const {
  block_factorization_count(model);  // checks the index
  const StepBlock& block = *work_->blocks.blocks[static_cast<size_t>(model)];
  if (block.lean_active) {
    return block.lean.is_supernodal() ? CholeskyBackend::kCholmodSupernodal
                                      : CholeskyBackend::kSimplicialLdlt;
  }
  return block.solver.cholesky().backend();
}

void Integrator::initial_acceleration(System& system) {
  // M a = f + g + f_int - D v at the current state, on the free coordinates, block by block.
  const int n = system.velocity_count();
  const Eigen::VectorXd& q = system.coordinates();
  Eigen::VectorXd v = system.velocities();
  for (const int index : system.fixed_coordinates()) {
    v[index] = 0.0;
  }
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  system.add_applied_forces(system.time(), q, v, rhs);
  system.add_inertial_forces(q, v, rhs);
  system.add_internal_forces(q, rhs);
  StepBlocks mass_blocks;
  mass_blocks.layout(system, low_rank_settings(settings_));
  for (const auto& block : mass_blocks.blocks) {
    if (!block->constant) {
      system.model(block->model)
          .assemble_matrices(q.segment(block->coordinate_offset, block->coordinate_count),
                             block->matrices);
    }
    const SparseMatrix& damping = block->full_matrices(system).damping;
    if (damping.nonZeros() > 0) {
      rhs.segment(block->velocity_offset, block->velocity_count).noalias() -=
          damping * v.segment(block->velocity_offset, block->velocity_count);
    }
    block->factor(system, 0.0, 0.0, /*fold_springs=*/false);
  }
  ++factorization_serial_;
  Eigen::VectorXd a;
  if (hook_) {
    // Constraints shape the initial acceleration too (otherwise Newmark's first predictor
    // starts off the constraint manifold): the hook solves M a = rhs with its rows at (q, v, t).
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    StepSystem step_system;
    step_system.time = system.time();
    step_system.predicted_coordinates = &q;
    step_system.predicted_velocities = &v;
    step_system.state_time = system.time();
    step_system.acceleration = &zero;
    step_system.factorization_serial = factorization_serial_;
    step_system.fixed_coordinates = &system.fixed_coordinates();
    step_system.rhs = &rhs;
    step_system.solve = [&mass_blocks](const Eigen::VectorXd& r, Eigen::VectorXd& x) {
      mass_blocks.solve(r, x);
    };
    hook_(step_system, a);
  } else {
    mass_blocks.solve(rhs, a);
  }
  if (first_non_finite(a) >= 0) {
    throw make_error("initial acceleration at t = ", system.time(), " is not finite");
  }
  system.set_accelerations(a);
}

void Integrator::step(System& system, double dt) {
  if (!std::isfinite(dt) || dt <= 0.0) {
    throw make_error("time step dt = ", dt, " must be positive and finite");
  }
  Workspace& w = *work_;
  const int n = system.velocity_count();
  const std::vector<int>& fixed = system.fixed_coordinates();
  const IntegratorScheme scheme = settings_.scheme;
  const double t = system.time();
  w.coefficients =
      step_coefficients(scheme, settings_.newmark_beta, settings_.newmark_gamma, t, dt);
  if (scheme != IntegratorScheme::kImplicitEuler) {
    refuse_massless_models(system, scheme);
  }
  if (scheme == IntegratorScheme::kNewmark && !system.accelerations_valid()) {
    initial_acceleration(system);
  }
  predict(system, scheme == IntegratorScheme::kNewmark, dt, w);
  const bool any_state_dependent = factor_constant_blocks(system);

  // Forces that the central scheme evaluates once at (t, q, v); implicit springs are evaluated
  // at the iterate (update_springs)
  if (scheme == IntegratorScheme::kCentral) {
    w.external.setZero(n);
    system.add_applied_forces(t, system.coordinates(), w.v_pred, w.external,
                              settings_.springs == SpringTreatment::kExplicit);
    system.add_inertial_forces(system.coordinates(), w.v_pred, w.external);
  }

  // Linearly implicit solve, then optional Newton iterations. Initial guess: zero when every
  // block is constant (one solve is exact for linear models); the last acceleration for Newmark
  // when some block is state-dependent, so that the terms the effective matrix leaves out
  // (d g / d qd, d(M a) / dq, geometric stiffness, state-dependent applied forces) enter the
  // linearly implicit step only through the O(dt) change of a, which keeps that step second
  // order. The guess is the same for every block, as when the system was factored whole, so a
  // constant model under state-dependent forces steps as it did then.
  const bool warm_start =
      any_state_dependent && scheme == IntegratorScheme::kNewmark && system.accelerations_valid();
  int iterations = settings_.newton_iterations;
  double tolerance = settings_.newton_tolerance;
  const bool automatic = any_state_dependent && automatic_newton_applies(settings_, system);
  if (automatic) {
    iterations = kAutomaticNewtonIterations;
    tolerance = kAutomaticNewtonTolerance;
  }
  // The automatic Newton iterates to its tolerance, so it may start from the factors the last
  // step ended with (IntegratorSettings::keep_factor_across_steps). Should that not converge
  // within the cap, or a factorization at an iterate fail, the step is solved again from its
  // predictor with the factor there, as without the setting.
  if (automatic && settings_.keep_factor_across_steps) {
    bool converged = false;
    try {
      converged = iterate(system, dt, warm_start, iterations, tolerance, FactorReuse::kAcrossSteps);
    } catch (const Error&) {
      converged = false;
    }
    if (!converged) {
      iterate(system, dt, warm_start, iterations, tolerance, FactorReuse::kNone);
    }
  } else {
    iterate(system, dt, warm_start, iterations, tolerance, FactorReuse::kNone);
  }

  // New state: q = q_pred "+" c_q a, v = v_store + c_v a; projection; finiteness
  w.increment = w.coefficients.position * w.a;
  w.q_new.resize(system.coordinate_count());
  system.advance_coordinates(w.q_pred, w.increment, w.q_new);
  w.v_new = w.v_store + w.coefficients.store * w.a;
  for (const int index : fixed) {
    w.v_new[index] = 0.0;
  }
  system.project_state(w.q_new, w.v_new);
  const int bad_q = first_non_finite(w.q_new);
  const int bad_v = first_non_finite(w.v_new);
  if (bad_q >= 0 || bad_v >= 0 || first_non_finite(w.a) >= 0) {
    throw make_error("the ", to_string(scheme), " step from t = ", t, " with dt = ", dt,
                     " produced a non-finite state (coordinate ", bad_q, ", velocity ", bad_v,
                     "); the state is unchanged");
  }
  system.commit_step(w.q_new, w.v_new, w.a, t + dt);
}

bool Integrator::iterate(const System& system, double dt, bool warm_start, int iterations,
                         double tolerance, FactorReuse first_reuse) {
  Workspace& w = *work_;
  if (warm_start) {
    w.a = system.accelerations();
    for (const int index : system.fixed_coordinates()) {
      w.a[index] = 0.0;
    }
  } else {
    w.a.setZero(system.velocity_count());
  }
  w.q_iter = w.q_pred;
  last_iterations_ = 0;
  double previous_correction = -1.0;
  for (int k = 0; k <= iterations; ++k) {
    const bool with_acceleration = k > 0 || warm_start;
    const int factorizations = factorization_count_;
    solve_iteration(system, dt, with_acceleration, previous_correction,
                    k == 0 ? first_reuse : FactorReuse::kWithinStep);
    last_iterations_ = k;
    const double correction = w.delta.norm();
    // The error left in a: |delta| before a contraction rate is known; after two corrections from
    // the same factor, whose rate is rho = |delta_k| / |delta_(k-1)| < 1, the geometric tail
    // rho / (1 - rho) |delta_k| (Hairer & Wanner, Solving Ordinary Differential Equations II,
    // section IV.8, eq. 8.10).
    double remaining = correction;
    if (previous_correction > 0.0 && factorization_count_ == factorizations &&
        correction < previous_correction) {
      const double rate = correction / previous_correction;
      remaining = rate / (1.0 - rate) * correction;
    }
    previous_correction = correction;
    if (with_acceleration && remaining <= tolerance * std::max(w.a.norm(), 1e-300)) {
      return true;
    }
  }
  return false;
}

bool Integrator::factor_constant_blocks(const System& system) {
  // Constant blocks of A: factored once per dt and scheme
  Workspace& w = *work_;
  const StepCoefficients& c = w.coefficients;
  w.blocks.layout(system, low_rank_settings(settings_));
  bool refactored = false;
  bool any_state_dependent = false;
  for (const auto& block : w.blocks.blocks) {
    if (!block->constant) {
      any_state_dependent = true;
    } else if (!block->factored || block->position_coefficient != c.position ||
               block->velocity_coefficient != c.velocity) {
      block->factor(system, c.velocity, c.position,
                    settings_.springs == SpringTreatment::kRefactor);
      ++factorization_count_;
      refactored = true;
    }
  }
  if (refactored) {
    ++factorization_serial_;
  }
  return any_state_dependent;
}

void Integrator::solve_iteration(const System& system, double dt, bool with_acceleration,
                                 double previous_correction, FactorReuse reuse) {
  Workspace& w = *work_;
  const StepCoefficients& c = w.coefficients;
  if (with_acceleration) {
    w.increment = c.position * w.a;
    system.advance_coordinates(w.q_pred, w.increment, w.q_iter);
  }
  w.v_iter = w.v_pred + c.velocity * w.a;
  // State-dependent blocks: iterates stay admissible (free weights above their minimum); the
  // springs' terms follow the iterate; then those blocks are re-assembled and re-factored at it.
  for (const auto& block : w.blocks.blocks) {
    if (!block->constant) {
      system.model(block->model)
          .project_state(w.q_iter.segment(block->coordinate_offset, block->coordinate_count),
                         w.v_iter.segment(block->velocity_offset, block->velocity_count));
    }
  }
  update_springs(system);
  // b = f + g + f_int(q) - D v - M a at the iterate, block by block (a = 0 before the first
  // solve without a warm start). The springs' pull k L^T (target - x) is in b where the spring
  // terms carry no target (a solve hook, kRefactor) or the springs are explicit.
  const bool explicit_springs = settings_.springs == SpringTreatment::kExplicit;
  const bool central = settings_.scheme == IntegratorScheme::kCentral;
  if (central) {
    w.rhs = w.external;
  } else {
    w.rhs.setZero(system.velocity_count());
    system.add_applied_forces(c.force_time, w.q_iter, w.v_iter, w.rhs, explicit_springs);
  }
  if (assemble_state_dependent_blocks(system, reuse)) {
    ++factorization_serial_;
  }
  for (const auto& block : w.blocks.blocks) {
    if (!central && !block->fused) {
      system.model(block->model)
          .add_inertial_force(w.q_iter.segment(block->coordinate_offset, block->coordinate_count),
                              w.v_iter.segment(block->velocity_offset, block->velocity_count),
                              w.rhs.segment(block->velocity_offset, block->velocity_count));
    }
  }
  if (!explicit_springs && (hook_ || settings_.springs == SpringTreatment::kRefactor)) {
    system.add_spring_forces(c.force_time, w.q_iter, w.rhs);
  }
  subtract_block_terms(system, with_acceleration, w);
  solve_step_system(system, dt);
  // Modified Newton: a correction from a kept factor that does not contract by kNewtonStallRatio
  // is discarded; the blocks are factored at this iterate and the same residual solved again
  // (a Newton correction, as the reference path takes at every iterate).
  if (previous_correction >= 0.0 && w.delta.norm() > kNewtonStallRatio * previous_correction &&
      refactor_reused_blocks(system)) {
    solve_step_system(system, dt);
  }
  w.a += w.delta;
}

bool Integrator::refactor_reused_blocks(const System& system) {
  Workspace& w = *work_;
  const StepCoefficients& c = w.coefficients;
  bool factored = false;
  for (const auto& block : w.blocks.blocks) {
    if (!block->reused) {
      continue;
    }
    system.model(block->model)
        .assemble_matrices(w.q_iter.segment(block->coordinate_offset, block->coordinate_count),
                           block->matrices);
    if (!block->factor_lean(c.velocity, c.position, block->lean.is_supernodal())) {
      block->factor(system, c.velocity, c.position, /*fold_springs=*/false);
    }
    block->reused = false;
    ++factorization_count_;
    factored = true;
  }
  if (factored) {
    ++factorization_serial_;
  }
  return factored;
}

void Integrator::solve_step_system(const System& system, double dt) {
  Workspace& w = *work_;
  const StepCoefficients& c = w.coefficients;
  const std::vector<int>& fixed = system.fixed_coordinates();
  if (hook_) {
    StepSystem step_system;
    step_system.time = c.force_time;
    step_system.dt = dt;
    step_system.position_coefficient = c.position;
    step_system.velocity_coefficient = c.velocity;
    step_system.predicted_coordinates = &w.q_iter;
    step_system.predicted_velocities = &w.v_iter;
    step_system.state_time = system.time() + dt;
    step_system.acceleration = &w.a;
    step_system.factorization_serial = factorization_serial_;
    step_system.fixed_coordinates = &fixed;
    step_system.rhs = &w.rhs;
    step_system.solve = [&w](const Eigen::VectorXd& r, Eigen::VectorXd& x) {
      w.blocks.solve(r, x);
    };
    hook_(step_system, w.delta);
    for (const int index : fixed) {
      w.delta[index] = 0.0;
    }
  } else {
    w.blocks.solve(w.rhs, w.delta);
  }
}

bool Integrator::assemble_state_dependent_blocks(const System& system, FactorReuse reuse) {
  Workspace& w = *work_;
  const StepCoefficients& c = w.coefficients;
  const bool fold_springs = settings_.springs == SpringTreatment::kRefactor;
  const bool central = settings_.scheme == IntegratorScheme::kCentral;
  const SparseCholeskySettings& cholesky = settings_.cholesky;
  bool factored = false;
  for (const auto& block : w.blocks.blocks) {
    if (block->constant) {
      continue;
    }
    const Model& model = system.model(block->model);
    const auto q = w.q_iter.segment(block->coordinate_offset, block->coordinate_count);
    const auto v = w.v_iter.segment(block->velocity_offset, block->velocity_count);
    auto rhs = w.rhs.segment(block->velocity_offset, block->velocity_count);
    // The lean factorization serves blocks without spring terms, by CHOLMOD where the backend
    // setting picks the supernodal factorization
    const bool supernodal =
        resolve_backend(cholesky, block->free.free_count()) == CholeskyBackend::kCholmodSupernodal;
    const bool lean = settings_.lean_step && block->springs.term_count() == 0;
    block->fused = settings_.lean_step;
    block->reused =
        lean && block->lean_active &&
        (reuse == FactorReuse::kWithinStep ||
         (reuse == FactorReuse::kAcrossSteps && model.needs_newton_iterations() &&
          block->position_coefficient == c.position && block->velocity_coefficient == c.velocity));
    if (block->reused) {
      // Modified Newton: the factor of an earlier iterate, the residual without the matrices
      model.add_step_residual(q, v, w.a.segment(block->velocity_offset, block->velocity_count),
                              !central, rhs);
      continue;
    }
    if (block->fused) {
      // One pass: M, D, K and b's f_int (+ g; the central scheme has g in `external`)
      model.assemble_step(q, v, !central, block->matrices, rhs);
    } else {
      model.assemble_matrices(q, block->matrices);
    }
    if (!lean || !block->factor_lean(c.velocity, c.position, supernodal)) {
      block->factor(system, c.velocity, c.position, fold_springs);
    }
    ++factorization_count_;
    factored = true;
  }
  return factored;
}

bool Integrator::update_springs(const System& system) {
  if (settings_.springs == SpringTreatment::kExplicit) {
    return false;
  }
  Workspace& w = *work_;
  const StepCoefficients& c = w.coefficients;
  const bool refactor = settings_.springs == SpringTreatment::kRefactor;
  // Target form unless a hook needs A^{-1} as a linear map (implicit_springs.h)
  const bool target_form = !refactor && !hook_;
  bool changed = false;
  for (const auto& block : w.blocks.blocks) {
    if (block->free.free_count() == 0) {
      continue;  // nothing to solve: the springs pull on fixed coordinates only
    }
    const bool block_changed =
        block->springs.update(system, block->spring_layout(), c.force_time, w.q_iter, c.position,
                              target_form, refactor ? nullptr : &block->solver);
    if (block_changed && refactor && block->constant) {
      block->factor(system, c.velocity, c.position, /*fold_springs=*/true);
      ++factorization_count_;
    }
    changed = changed || block_changed;
  }
  if (changed) {
    ++factorization_serial_;
  }
  return changed;
}

}  // namespace dnurbs
