#pragma once
// A scene turned into a running simulation: the System of its models (with boundary
// conditions), the applied forces with their time windows, the constraint solver and the
// integrator; one step at a time, with divergence detection, sampling for the CSV log, meshes of
// the current shapes, checkpoints and a cost estimate.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/constraints/constraint_solver.h"
#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/energy_budget.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/io/checkpoint.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_controls.h"
#include "dnurbs/io/scene_cost.h"
#include "dnurbs/io/scene_obstacles.h"
#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// Thrown by SceneSimulation::step when a step diverges: the integrator rejects it (a non-finite
/// state), or its energy fails the energy budget (dynamics/integrators/energy_budget.h: beyond
/// the forces' work by more than integrator.energy_growth times the energy moved, or above
/// integrator.max_energy). The message names what drove it (a force of the scene or an
/// integrator setting); the simulation is back at the last state that passed the check.
class SimulationDiverged : public Error {
 public:
  explicit SimulationDiverged(const std::string& message) : Error(message) {}
};

/// What is logged at one step.
struct SceneSample {
  int step = 0;
  double time = 0.0;
  double kinetic_energy = 0.0;
  double potential_energy = 0.0;
  Eigen::VectorXd violations;           ///< |C_i| per constraint
  std::vector<Eigen::Vector3d> probes;  ///< positions of the scene's probes
};

class SceneSimulation {
 public:
  /// Runs the scene's pending fits (fit_initial_shapes) and builds everything; throws Error
  /// "<source>: <json path>: <problem>" when the library rejects a model, boundary condition,
  /// force or constraint.
  explicit SceneSimulation(Scene scene);

  const Scene& scene() const { return scene_; }
  const System& system() const { return system_; }
  const ConstraintSolver& constraints() const { return solver_; }
  const Integrator& integrator() const { return integrator_; }
  /// The energy budget of the run (its last accepted state is the simulation's state).
  const EnergyBudget& energy_budget() const { return budget_; }
  /// The scene's obstacles and the contact points of every model (io/scene_obstacles.h).
  const SceneContacts& contacts() const { return contacts_; }
  /// Steps done so far (restored by a checkpoint).
  int steps_done() const { return steps_; }

  /// Advances one integrator.dt (then projects the nodes out of the obstacles with projection
  /// contact; models before their start frame stay at their initial state, and at the start of a
  /// frame resets and keyed materials apply: io/scene_controls.h). Throws SimulationDiverged (state
  /// back to the last good one) if the integrator rejects the step or its energy fails the energy
  /// budget (plastic rest shapes back too).
  void step();

  SceneSample sample() const;
  /// Column names of the CSV log (after "step") and the row of a sample.
  std::vector<std::string> log_columns() const;
  std::vector<double> log_row(const SceneSample& sample) const;

  /// One mesh per model at the current state, named after the model; `resolution` segments per
  /// direction times the model's resolution_scale.
  std::vector<TriangleMesh> meshes(int resolution) const;
  /// The mesh of model i alone (as meshes()[i]); throws for an index out of range.
  TriangleMesh mesh(int i, int resolution) const;

  /// Sets the stacked coordinates (System order, e.g. a DesignResult's) with zero velocities at
  /// the current time; throws Error if the size is wrong or a value is not finite.
  void set_coordinates(const Eigen::VectorXd& q);
  /// Sets the stacked coordinates and velocities at the current time (System::set_state checks
  /// them); the energy budget starts again there.
  void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  /// Continues from `previous`, a simulation of the same models with other settings (a changed
  /// material, time step or constraint): its coordinates, velocities, last acceleration, time and
  /// step count. The energy budget starts again there. Throws Error if the sizes differ.
  void continue_from(const SceneSimulation& previous);
  /// Model i's current exact shape (Model::exact_shape: D-NURBS curves and surfaces).
  std::optional<Shape> shape(int i) const;

  // Interactive sculpting (sculpt/): springs and forces added while the scene runs. `label`
  // names each in the divergence report ("the drag of client 2 on hat").
  /// Attaches an implicit spring to model i (System::add_spring); returns its id.
  int add_interactive_spring(int model, Spring spring, std::string label);
  /// Replaces spring `id`'s function (a moved target or material point).
  void set_interactive_spring(int id, Spring spring);
  /// Detaches spring `id` (System::remove_spring).
  void remove_interactive_spring(int id);
  /// Adds an applied force on model i (System::add_force); returns its index.
  int add_interactive_force(int model, Force force, std::string label);

  Checkpoint checkpoint() const;
  /// Continues from a checkpoint; throws Error naming `source` if its scene hash or sizes do not
  /// match this scene.
  void restore(const Checkpoint& checkpoint, const std::string& source);

  /// Per-model sizes and costs at the initial state.
  std::vector<SceneModelCost> cost() const;

 private:
  void add_models();
  void add_forces();
  void add_constraints();
  // What drove a failed energy check, in the scene's words.
  std::string energy_driver(const EnergyCheck& check) const;

  Scene scene_;
  System system_;
  ConstraintSolver solver_;
  Integrator integrator_;
  std::string hash_;
  int steps_ = 0;
  std::vector<double> tube_radii_;  ///< curves and snakes: tube radius of their meshes
  EnergyBudget budget_;
  SceneContacts contacts_;  ///< obstacles: penalty forces in system_, or projection per step
  SceneControls controls_;  ///< keyed materials, start frames and resets of the models
  std::vector<std::string> force_labels_;   ///< what each System force is, for reports
  std::vector<std::string> spring_labels_;  ///< what each System spring id is
};

}  // namespace dnurbs
