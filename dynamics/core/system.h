#pragma once
// The multi-model system (DESIGN.md, "The Model contract"): models are concatenated, their
// coordinates stacked and their matrices placed block-diagonally; the System owns the state
// (q, qd, t) and the applied forces. Integrators, forces and (later) constraints see only this
// class and the Model contract.

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/model.h"
#include "dnurbs/dynamics/core/spring.h"

namespace dnurbs {

/// An applied force on one model: adds its generalized force (velocity space of `model`, size
/// model.velocity_count()) at time t and state (q, qd) into `force`.
using Force = std::function<void(const Model& model, double time, ConstVectorRef q,
                                 ConstVectorRef qd, VectorRef force)>;

/// Several models stepped together. Stacked vectors put model 0 first; model i's coordinates are
/// coordinates().segment(coordinate_offset(i), model(i).coordinate_count()), and likewise for
/// velocities with velocity_offset(i). Matrices are velocity_count() by velocity_count(),
/// block diagonal. A System is a value: copying it clones its models.
class System {
 public:
  System() = default;
  /// A system of one model.
  explicit System(const Model& model) { add_model(model); }
  System(const System& other);
  System& operator=(const System& other);
  System(System&&) noexcept = default;
  System& operator=(System&&) noexcept = default;
  ~System() = default;

  /// Adds a copy of `model` with its initial coordinates and zero velocity; returns its index.
  /// Later changes to `model` itself do not reach the System: fix points on the model before
  /// adding it, or afterwards through fix_point and fix_border below.
  int add_model(const Model& model);
  /// Model::fix_point(point) on the System's copy of model `model`: the point's coordinates keep
  /// their current values and their velocities become zero (Error naming a bad index).
  void fix_point(int model, int point);
  /// Model::fix_border() on the System's copy of model `model` (Error if the model has none).
  void fix_border(int model);
  int model_count() const { return static_cast<int>(models_.size()); }
  const Model& model(int i) const;
  int coordinate_offset(int i) const;
  int velocity_offset(int i) const;
  int coordinate_count() const { return static_cast<int>(coordinates_.size()); }
  int velocity_count() const { return static_cast<int>(velocities_.size()); }

  // State -----------------------------------------------------------------------------------
  double time() const { return time_; }
  const Eigen::VectorXd& coordinates() const { return coordinates_; }
  const Eigen::VectorXd& velocities() const { return velocities_; }
  /// Model i's coordinates and velocities (views into the stacked state).
  Eigen::VectorXd::ConstSegmentReturnType coordinates(int i) const;
  Eigen::VectorXd::ConstSegmentReturnType velocities(int i) const;
  /// Setters check sizes and finiteness (Error naming the value) and invalidate the stored
  /// acceleration. Velocities of fixed coordinates are set to zero.
  void set_coordinates(int i, ConstVectorRef q);
  void set_velocities(int i, ConstVectorRef qd);
  void set_state(ConstVectorRef q, ConstVectorRef qd, double time);
  void set_time(double time);
  /// Acceleration of the last step (Newmark needs it); invalid after any setter.
  const Eigen::VectorXd& accelerations() const { return accelerations_; }
  bool accelerations_valid() const { return accelerations_valid_; }
  void set_accelerations(ConstVectorRef a);
  /// For integrators: swaps in a new state (q, qd, a at `time`) without copying; the arguments
  /// receive the old vectors. Sizes must match (checked); finiteness is the caller's duty. Then
  /// plastic rest shapes yield towards the new state (flow_rest_shapes, dt = time - the old time).
  void commit_step(Eigen::VectorXd& q, Eigen::VectorXd& qd, Eigen::VectorXd& a, double time);

  /// x(u) of model i at the current state.
  Eigen::Vector3d position(int i, const Eigen::Vector2d& u) const;

  // Forces ----------------------------------------------------------------------------------
  /// Applies `force` to model i; returns the force's index.
  int add_force(int i, Force force);
  void clear_forces() { forces_.clear(); }
  bool has_forces() const { return !forces_.empty(); }
  /// Number of applied forces (indices of add_force).
  int force_count() const { return static_cast<int>(forces_.size()); }
  /// Adds applied force `index` alone at (t, q, qd) (stacked vectors) into `force`.
  void add_applied_force(int index, double time, ConstVectorRef q, ConstVectorRef qd,
                         VectorRef force) const;
  /// Adds every applied force at (t, q, qd) (stacked vectors) into `force`: the Force
  /// functions and, when `include_springs`, the springs' forces evaluated explicitly at q
  /// (add_spring_forces). The integrators leave the springs out and treat them implicitly.
  void add_applied_forces(double time, ConstVectorRef q, ConstVectorRef qd, VectorRef force,
                          bool include_springs = true) const;

  // Springs (dynamics/core/spring.h): implicit in the integrators ----------------------------
  /// Attaches `spring` to model i; returns its id (ids of removed springs are not reused).
  /// Throws Error for an index out of range or an empty function.
  int add_spring(int i, Spring spring);
  /// Replaces spring `id`'s function (an interactive drag may instead give a function of time).
  void set_spring(int id, Spring spring);
  /// Detaches spring `id`. Throws Error naming the id if there is no such spring.
  void remove_spring(int id);
  /// One past the largest spring id so far (removed ids included).
  int spring_id_count() const { return static_cast<int>(springs_.size()); }
  /// True if spring `id` exists (was added and not removed).
  bool has_spring(int id) const;
  /// The model of spring `id`; throws Error if there is none.
  int spring_model(int id) const;
  /// Spring `id`'s state at `time`, checked (check_spring_state); throws Error if none.
  SpringState spring_state(int id, double time) const;
  /// Adds every spring's generalized force L(u)^T k (target - x(u)) at time t and stacked q.
  void add_spring_forces(double time, ConstVectorRef q, VectorRef force) const;
  /// Adds L(u)^T k (target - x(u)) of one spring state on model i at stacked q into the stacked
  /// `force` (any real k: a negative one subtracts the force of stiffness -k).
  void add_spring_force(int i, const SpringState& state, ConstVectorRef q, VectorRef force) const;
  /// Sum of (1/2) k |x(u) - target|^2 over the springs at time t and stacked q.
  double spring_energy(double time, ConstVectorRef q) const;
  /// spring_energy at the current time and state.
  double spring_energy() const { return spring_energy(time_, coordinates_); }

  /// Adds every model's internal force f_int(q) into `force`.
  void add_internal_forces(ConstVectorRef q, VectorRef force) const;
  /// Adds every model's generalized inertial force g(q, qd) into `force`.
  void add_inertial_forces(ConstVectorRef q, ConstVectorRef qd, VectorRef force) const;

  // Matrices --------------------------------------------------------------------------------
  bool matrices_are_constant() const;
  /// Block-diagonal M, D, K when every model's are constant (built once), else nullptr.
  const ModelMatrices* constant_matrices() const;
  /// Block-diagonal M, D, K at stacked coordinates q.
  void assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const;
  /// 3 if every model has M = S (x) I_3 structure (then scalar_matrices() is the block-diagonal
  /// stack of the scalar matrices, nodes by nodes, node k holding velocities 3k..3k+2), else 0.
  int kronecker_block_size() const;
  const ModelMatrices* scalar_matrices() const;

  // Coordinates and boundary conditions -----------------------------------------------------
  /// Velocity-space indices held fixed, sorted (every model's, shifted by its offset).
  const std::vector<int>& fixed_coordinates() const { return fixed_; }
  void advance_coordinates(ConstVectorRef q, ConstVectorRef dv,
                           Eigen::Ref<Eigen::VectorXd> q_out) const;
  void project_state(Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd) const;

  // Energy ----------------------------------------------------------------------------------
  /// (1/2) qd^T M(q) qd at the current state.
  double kinetic_energy() const;
  /// Sum of the models' elastic energies at the current state.
  double potential_energy() const;

  // Plastic flow (dynamics/core/plastic_flow.h) ---------------------------------------------
  /// Model::flow_rest_shape of every model at the current state, after a step of dt (commit_step
  /// calls it after each step); returns the nodes that yielded, over all models.
  int flow_rest_shapes(double dt);
  /// Every model's Model::flowing_rest_coordinates, stacked in model order (empty when no
  /// model's rest shape yields); a checkpoint keeps them. restore sets them back and throws Error
  /// naming the size when it is not that of flowing_rest_coordinates().
  Eigen::VectorXd flowing_rest_coordinates() const;
  void restore_flowing_rest_coordinates(ConstVectorRef rest);

  // Keyable material (Model::material_parameters) ------------------------------------------
  /// Model::set_material_parameters(values) on the System's copy of model i, between steps:
  /// the state stays, the acceleration of the last step is invalidated (it belongs to the old
  /// material: Newmark recomputes it), and when M, D or K changed the constant matrices are
  /// taken again and the revision changes (integrators refactor once; a change of forces alone,
  /// the PDE surface's tangents, keeps the factorization). Returns false, changing nothing, when
  /// the values equal the model's current ones. Throws the model's Error (nothing changed) for
  /// a bad value or size, or Error naming i out of range.
  bool set_material_parameters(int i, ConstVectorRef values);

  /// Changes whenever models are added, points fixed or materials set (integrators refactor when
  /// it changes); unique across the process's systems (a copy keeps its original's until it
  /// changes).
  std::uint64_t revision() const { return revision_; }

 private:
  void rebuild_caches();
  void check_index(int i) const;
  // fixed_ again from every model's fixed coordinates, their velocities zeroed; a new revision.
  void refresh_fixed();

  std::vector<std::unique_ptr<Model>> models_;
  std::vector<int> coordinate_offsets_;
  std::vector<int> velocity_offsets_;
  std::vector<std::pair<int, Force>> forces_;
  std::vector<std::pair<int, Spring>> springs_;  // (model, spring); model -1: removed
  std::vector<int> fixed_;
  Eigen::VectorXd coordinates_;
  Eigen::VectorXd velocities_;
  Eigen::VectorXd accelerations_;
  bool accelerations_valid_ = false;
  double time_ = 0.0;
  std::uint64_t revision_ = 0;
  bool constant_ = true;
  int kronecker_ = 0;
  ModelMatrices constant_matrices_;
  ModelMatrices scalar_matrices_;
};

}  // namespace dnurbs
