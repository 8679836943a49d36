#include "dnurbs/design/energy_minimization.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include <nlopt.hpp>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// NLopt's name of a result code ("XTOL_REACHED"; nlopt_result_to_string, NLopt >= 2.7), or
// "UNKNOWN" for a code it does not name.
const char* result_name(nlopt::result result) {
  const char* name = nlopt_result_to_string(static_cast<nlopt_result>(result));
  return name != nullptr ? name : "UNKNOWN";
}

// Velocity index -> stacked coordinate index of the same vector-space coordinate, or -1 where the
// velocity has no such coordinate (Model::velocity_coordinate: a superquadric's body angular
// velocity, whose orientation is a quaternion and is held).
std::vector<int> velocity_to_coordinate(const System& system) {
  std::vector<int> map(static_cast<size_t>(system.velocity_count()), -1);
  for (int i = 0; i < system.model_count(); ++i) {
    const Model& model = system.model(i);
    for (int v = 0; v < model.velocity_count(); ++v) {
      const int coordinate = model.velocity_coordinate(v);
      if (coordinate >= 0) {
        map[static_cast<size_t>(system.velocity_offset(i) + v)] =
            system.coordinate_offset(i) + coordinate;
      }
    }
  }
  return map;
}

// The optimization problem on the free coordinates: x = q[free], the rest held at q0.
struct Problem {
  const System* system = nullptr;
  const ConstraintSolver* constraints = nullptr;
  Eigen::VectorXd applied_force;
  Eigen::VectorXd start;
  std::vector<int> free;        // velocity index of each variable
  std::vector<int> variable;    // variable of each velocity index (-1 when held)
  std::vector<int> coordinate;  // stacked coordinate index of each velocity index (or -1)
  int evaluations = 0;
  const std::function<void(int, double)>* on_evaluation = nullptr;  // DesignSettings'
  // Scratch.
  Eigen::VectorXd q;
  Eigen::VectorXd gradient;
  ConstraintSolver::Evaluation evaluation;

  void set_point(const double* x) {
    q = start;
    for (size_t k = 0; k < free.size(); ++k) {
      q[coordinate[static_cast<size_t>(free[k])]] = x[k];
    }
  }
};

double objective(unsigned n, const double* x, double* grad, void* data) {
  auto& problem = *static_cast<Problem*>(data);
  ++problem.evaluations;
  problem.set_point(x);
  const double value = design_energy(*problem.system, problem.applied_force, problem.q,
                                     grad != nullptr ? &problem.gradient : nullptr);
  if (grad != nullptr) {
    for (unsigned k = 0; k < n; ++k) {
      grad[k] = problem.gradient[problem.free[k]];
    }
  }
  if (*problem.on_evaluation) {
    (*problem.on_evaluation)(problem.evaluations, value);
  }
  return value;
}

void equalities(unsigned m, double* result, unsigned n, const double* x, double* grad, void* data) {
  auto& problem = *static_cast<Problem*>(data);
  problem.set_point(x);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(problem.system->velocity_count());
  problem.constraints->evaluate(*problem.system, problem.q, zero, problem.system->time(),
                                problem.evaluation);
  for (unsigned i = 0; i < m; ++i) {
    result[i] = problem.evaluation.value[i];
  }
  if (grad != nullptr) {
    // NLopt wants the m by n Jacobian row-major: grad[i * n + k] = dC_i / dx_k.
    std::fill(grad, grad + static_cast<size_t>(m) * n, 0.0);
    const SparseMatrix& C_q = problem.evaluation.jacobian;
    for (Eigen::Index j = 0; j < C_q.outerSize(); ++j) {
      const int k = problem.variable[static_cast<size_t>(j)];
      if (k < 0) {
        continue;
      }
      for (SparseMatrix::InnerIterator it(C_q, j); it; ++it) {
        grad[static_cast<size_t>(it.row()) * n + static_cast<size_t>(k)] += it.value();
      }
    }
  }
}

}  // namespace

double design_energy(const System& system, const Eigen::VectorXd& applied_force,
                     const Eigen::VectorXd& q, Eigen::VectorXd* gradient) {
  const std::vector<int> coordinate = velocity_to_coordinate(system);
  double energy = 0.0;
  for (size_t v = 0; v < coordinate.size(); ++v) {
    if (coordinate[v] >= 0) {
      energy -= applied_force[static_cast<Eigen::Index>(v)] * q[coordinate[v]];
    }
  }
  for (int i = 0; i < system.model_count(); ++i) {
    energy += system.model(i).potential_energy(
        q.segment(system.coordinate_offset(i), system.model(i).coordinate_count()));
  }
  if (gradient != nullptr) {
    // dPi/dq = -f_int(q) - f.
    gradient->setZero(system.velocity_count());
    system.add_internal_forces(q, *gradient);
    *gradient += applied_force;
    *gradient = -*gradient;
  }
  return energy;
}

namespace {

void check_settings(const System& system, const DesignSettings& settings) {
  if (settings.max_evaluations <= 0) {
    throw make_error("design max_evaluations must be > 0 (it is ", settings.max_evaluations, ")");
  }
  if (!(settings.variable_tolerance >= 0.0) || !(settings.energy_tolerance >= 0.0) ||
      !(settings.constraint_tolerance >= 0.0) || !(settings.max_seconds >= 0.0)) {
    throw make_error("design tolerances and time limit must be >= 0 (variable ",
                     settings.variable_tolerance, ", energy ", settings.energy_tolerance,
                     ", constraint ", settings.constraint_tolerance, ", seconds ",
                     settings.max_seconds, ")");
  }
  if (!system.coordinates().allFinite()) {
    throw make_error("energy minimization cannot start from non-finite coordinates");
  }
}

// The free variables (velocities that are coordinates and not fixed), their starting values
// inside the bounds (x) and their lower bounds (Model::coordinate_lower_bounds).
void choose_variables(const System& system, Problem& problem, std::vector<double>& x,
                      std::vector<double>& lower_free) {
  const int n = system.velocity_count();
  Eigen::VectorXd bounds = Eigen::VectorXd::Constant(n, -HUGE_VAL);
  for (int i = 0; i < system.model_count(); ++i) {
    system.model(i).coordinate_lower_bounds(
        bounds.segment(system.velocity_offset(i), system.model(i).velocity_count()));
  }
  problem.coordinate = velocity_to_coordinate(system);
  problem.variable.assign(static_cast<size_t>(n), 0);
  for (const int index : system.fixed_coordinates()) {
    problem.variable[static_cast<size_t>(index)] = -1;
  }
  for (int j = 0; j < n; ++j) {
    if (problem.coordinate[static_cast<size_t>(j)] < 0) {
      problem.variable[static_cast<size_t>(j)] = -1;
    }
  }
  for (int j = 0; j < n; ++j) {
    if (problem.variable[static_cast<size_t>(j)] < 0) {
      continue;
    }
    problem.variable[static_cast<size_t>(j)] = static_cast<int>(problem.free.size());
    problem.free.push_back(j);
    // Start inside the bounds.
    x.push_back(std::max(problem.start[problem.coordinate[static_cast<size_t>(j)]], bounds[j]));
    lower_free.push_back(bounds[j]);
  }
}

// Runs NLopt from x (updated to the best point found); returns its status. NLopt's C++ API
// throws for failures but leaves the best point found in x.
nlopt::result optimize(Problem& problem, const DesignSettings& settings,
                       const std::vector<double>& lower_free, std::vector<double>& x) {
  const auto variable_count = static_cast<unsigned>(x.size());
  const bool auglag = settings.algorithm == DesignAlgorithm::kAugmentedLagrangianLbfgs;
  nlopt::opt optimizer(auglag ? nlopt::AUGLAG_EQ : nlopt::LD_SLSQP, variable_count);
  if (auglag) {
    nlopt::opt local(nlopt::LD_LBFGS, variable_count);
    local.set_xtol_rel(settings.variable_tolerance);
    local.set_ftol_rel(settings.energy_tolerance);
    local.set_maxeval(settings.max_evaluations);
    optimizer.set_local_optimizer(local);
  }
  optimizer.set_lower_bounds(lower_free);
  optimizer.set_min_objective(objective, &problem);
  optimizer.set_xtol_rel(settings.variable_tolerance);
  optimizer.set_ftol_rel(settings.energy_tolerance);
  optimizer.set_maxeval(settings.max_evaluations);
  if (settings.max_seconds > 0.0) {
    optimizer.set_maxtime(settings.max_seconds);
  }
  if (problem.constraints != nullptr) {
    const std::vector<double> tolerances(static_cast<size_t>(problem.constraints->row_count()),
                                         settings.constraint_tolerance);
    optimizer.add_equality_mconstraint(equalities, &problem, tolerances);
  }
  double value = 0.0;
  try {
    return optimizer.optimize(x, value);
  } catch (const nlopt::roundoff_limited&) {
    return nlopt::ROUNDOFF_LIMITED;
  } catch (const nlopt::forced_stop&) {
    return nlopt::FORCED_STOP;
  } catch (const std::invalid_argument& error) {
    throw make_error("NLopt rejected the design problem (", variable_count,
                     " variables): ", error.what());
  } catch (const std::bad_alloc&) {
    throw make_error("NLopt ran out of memory on a design problem of ", variable_count,
                     " variables");
  } catch (const std::runtime_error&) {
    return nlopt::FAILURE;
  }
}

}  // namespace

DesignResult minimize_energy(const System& system, const ConstraintSolver* constraints,
                             const DesignSettings& settings) {
  check_settings(system, settings);
  const int n = system.velocity_count();
  Problem problem;
  problem.system = &system;
  problem.on_evaluation = &settings.on_evaluation;
  problem.constraints =
      (constraints != nullptr && constraints->row_count() > 0) ? constraints : nullptr;
  problem.start = system.coordinates();
  problem.applied_force = Eigen::VectorXd::Zero(n);
  system.add_applied_forces(system.time(), problem.start, Eigen::VectorXd::Zero(n),
                            problem.applied_force);
  std::vector<double> x;
  std::vector<double> lower_free;
  choose_variables(system, problem, x, lower_free);

  DesignResult result;
  if (x.empty()) {
    result.coordinates = problem.start;
    result.energy = design_energy(system, problem.applied_force, problem.start, nullptr);
    result.status = static_cast<int>(nlopt::SUCCESS);
    result.status_name = "SUCCESS";
  } else {
    const nlopt::result status = optimize(problem, settings, lower_free, x);
    problem.set_point(x.data());
    result.coordinates = problem.q;
    result.energy = design_energy(system, problem.applied_force, problem.q, nullptr);
    result.status = static_cast<int>(status);
    result.status_name = result_name(status);
  }
  result.iterations = problem.evaluations;
  if (!result.coordinates.allFinite()) {
    throw make_error("energy minimization produced non-finite coordinates (NLopt status ",
                     result.status_name, ")");
  }
  if (problem.constraints != nullptr) {
    ConstraintSolver::Evaluation evaluation;
    problem.constraints->evaluate(system, result.coordinates, Eigen::VectorXd::Zero(n),
                                  system.time(), evaluation);
    result.constraint_violation = evaluation.value.cwiseAbs().maxCoeff();
  }
  return result;
}

}  // namespace dnurbs
