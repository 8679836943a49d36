#include "dnurbs/dynamics/integrators/energy_budget.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

// E = kinetic + elastic + springs (the parts kept in `check`).
void system_energy(const System& system, EnergyCheck& check) {
  check.kinetic_energy = system.kinetic_energy();
  check.potential_energy = system.potential_energy();
  check.energy = check.kinetic_energy + check.potential_energy + system.spring_energy();
}

// (1/2) k |x(q, u) - target|^2 of one spring state on model i at stacked q.
double spring_energy(const System& system, int i, const SpringState& state,
                     const Eigen::VectorXd& q) {
  const Model& model = system.model(i);
  const auto q_model = q.segment(system.coordinate_offset(i), model.coordinate_count());
  return 0.5 * state.stiffness *
         (model.position(q_model, state.parameter) - state.target).squaredNorm();
}

// The velocity-space displacement of a step: q_{n+1} - q_n where coordinates are a vector
// space, (v_n + v_{n+1}) dt / 2 where they are not (a quaternion's body angular velocity).
Eigen::VectorXd displacement(const System& system, const Eigen::VectorXd& q0,
                             const Eigen::VectorXd& v0, double dt) {
  Eigen::VectorXd dq(system.velocity_count());
  for (int i = 0; i < system.model_count(); ++i) {
    const Model& m = system.model(i);
    const int cq = system.coordinate_offset(i);
    const int cv = system.velocity_offset(i);
    if (m.coordinate_count() == m.velocity_count()) {
      dq.segment(cv, m.velocity_count()) = system.coordinates().segment(cq, m.coordinate_count()) -
                                           q0.segment(cq, m.coordinate_count());
    } else {
      dq.segment(cv, m.velocity_count()) = 0.5 * dt *
                                           (v0.segment(cv, m.velocity_count()) +
                                            system.velocities().segment(cv, m.velocity_count()));
    }
  }
  return dq;
}

}  // namespace

EnergyBudget::EnergyBudget(EnergyBudgetSettings settings) : settings_(settings) {
  if (!(settings_.growth_tolerance >= 0.0) || !std::isfinite(settings_.growth_tolerance)) {
    throw make_error("energy growth tolerance ", settings_.growth_tolerance,
                     " is not a non-negative finite number");
  }
  if (!(settings_.max_energy > 0.0)) {
    throw make_error("maximum energy ", settings_.max_energy, " must be > 0");
  }
}

void EnergyBudget::record(const System& system, const EnergyCheck& energy,
                          std::vector<Eigen::VectorXd>* forces) {
  energy_ = energy.energy;
  kinetic_energy_ = energy.kinetic_energy;
  potential_energy_ = energy.potential_energy;
  time_ = system.time();
  q_ = system.coordinates();
  v_ = system.velocities();
  if (forces != nullptr && static_cast<int>(forces->size()) == system.force_count()) {
    forces_.swap(*forces);  // evaluated by the caller at this state
  } else {
    forces_.resize(static_cast<size_t>(system.force_count()));
    for (int f = 0; f < system.force_count(); ++f) {
      forces_[static_cast<size_t>(f)].setZero(system.velocity_count());
      system.add_applied_force(f, time_, q_, v_, forces_[static_cast<size_t>(f)]);
    }
  }
  springs_.clear();
  for (int id = 0; id < system.spring_id_count(); ++id) {
    if (system.has_spring(id)) {
      springs_.push_back({id, system.spring_model(id), system.spring_state(id, time_)});
    }
  }
}

void EnergyBudget::start(const System& system) {
  EnergyCheck start;
  system_energy(system, start);
  if (!std::isfinite(start.energy)) {
    throw make_error("energy budget: the starting energy ", start.energy, " is not finite");
  }
  record(system, start);
  initial_energy_ = start.energy;
  work_ = 0.0;
  moved_ = std::abs(start.energy);
  extra_.resize(0);
  started_ = true;
}

// Step work of every contributor (trapezoid for forces, mid-state energy change for springs),
// then the check; the largest contributor names the driver of a failure.
EnergyCheck EnergyBudget::after_step(const System& system, const Eigen::VectorXd& extra_force) {
  if (!started_) {
    start(system);
  }
  EnergyCheck check;
  system_energy(system, check);
  check.growth = check.energy - energy_;
  const Eigen::VectorXd dq = displacement(system, q_, v_, system.time() - time_);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(system.velocity_count());
  double moved = 0.0;
  const auto account = [&](EnergyDriver driver, int index, double work) {
    check.step_work += work;
    moved += std::abs(work);
    if (std::abs(work) > std::abs(check.driver_work)) {
      check.driver = driver;
      check.index = index;
      check.driver_work = work;
    }
  };
  std::vector<Eigen::VectorXd> forces(static_cast<size_t>(system.force_count()));
  for (int f = 0; f < system.force_count(); ++f) {
    Eigen::VectorXd& now = forces[static_cast<size_t>(f)];
    now = zero;
    system.add_applied_force(f, system.time(), system.coordinates(), system.velocities(), now);
    const Eigen::VectorXd& before =
        f < static_cast<int>(forces_.size()) ? forces_[static_cast<size_t>(f)] : zero;
    account(EnergyDriver::kForce, f, 0.5 * (before + now).dot(dq));
  }
  // Springs: the change of energy at the mid-step state that their new target, parameter or
  // stiffness makes (their pull on the model is inside E). A spring added since the last
  // accepted state (a grab between steps) brings its whole energy at that state: the step began
  // there with the spring already pulling, and a step that moves the point toward the target
  // ends with less (implicit Euler: E_{n+1} <= E_n + E_spring(q_n)). At the mid-step state a
  // stiff grab that closes most of its gap in one step was counted at a fraction of its energy,
  // and the check stopped a sound run.
  const Eigen::VectorXd q_mid = 0.5 * (q_ + system.coordinates());
  for (int id = 0; id < system.spring_id_count(); ++id) {
    const auto old = std::find_if(springs_.begin(), springs_.end(),
                                  [id](const SpringRecord& r) { return r.id == id; });
    const bool added = old == springs_.end();
    double work = system.has_spring(id)
                      ? spring_energy(system, system.spring_model(id),
                                      system.spring_state(id, system.time()), added ? q_ : q_mid)
                      : 0.0;
    if (!added) {
      work -= spring_energy(system, old->model, old->state, q_mid);
    }
    if (work != 0.0) {
      account(EnergyDriver::kSpring, id, work);
    }
  }
  if (extra_force.size() == system.velocity_count()) {
    // The first step after start has no earlier value: the end value stands for the step
    const Eigen::VectorXd& before = extra_.size() == extra_force.size() ? extra_ : extra_force;
    account(EnergyDriver::kExtra, -1, 0.5 * (before + extra_force).dot(dq));
  }
  check.budget = initial_energy_ + work_ + check.step_work;
  check.scale = moved_ + moved;
  check.not_finite = !std::isfinite(check.energy);
  check.above_ceiling = check.energy > settings_.max_energy * std::max(1.0, check.scale);
  check.passed = !check.not_finite && !check.above_ceiling &&
                 check.energy - check.budget <= settings_.growth_tolerance * check.scale;
  if (check.passed) {
    work_ += check.step_work;
    moved_ += moved;
    record(system, check, &forces);
    extra_ = extra_force;
    check.driver = EnergyDriver::kNone;
    check.index = -1;
  } else if (!(std::abs(check.driver_work) >= 0.1 * std::abs(check.growth)) || check.not_finite) {
    check.driver = EnergyDriver::kSetting;  // no force explains the growth
    check.index = -1;
  }
  return check;
}

std::string divergence_setting(const IntegratorSettings& settings, const System& system,
                               double dt) {
  std::ostringstream text;
  if (settings.scheme == IntegratorScheme::kNewmark && settings.newmark_gamma < 0.5) {
    text << "integrator.newmark_gamma = " << settings.newmark_gamma
         << " < 1/2 (negative numerical damping: every vibration grows)";
    return text.str();
  }
  if (settings.scheme == IntegratorScheme::kCentral) {
    text << "the central scheme at integrator.dt = " << dt
         << " (its explicit damping and forces are stable only for small dt)";
    return text.str();
  }
  const bool iterated =
      settings.newton_iterations > 0 || automatic_newton_applies(settings, system);
  for (int i = 0; i < system.model_count(); ++i) {
    if (!system.model(i).matrices_are_constant() && !iterated) {
      text << "model " << i << "'s state-dependent matrices in a linearly implicit step "
           << "(integrator.newton_iterations = 0, dt = " << dt << ")";
      return text.str();
    }
  }
  text << "integrator.dt = " << dt << " (" << to_string(settings.scheme) << ")";
  return text.str();
}

}  // namespace dnurbs
