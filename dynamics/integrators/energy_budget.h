#pragma once
// Divergence that means something: a run's energy checked against what its forces put in.
//
// The energy of a System is E = (1/2) qd^T M qd + E_elastic(q) + the springs' (1/2) k |x - t|^2.
// Along an exact trajectory E changes by the work of the applied forces (and of the springs'
// moving targets, parameters and stiffness) less what damping dissipates (Terzopoulos, Deformable
// Models: Classic, Topology-Adaptive and Generalized Formulations, eq. 1.24: the power balance
// qd^T (M qdd + D qd + K q) = qd^T f). So E_n <= E_0 + W_n, W_n the work done so far; the
// integrators keep this up to their truncation error (Newmark's average acceleration exactly on
// linear models, implicit Euler with dissipation). A run diverges when its energy exceeds that
// budget by more than a fraction of the energy the run has moved, E_0 + sum |work| (a relative
// test, unlike a fixed ceiling, which an instability passes only after many steps of growth).
//
// The work of each force over a step is the trapezoid (1/2) (f_n + f_{n+1}) . dq (exact for
// Newmark's average acceleration, second order otherwise); a spring's is the change of its energy
// at the mid-step state when its target, parameter or stiffness changes. When the check fails,
// the contributor whose work in the failing step is largest names the driver; when no force did
// a tenth of the step's growth, the integrator setting does (divergence_setting).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/integrator.h"

namespace dnurbs {

struct EnergyBudgetSettings {
  /// The step fails when E > budget + growth_tolerance * scale (>= 0).
  double growth_tolerance = 1.0;
  /// It fails too when E exceeds this ceiling times the run's energy scale E_0 + sum |work|
  /// (or times 1 while that scale is below 1): a ratio, so that a stiff model that starts at a
  /// large energy is not stopped while its energy falls (> 0; infinity: none).
  double max_energy = 1e300;
};

/// What drove a failed check.
enum class EnergyDriver {
  kNone,     ///< the check passed
  kForce,    ///< applied force `index` (System::add_force order)
  kSpring,   ///< spring `index` (System::add_spring id)
  kExtra,    ///< the extra force of after_step (constraint forces)
  kSetting,  ///< no force did a tenth of the growth: the integrator setting
};

/// The check of one step.
struct EnergyCheck {
  bool passed = true;
  double energy = 0.0;     ///< E after the step (kinetic + elastic + springs)
  double budget = 0.0;     ///< E_0 + W: the energy the forces allow
  double scale = 0.0;      ///< E_0 + sum |work|: the energy the run has moved
  double growth = 0.0;     ///< E after minus E before the step
  double step_work = 0.0;  ///< work of all forces in the step
  EnergyDriver driver = EnergyDriver::kNone;
  int index = -1;                 ///< the driving force's or spring's index
  double driver_work = 0.0;       ///< its work in the step
  double kinetic_energy = 0.0;    ///< (1/2) qd^T M qd after the step
  double potential_energy = 0.0;  ///< E_elastic after the step (energy = these + the springs')
  bool not_finite = false;        ///< the energy is not finite
  bool above_ceiling = false;     ///< the energy exceeds max_energy * max(1, scale)
};

/// The energy budget of a run of one System. Call start at the first state (and after any jump
/// of the state: a restored checkpoint), then after_step after every step.
class EnergyBudget {
 public:
  /// Throws Error naming the value for a negative or non-finite growth_tolerance or a
  /// non-positive max_energy.
  explicit EnergyBudget(EnergyBudgetSettings settings = {});

  /// Starts the budget at the system's current state: E_0, no work yet.
  void start(const System& system);
  /// Accounts the step from the state of the last start or passed check to the system's current
  /// one and checks its energy. `extra_force` (velocity space, or empty): a generalized force
  /// not among the System's, at the end of the step (constraint forces), whose trapezoidal work
  /// is counted too (its end value alone in the first step after start, whose start value the
  /// budget does not have). A passed check becomes the start of the next step; a failed one leaves
  /// the budget at the last good state (the caller restores the system to it).
  EnergyCheck after_step(const System& system, const Eigen::VectorXd& extra_force = {});

  double initial_energy() const { return initial_energy_; }
  double work() const { return work_; }
  /// E_0 plus every |work| so far: the energy scale of the run.
  double energy_moved() const { return moved_; }
  const EnergyBudgetSettings& settings() const { return settings_; }
  /// The last accepted state's energy.
  double energy() const { return energy_; }
  /// Its kinetic and elastic parts (System::kinetic_energy and potential_energy at that state),
  /// so that a caller logging them need not evaluate them again.
  double kinetic_energy() const { return kinetic_energy_; }
  double potential_energy() const { return potential_energy_; }

 private:
  struct SpringRecord {
    int id = -1;
    int model = 0;
    SpringState state;
  };
  // Force values, springs and state at the last accepted state.
  // `forces`: the applied forces at the system's state, when the caller has them (after_step
  // evaluated them at that very state), moved in instead of being evaluated again.
  void record(const System& system, const EnergyCheck& energy,
              std::vector<Eigen::VectorXd>* forces = nullptr);

  EnergyBudgetSettings settings_;
  bool started_ = false;
  double initial_energy_ = 0.0;
  double work_ = 0.0;
  double moved_ = 0.0;  // sum of |work| over steps and contributors
  double energy_ = 0.0;
  double kinetic_energy_ = 0.0;
  double potential_energy_ = 0.0;
  double time_ = 0.0;
  Eigen::VectorXd q_, v_, extra_;
  std::vector<Eigen::VectorXd> forces_;
  std::vector<SpringRecord> springs_;
};

/// The integrator setting that most likely drove a divergence no force explains: Newmark with
/// gamma < 1/2 (negative numerical damping), the central scheme (conditionally stable), a model
/// with state-dependent matrices stepped linearly implicitly (newton_iterations = 0), else the
/// time step. One sentence naming the setting and its value.
std::string divergence_setting(const IntegratorSettings& settings, const System& system, double dt);

}  // namespace dnurbs
