#include "dynamics/integrators/integrator.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/SparseCholesky>

#include "core/error.h"
#include "core/fixed_coordinates.h"
#include "core/kronecker.h"

namespace dnurbs {

namespace {

using RowMatrixX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using NodeMap = Eigen::Map<RowMatrixX3>;
using ConstNodeMap = Eigen::Map<const RowMatrixX3>;

// M + c_D D + c_K K (an empty D and zero coefficients are skipped, so that c_D = c_K = 0
// factors M with its own pattern).
SparseMatrix effective_matrix(const ModelMatrices& matrices, double damping_coefficient,
                              double stiffness_coefficient) {
  SparseMatrix result = matrices.mass;
  if (stiffness_coefficient != 0.0) {
    result += stiffness_coefficient * matrices.stiffness;
  }
  if (damping_coefficient != 0.0 && matrices.damping.nonZeros() > 0) {
    result += damping_coefficient * matrices.damping;
  }
  return result;
}

bool same_pattern(const SparseMatrix& a, const SparseMatrix& b) {
  if (a.rows() != b.rows() || a.nonZeros() != b.nonZeros() || !a.isCompressed() ||
      !b.isCompressed()) {
    return false;
  }
  return std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
}

int first_non_finite(const Eigen::VectorXd& x) {
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i])) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

// One diagonal block of A: the velocities of one model (the System's matrices are block
// diagonal by model, so A^{-1} r is the per-block solves stacked). Fixed coordinates are
// eliminated inside the block; a constant model with the S (x) I_3 structure whose fixed
// coordinates come in node triples is factored as its scalar matrix with x, y, z as three
// right-hand sides (the Kronecker layout: unknowns are nodes, right-hand sides node-by-3).
struct MatrixBlock {
  int model = 0;
  int coordinate_offset = 0;
  int coordinate_count = 0;
  int velocity_offset = 0;
  int velocity_count = 0;
  bool constant = false;
  bool kronecker = false;
  // The coefficients the factorization was built for (constant blocks reuse it).
  bool factored = false;
  double position_coefficient = 0.0;
  double velocity_coefficient = 0.0;
  int factorizations = 0;
  // The free unknowns of the block (nodes in the Kronecker layout, velocities otherwise).
  FreeCoordinates free;
  Eigen::SimplicialLDLT<SparseMatrix> solver;
  SparseMatrix analyzed_pattern;  // reduced block whose pattern the solver has analyzed
  ModelMatrices matrices;         // state-dependent blocks: M, D, K at the current iterate
  Eigen::MatrixXd rhs_free, x_free;

  MatrixBlock(const System& system, int index) : model(index) {
    const Model& m = system.model(index);
    coordinate_offset = system.coordinate_offset(index);
    coordinate_count = m.coordinate_count();
    velocity_offset = system.velocity_offset(index);
    velocity_count = m.velocity_count();
    constant = m.matrices_are_constant() && m.constant_matrices() != nullptr;
    const std::vector<int>& fixed = m.fixed_coordinates();
    const std::optional<std::vector<int>> nodes = fixed_nodes(fixed, 3);
    kronecker = constant && m.kronecker_block_size() == 3 && m.scalar_matrices() != nullptr &&
                velocity_count % 3 == 0 && coordinate_count == velocity_count && nodes;
    free = kronecker ? FreeCoordinates(velocity_count / 3, *nodes)
                     : FreeCoordinates(velocity_count, fixed);
  }

  // The model's full (velocity-space) matrices: the constant ones, or those last assembled.
  const ModelMatrices& full_matrices(const System& system) const {
    return constant ? *system.model(model).constant_matrices() : matrices;
  }

  // Factors M + c_D D + c_K K of the block (the scalar matrices in the Kronecker layout, which
  // constant blocks take from the model; state-dependent blocks from `matrices`). A block whose
  // factorization throws stays unfactored.
  void factor(const System& system, double damping_coefficient, double stiffness_coefficient) {
    const ModelMatrices& source =
        kronecker ? *system.model(model).scalar_matrices() : full_matrices(system);
    factored = false;
    ++factorizations;
    if (free.free_count() > 0) {
      factor_free(source, damping_coefficient, stiffness_coefficient);
    }
    position_coefficient = stiffness_coefficient;
    velocity_coefficient = damping_coefficient;
    factored = true;
  }

  // SimplicialLDLT of the free rows and columns (the pattern analyzed only when it changes).
  void factor_free(const ModelMatrices& source, double damping_coefficient,
                   double stiffness_coefficient) {
    const SparseMatrix reduced =
        free.reduce(effective_matrix(source, damping_coefficient, stiffness_coefficient));
    if (!same_pattern(reduced, analyzed_pattern)) {
      solver.analyzePattern(reduced);
      analyzed_pattern = reduced;
    }
    solver.factorize(reduced);
    if (solver.info() != Eigen::Success) {
      throw make_error("the effective matrix A = M + c D + c' K of model ", model, " (",
                       reduced.rows(),
                       " free unknowns) could not be factored: is some free coordinate without "
                       "mass?");
    }
  }

  // x = A_ff^{-1} r on the block's free unknowns, zero on its fixed ones (block segments of the
  // stacked vectors).
  void solve(const Eigen::VectorXd& r, Eigen::VectorXd& x) {
    const auto free_count = static_cast<Eigen::Index>(free.free_count());
    if (free_count == 0) {
      return;
    }
    if (kronecker) {
      const ConstNodeMap R(r.data() + velocity_offset, velocity_count / 3, 3);
      NodeMap X(x.data() + velocity_offset, velocity_count / 3, 3);
      rhs_free.resize(free_count, 3);
      for (Eigen::Index i = 0; i < free_count; ++i) {
        rhs_free.row(i) = R.row(free.free_unknown(static_cast<int>(i)));
      }
      x_free = solver.solve(rhs_free);
      for (Eigen::Index i = 0; i < free_count; ++i) {
        X.row(free.free_unknown(static_cast<int>(i))) = x_free.row(i);
      }
    } else {
      rhs_free.resize(free_count, 1);
      for (Eigen::Index i = 0; i < free_count; ++i) {
        rhs_free(i, 0) = r[velocity_offset + free.free_unknown(static_cast<int>(i))];
      }
      x_free = solver.solve(rhs_free);
      for (Eigen::Index i = 0; i < free_count; ++i) {
        x[velocity_offset + free.free_unknown(static_cast<int>(i))] = x_free(i, 0);
      }
    }
  }
};

// The blocks of one System layout (rebuilt when the System's revision or size changes).
struct MatrixBlocks {
  bool laid_out = false;
  std::uint64_t revision = 0;
  int velocity_count = 0;
  std::vector<std::unique_ptr<MatrixBlock>> blocks;

  void layout(const System& system) {
    if (laid_out && revision == system.revision() && velocity_count == system.velocity_count() &&
        static_cast<int>(blocks.size()) == system.model_count()) {
      return;
    }
    blocks.clear();
    for (int i = 0; i < system.model_count(); ++i) {
      blocks.push_back(std::make_unique<MatrixBlock>(system, i));
    }
    laid_out = true;
    revision = system.revision();
    velocity_count = system.velocity_count();
  }

  // x = A^{-1} r block by block (zero on fixed coordinates).
  void solve(const Eigen::VectorXd& r, Eigen::VectorXd& x) {
    x.setZero(r.size());
    for (const auto& block : blocks) {
      block->solve(r, x);
    }
  }
};

}  // namespace

IntegratorScheme parse_integrator_scheme(std::string_view name) {
  if (name == "central") {
    return IntegratorScheme::kCentral;
  }
  if (name == "implicit-euler") {
    return IntegratorScheme::kImplicitEuler;
  }
  if (name == "newmark") {
    return IntegratorScheme::kNewmark;
  }
  throw make_error("unknown integrator '", std::string(name),
                   "' (expected central, implicit-euler or newmark)");
}

std::string_view to_string(IntegratorScheme scheme) {
  switch (scheme) {
    case IntegratorScheme::kCentral:
      return "central";
    case IntegratorScheme::kImplicitEuler:
      return "implicit-euler";
    case IntegratorScheme::kNewmark:
      return "newmark";
  }
  return "unknown";
}

// The blocks of A and the work vectors of a step, kept between steps.
namespace {

// The coefficients of one step of a scheme (integrator.h's header comment).
struct StepCoefficients {
  double position = 0.0;  // q_new = q_pred "+" position a
  double velocity = 0.0;  // v_eq = v_pred + velocity a
  double store = 0.0;     // v_new = v_store + store a
  double force_time = 0.0;
  double predictor_acceleration_q = 0.0;  // Newmark: q_pred gets (1/2 - beta) dt^2 a_old
  double predictor_acceleration_v = 0.0;  // and v_pred (1 - gamma) dt a_old
};

StepCoefficients step_coefficients(const IntegratorSettings& settings, double t, double dt) {
  StepCoefficients c;
  c.position = dt * dt;
  c.velocity = dt;
  c.store = dt;
  c.force_time = t + dt;
  if (settings.scheme == IntegratorScheme::kNewmark) {
    const double beta = settings.newmark_beta;
    const double gamma = settings.newmark_gamma;
    c.position = beta * dt * dt;
    c.velocity = gamma * dt;
    c.store = gamma * dt;
    c.predictor_acceleration_q = (0.5 - beta) * dt * dt;
    c.predictor_acceleration_v = (1.0 - gamma) * dt;
  } else if (settings.scheme == IntegratorScheme::kCentral) {
    c.velocity = 0.5 * dt;  // (q(t+dt) - q(t-dt)) / (2 dt) = v + dt a / 2
    c.force_time = t;
  }
  return c;
}

}  // namespace

struct Integrator::Workspace {
  MatrixBlocks blocks;
  StepCoefficients coefficients;
  Eigen::VectorXd q_pred, v_pred, v_store, a, delta, rhs, q_iter, v_iter, external, increment;
  Eigen::VectorXd q_new, v_new;
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
      const ModelMatrices& scalar = *system.model(block->model).scalar_matrices();
      const Eigen::Index nodes = vc / 3;
      NodeMap R(w.rhs.data() + vo, nodes, 3);
      R.noalias() -=
          scalar.stiffness * ConstNodeMap(w.q_iter.data() + block->coordinate_offset, nodes, 3);
      if (scalar.damping.nonZeros() > 0) {
        R.noalias() -= scalar.damping * ConstNodeMap(w.v_iter.data() + vo, nodes, 3);
      }
      if (with_acceleration) {
        R.noalias() -= scalar.mass * ConstNodeMap(w.a.data() + vo, nodes, 3);
      }
    } else {
      system.model(block->model)
          .add_internal_force(w.q_iter.segment(block->coordinate_offset, block->coordinate_count),
                              w.rhs.segment(vo, vc));
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
  const MatrixBlocks& blocks = work_->blocks;
  if (model < 0 || model >= static_cast<int>(blocks.blocks.size())) {
    throw make_error("model index ", model, " is outside the ", blocks.blocks.size(),
                     " blocks of the last stepped system");
  }
  return blocks.blocks[static_cast<size_t>(model)]->factorizations;
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
  MatrixBlocks mass_blocks;
  mass_blocks.layout(system);
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
    block->factor(system, 0.0, 0.0);
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
  w.coefficients = step_coefficients(settings_, t, dt);
  if (scheme == IntegratorScheme::kNewmark && !system.accelerations_valid()) {
    initial_acceleration(system);
  }
  predict(system, scheme == IntegratorScheme::kNewmark, dt, w);
  const bool any_state_dependent = factor_constant_blocks(system);

  // Forces that the central scheme evaluates once at (t, q, v)
  if (scheme == IntegratorScheme::kCentral) {
    w.external.setZero(n);
    system.add_applied_forces(t, system.coordinates(), w.v_pred, w.external);
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
  if (warm_start) {
    w.a = system.accelerations();
    for (const int index : fixed) {
      w.a[index] = 0.0;
    }
  } else {
    w.a.setZero(n);
  }
  w.q_iter = w.q_pred;
  last_iterations_ = 0;
  for (int k = 0; k <= settings_.newton_iterations; ++k) {
    const bool with_acceleration = k > 0 || warm_start;
    solve_iteration(system, dt, with_acceleration);
    last_iterations_ = k;
    if (with_acceleration &&
        w.delta.norm() <= settings_.newton_tolerance * std::max(w.a.norm(), 1e-300)) {
      break;
    }
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

bool Integrator::factor_constant_blocks(const System& system) {
  // Constant blocks of A: factored once per dt and scheme
  Workspace& w = *work_;
  const StepCoefficients& c = w.coefficients;
  w.blocks.layout(system);
  bool refactored = false;
  bool any_state_dependent = false;
  for (const auto& block : w.blocks.blocks) {
    if (!block->constant) {
      any_state_dependent = true;
    } else if (!block->factored || block->position_coefficient != c.position ||
               block->velocity_coefficient != c.velocity) {
      block->factor(system, c.velocity, c.position);
      ++factorization_count_;
      refactored = true;
    }
  }
  if (refactored) {
    ++factorization_serial_;
  }
  return any_state_dependent;
}

void Integrator::solve_iteration(const System& system, double dt, bool with_acceleration) {
  Workspace& w = *work_;
  const StepCoefficients& c = w.coefficients;
  const std::vector<int>& fixed = system.fixed_coordinates();
  if (with_acceleration) {
    w.increment = c.position * w.a;
    system.advance_coordinates(w.q_pred, w.increment, w.q_iter);
  }
  w.v_iter = w.v_pred + c.velocity * w.a;
  // State-dependent blocks: iterates stay admissible (free weights above their minimum), then
  // the block is re-assembled and re-factored at the iterate.
  bool assembled = false;
  for (const auto& block : w.blocks.blocks) {
    if (block->constant) {
      continue;
    }
    const Model& model = system.model(block->model);
    auto q_block = w.q_iter.segment(block->coordinate_offset, block->coordinate_count);
    auto v_block = w.v_iter.segment(block->velocity_offset, block->velocity_count);
    model.project_state(q_block, v_block);
    model.assemble_matrices(q_block, block->matrices);
    block->factor(system, c.velocity, c.position);
    ++factorization_count_;
    assembled = true;
  }
  if (assembled) {
    ++factorization_serial_;
  }
  // b = f + g + f_int(q) - D v - M a at the iterate, block by block (a = 0 before the first
  // solve without a warm start).
  if (settings_.scheme == IntegratorScheme::kCentral) {
    w.rhs = w.external;
  } else {
    w.rhs.setZero(system.velocity_count());
    system.add_applied_forces(c.force_time, w.q_iter, w.v_iter, w.rhs);
    system.add_inertial_forces(w.q_iter, w.v_iter, w.rhs);
  }
  subtract_block_terms(system, with_acceleration, w);
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
  w.a += w.delta;
}

}  // namespace dnurbs
