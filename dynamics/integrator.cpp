#include "dynamics/integrator.h"

#include <cmath>

#include <Eigen/SparseCholesky>

#include "nurbs/error.h"

namespace dnurbs {

namespace {

using RowMatrixX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using NodeMap = Eigen::Map<RowMatrixX3>;
using ConstNodeMap = Eigen::Map<const RowMatrixX3>;

// Rows and columns of A whose index maps to a free index (>= 0), in order.
SparseMatrix reduce(const SparseMatrix& matrix, const std::vector<int>& free_index,
                    int free_count) {
  if (free_count == matrix.rows()) {
    return matrix;
  }
  SparseMatrix result(free_count, free_count);
  Eigen::VectorXi sizes = Eigen::VectorXi::Zero(free_count);
  for (Eigen::Index j = 0; j < matrix.outerSize(); ++j) {
    const int fj = free_index[static_cast<size_t>(j)];
    if (fj < 0) {
      continue;
    }
    for (SparseMatrix::InnerIterator it(matrix, j); it; ++it) {
      sizes[fj] += free_index[static_cast<size_t>(it.row())] >= 0 ? 1 : 0;
    }
  }
  result.reserve(sizes);
  for (Eigen::Index j = 0; j < matrix.outerSize(); ++j) {
    const int fj = free_index[static_cast<size_t>(j)];
    if (fj < 0) {
      continue;
    }
    for (SparseMatrix::InnerIterator it(matrix, j); it; ++it) {
      const int fi = free_index[static_cast<size_t>(it.row())];
      if (fi >= 0) {
        result.insert(fi, fj) = it.value();
      }
    }
  }
  result.makeCompressed();
  return result;
}

// M + c_D D + c_K K (an empty D is skipped).
SparseMatrix effective_matrix(const ModelMatrices& matrices, double damping_coefficient,
                              double stiffness_coefficient) {
  SparseMatrix result = matrices.mass + stiffness_coefficient * matrices.stiffness;
  if (matrices.damping.nonZeros() > 0) {
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

// Factorization of A on the free coordinates and the work vectors of a step, kept between
// steps. In the Kronecker layout the unknowns are nodes (3 velocities each) and right-hand
// sides are node-by-3 matrices.
struct Integrator::Workspace {
  // What the factorization was built for.
  bool factored = false;
  bool constant = false;
  bool kronecker = false;
  std::uint64_t revision = 0;
  double position_coefficient = 0.0;
  double velocity_coefficient = 0.0;
  // Elimination of fixed coordinates: free_index[k] >= 0 for free unknowns (nodes in the
  // Kronecker layout, velocities otherwise), free_list the inverse map.
  std::vector<int> free_index;
  std::vector<int> free_list;
  Eigen::SimplicialLDLT<SparseMatrix> solver;
  SparseMatrix analyzed_pattern;  // reduced A whose pattern the solver has analyzed
  // Work vectors.
  ModelMatrices matrices;
  Eigen::VectorXd q_pred, v_pred, v_store, a, delta, rhs, q_iter, v_iter, external, increment;
  Eigen::VectorXd q_new, v_new;
  Eigen::MatrixXd rhs_free, x_free;

  void set_free(const std::vector<int>& fixed, int unknowns, int block) {
    free_index.assign(static_cast<size_t>(unknowns), 0);
    for (const int index : fixed) {
      free_index[static_cast<size_t>(index / block)] = -1;
    }
    free_list.clear();
    for (int k = 0; k < unknowns; ++k) {
      if (free_index[static_cast<size_t>(k)] >= 0) {
        free_index[static_cast<size_t>(k)] = static_cast<int>(free_list.size());
        free_list.push_back(k);
      }
    }
  }

  void factor(const SparseMatrix& reduced) {
    if (!same_pattern(reduced, analyzed_pattern)) {
      solver.analyzePattern(reduced);
      analyzed_pattern = reduced;
    }
    solver.factorize(reduced);
    if (solver.info() != Eigen::Success) {
      throw make_error("the effective matrix A = M + c D + c' K (", reduced.rows(),
                       " free unknowns) could not be factored: is some free coordinate without "
                       "mass?");
    }
  }

  // x = A_ff^{-1} r on the free unknowns, zero on the fixed ones.
  void solve(const Eigen::VectorXd& r, Eigen::VectorXd& x) {
    x.setZero(r.size());
    const auto free_count = static_cast<Eigen::Index>(free_list.size());
    if (kronecker) {
      const ConstNodeMap R(r.data(), r.size() / 3, 3);
      NodeMap X(x.data(), x.size() / 3, 3);
      rhs_free.resize(free_count, 3);
      for (Eigen::Index i = 0; i < free_count; ++i) {
        rhs_free.row(i) = R.row(free_list[static_cast<size_t>(i)]);
      }
      x_free = solver.solve(rhs_free);
      for (Eigen::Index i = 0; i < free_count; ++i) {
        X.row(free_list[static_cast<size_t>(i)]) = x_free.row(i);
      }
    } else {
      rhs_free.resize(free_count, 1);
      for (Eigen::Index i = 0; i < free_count; ++i) {
        rhs_free(i, 0) = r[free_list[static_cast<size_t>(i)]];
      }
      x_free = solver.solve(rhs_free);
      for (Eigen::Index i = 0; i < free_count; ++i) {
        x[free_list[static_cast<size_t>(i)]] = x_free(i, 0);
      }
    }
  }
};

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

void Integrator::initial_acceleration(System& system) {
  // M a = f + g + f_int - D v at the current state, on the free coordinates.
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
  ModelMatrices matrices;
  system.assemble_matrices(q, matrices);
  if (matrices.damping.nonZeros() > 0) {
    rhs.noalias() -= matrices.damping * v;
  }
  Workspace mass_work;
  mass_work.set_free(system.fixed_coordinates(), n, 1);
  mass_work.factor(
      reduce(matrices.mass, mass_work.free_index, static_cast<int>(mass_work.free_list.size())));
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
    step_system.solve = [&mass_work](const Eigen::VectorXd& r, Eigen::VectorXd& x) {
      mass_work.solve(r, x);
    };
    hook_(step_system, a);
  } else {
    mass_work.solve(rhs, a);
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

  // Step coefficients of the scheme ------------------------------------------------------------
  double position_coefficient = dt * dt;
  double velocity_coefficient = dt;
  double store_coefficient = dt;
  double force_time = t + dt;
  double predictor_acceleration_q = 0.0;
  double predictor_acceleration_v = 0.0;
  if (scheme == IntegratorScheme::kNewmark) {
    const double beta = settings_.newmark_beta;
    const double gamma = settings_.newmark_gamma;
    position_coefficient = beta * dt * dt;
    velocity_coefficient = gamma * dt;
    store_coefficient = gamma * dt;
    predictor_acceleration_q = (0.5 - beta) * dt * dt;
    predictor_acceleration_v = (1.0 - gamma) * dt;
    if (!system.accelerations_valid()) {
      initial_acceleration(system);
    }
  } else if (scheme == IntegratorScheme::kCentral) {
    velocity_coefficient = 0.5 * dt;  // (q(t+dt) - q(t-dt)) / (2 dt) = v + dt a / 2
    force_time = t;
  }

  // Predictor ---------------------------------------------------------------------------------
  const Eigen::VectorXd& q = system.coordinates();
  w.v_pred = system.velocities();
  for (const int index : fixed) {
    w.v_pred[index] = 0.0;
  }
  w.increment = dt * w.v_pred;
  if (scheme == IntegratorScheme::kNewmark) {
    const Eigen::VectorXd& a_old = system.accelerations();
    w.increment += predictor_acceleration_q * a_old;
    w.v_pred += predictor_acceleration_v * a_old;
    for (const int index : fixed) {
      w.increment[index] = 0.0;
      w.v_pred[index] = 0.0;
    }
  }
  // Central stores v + dt a but damps with v + dt a / 2; the others store what they damp with.
  w.v_store = w.v_pred;
  w.q_pred.resize(system.coordinate_count());
  system.advance_coordinates(q, w.increment, w.q_pred);

  // Factorization of A (constant matrices: once per dt and scheme) ---------------------------
  const bool constant = system.matrices_are_constant();
  const bool kronecker = constant && system.kronecker_block_size() == 3 && [&] {
    for (size_t i = 0; i < fixed.size(); i += 3) {
      if (i + 2 >= fixed.size() || fixed[i] % 3 != 0 || fixed[i + 1] != fixed[i] + 1 ||
          fixed[i + 2] != fixed[i] + 2) {
        return false;
      }
    }
    return true;
  }();
  const bool reuse = w.factored && w.constant && constant && w.kronecker == kronecker &&
                     w.revision == system.revision() &&
                     w.position_coefficient == position_coefficient &&
                     w.velocity_coefficient == velocity_coefficient;
  if (!reuse) {
    w.factored = false;
    w.constant = constant;
    w.kronecker = kronecker;
    w.revision = system.revision();
    w.position_coefficient = position_coefficient;
    w.velocity_coefficient = velocity_coefficient;
    if (kronecker) {
      w.set_free(fixed, n / 3, 3);
      w.factor(reduce(
          effective_matrix(*system.scalar_matrices(), velocity_coefficient, position_coefficient),
          w.free_index, static_cast<int>(w.free_list.size())));
      ++factorization_count_;
      ++factorization_serial_;
      w.factored = true;
    } else {
      w.set_free(fixed, n, 1);
      if (constant) {
        w.factor(reduce(effective_matrix(*system.constant_matrices(), velocity_coefficient,
                                         position_coefficient),
                        w.free_index, static_cast<int>(w.free_list.size())));
        ++factorization_count_;
        ++factorization_serial_;
        w.factored = true;
      }
    }
  }

  // Forces that the central scheme evaluates once at (t, q, v) ---------------------------------
  const bool central = scheme == IntegratorScheme::kCentral;
  if (central) {
    w.external.setZero(n);
    system.add_applied_forces(t, q, w.v_pred, w.external);
    system.add_inertial_forces(q, w.v_pred, w.external);
  }

  // Linearly implicit solve, then optional Newton iterations ----------------------------------
  // Initial guess: zero for constant matrices (one solve is exact for linear models); the last
  // acceleration for Newmark with state-dependent matrices, so that the terms the effective
  // matrix leaves out (d g / d qd, d(M a) / dq, geometric stiffness) enter the linearly
  // implicit step only through the O(dt) change of a, which keeps that step second order.
  const bool warm_start =
      !constant && scheme == IntegratorScheme::kNewmark && system.accelerations_valid();
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
  const int iterations = settings_.newton_iterations;
  for (int k = 0; k <= iterations; ++k) {
    if (k > 0 || warm_start) {
      w.increment = position_coefficient * w.a;
      system.advance_coordinates(w.q_pred, w.increment, w.q_iter);
    }
    w.v_iter = w.v_pred + velocity_coefficient * w.a;
    if (!constant) {
      // Iterates stay admissible too (free weights above their minimum).
      system.project_state(w.q_iter, w.v_iter);
    }
    const ModelMatrices* matrices = system.constant_matrices();
    if (!constant) {
      system.assemble_matrices(w.q_iter, w.matrices);
      matrices = &w.matrices;
      w.factor(reduce(effective_matrix(w.matrices, velocity_coefficient, position_coefficient),
                      w.free_index, static_cast<int>(w.free_list.size())));
      ++factorization_count_;
      ++factorization_serial_;
    }

    // b = f + g + f_int(q) - D v - M a at the iterate.
    if (central) {
      w.rhs = w.external;
    } else {
      w.rhs.setZero(n);
      system.add_applied_forces(force_time, w.q_iter, w.v_iter, w.rhs);
      system.add_inertial_forces(w.q_iter, w.v_iter, w.rhs);
    }
    if (kronecker) {
      const ModelMatrices& scalar = *system.scalar_matrices();
      NodeMap R(w.rhs.data(), n / 3, 3);
      R.noalias() -= scalar.stiffness * ConstNodeMap(w.q_iter.data(), n / 3, 3);
      if (scalar.damping.nonZeros() > 0) {
        R.noalias() -= scalar.damping * ConstNodeMap(w.v_iter.data(), n / 3, 3);
      }
      if (k > 0) {
        R.noalias() -= scalar.mass * ConstNodeMap(w.a.data(), n / 3, 3);
      }
    } else {
      system.add_internal_forces(w.q_iter, w.rhs);
      if (matrices->damping.nonZeros() > 0) {
        w.rhs.noalias() -= matrices->damping * w.v_iter;
      }
      if (k > 0 || warm_start) {
        w.rhs.noalias() -= matrices->mass * w.a;
      }
    }

    if (hook_) {
      StepSystem step_system;
      step_system.time = force_time;
      step_system.dt = dt;
      step_system.position_coefficient = position_coefficient;
      step_system.velocity_coefficient = velocity_coefficient;
      step_system.predicted_coordinates = &w.q_iter;
      step_system.predicted_velocities = &w.v_iter;
      step_system.state_time = t + dt;
      step_system.acceleration = &w.a;
      step_system.factorization_serial = factorization_serial_;
      step_system.fixed_coordinates = &fixed;
      step_system.rhs = &w.rhs;
      step_system.solve = [&w](const Eigen::VectorXd& r, Eigen::VectorXd& x) { w.solve(r, x); };
      hook_(step_system, w.delta);
      for (const int index : fixed) {
        w.delta[index] = 0.0;
      }
    } else {
      w.solve(w.rhs, w.delta);
    }
    w.a += w.delta;
    last_iterations_ = k;
    if ((k > 0 || warm_start) &&
        w.delta.norm() <= settings_.newton_tolerance * std::max(w.a.norm(), 1e-300)) {
      break;
    }
  }

  // New state: q = q_pred "+" c_q a, v = v_store + c_v a; projection; finiteness -------------
  w.increment = position_coefficient * w.a;
  w.q_new.resize(system.coordinate_count());
  system.advance_coordinates(w.q_pred, w.increment, w.q_new);
  w.v_new = w.v_store + store_coefficient * w.a;
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

}  // namespace dnurbs
