#pragma once
// What a scene file holds for one model, force or constraint, whatever its type: the interfaces
// that each type's reader (io/scene_registry.h) returns and that the scene dispatcher, the
// writer and SceneSimulation use without knowing the type (in the manner of pbrt-v4's
// Shape::Create(parameters): every type owns its keys). The specs hold the library's own
// settings and material structs.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/constraints/constraint_solver.h"
#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/model.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/io/scene_writer.h"

namespace dnurbs {

/// Fitting a model's initial shape to points instead of giving it (scene key "fit";
/// io/scene_fit.h runs it after parsing).
struct SceneFit {
  std::string points;  ///< as written; a relative path resolves against Scene::directory
  /// D-NURBS (a clamped uniform start over the points' principal axes, fit_dnurbs_curve or
  /// fit_dnurbs_surface with the model's material as the smoothness energy):
  int degree = 3;           ///< in each direction
  int spans = 4;            ///< knot spans in each direction
  double smoothness = 0.0;  ///< DNurbsFitSettings::smoothness
  int iterations = 30;      ///< DNurbsFitSettings::max_iterations
  /// Superquadric (fit_superquadric): SuperquadricFitSettings::max_evaluations, fit_twist,
  /// fit_shear and fit_bend_shape.
  int max_evaluations = 20000;
  bool twist = true;
  bool shear = true;
  bool bend_shape = false;
  bool operator==(const SceneFit&) const = default;
};

/// What a model's keys control over a run, beyond the model built at time 0 (Romero 2005,
/// section 5.2.1.2: the PDE tool's keyable attributes and start frame; section 5.3: its reset).
/// Frames are the run's (scene.h: `substeps` steps each, one step when the run is not in frames);
/// io/scene_controls.h applies them.
struct SceneModelControls {
  /// The model's material parameters (Model::set_material_parameters) at a time, or empty when
  /// none of the type's material keys is keyed. Throws SceneKeyError naming the key
  /// (".material.density") when a keyed value at that time is out of its range.
  std::function<Eigen::VectorXd(double)> material;
  /// The model stays at its initial state, unstepped, until this frame (0: from the start).
  int start_frame = 0;
  /// Frames, ascending, at which the model returns to its initial state (positions, velocities
  /// and a plastic rest shape).
  std::vector<int> reset_frames;
};

/// One model of a scene: its type's keys, the library model they build, its fit and the naive
/// path of the cost report.
class SceneModelSpec {
 public:
  virtual ~SceneModelSpec() = default;
  virtual std::unique_ptr<SceneModelSpec> clone() const = 0;
  /// The model's "type" string.
  virtual std::string type() const = 0;
  /// Writes the type's keys into `model`, after "name" and "type" (every key, so that reading
  /// it back gives an equal spec).
  virtual void write(JsonOut& model) const = 0;
  /// The library model (boundary conditions are applied by the caller). Throws Error with the
  /// library's message when it rejects a value, or when a fit is pending.
  virtual std::unique_ptr<Model> build() const = 0;
  /// Adds the forces that the type's own keys define (the PDE surface's force regions) to model
  /// `model` of `system`, after the model is added. Default: none.
  virtual void add_model_forces(System& /*system*/, int /*model*/) const {}
  /// The coordinates whose values the scene prescribes at `time` instead of the dynamics (the
  /// keyed parameters of a deformation field model), as (coordinate index, value) pairs, for
  /// models whose coordinates are their velocities; the built model holds them fixed
  /// (io/scene_prescribed.h sets them). Default: none.
  virtual std::vector<std::pair<int, double>> prescribed_coordinates(double /*time*/) const {
    return {};
  }
  /// The keyed material, start frame and resets of the model. Default: none.
  virtual SceneModelControls controls() const { return {}; }
  /// An estimate of the memory the built model and its step will need, checked before it is
  /// built (core/memory_budget.h), with the key to lower: {bytes, key}. Default {0, ""}: models
  /// whose size is bounded by their shape file or keys.
  virtual std::pair<double, std::string> memory_estimate() const { return {0.0, ""}; }
  /// The model's fit when its initial shape is still to be fitted, else nullptr.
  virtual const SceneFit* pending_fit() const { return nullptr; }
  /// Fits the initial shape to `points` (#points by 3) with the fit's settings; the fit stays in
  /// the spec (and is written back). Throws Error from the fitter. Default: throws (no fit).
  virtual void run_fit(const Eigen::MatrixX3d& points);
  /// The cost report's naive path: this model without the library's automatic choice (free
  /// weights for fixed ones, every superquadric part, every PDE node) and a description of the
  /// choice; nullopt when the model already takes the naive path (the default).
  virtual std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>> naive_variant()
      const {
    return std::nullopt;
  }
};

/// An error about one key of a force or constraint found when it is applied: `key` is the key's
/// path relative to the force or constraint (".control_points[1]").
class SceneKeyError : public Error {
 public:
  SceneKeyError(std::string key, const std::string& message)
      : Error(message), key_(std::move(key)) {}
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

/// One applied force of a scene (its time window is the caller's).
class SceneForceSpec {
 public:
  virtual ~SceneForceSpec() = default;
  virtual std::unique_ptr<SceneForceSpec> clone() const = 0;
  /// The force's "type" string.
  virtual std::string type() const = 0;
  /// Writes {"type": ..., the type's keys} into `force`.
  virtual void write(JsonOut& force) const = 0;
  /// Adds the force to `system`, acting while start <= t < end. Throws Error, or SceneKeyError
  /// naming a key.
  virtual void apply(System& system, double start, double end) const = 0;
  /// Local sculpting: adds the parameters and control points the force acts on in model `model`
  /// to `region`; returns true if it acts everywhere on that model.
  virtual bool add_to_region(int model, SculptedRegion& region) const = 0;
};

/// One constraint of a scene (its Baumgarte parameters are the caller's).
class SceneConstraintSpec {
 public:
  virtual ~SceneConstraintSpec() = default;
  virtual std::unique_ptr<SceneConstraintSpec> clone() const = 0;
  /// The constraint's "type" string.
  virtual std::string type() const = 0;
  /// Writes {"type": ..., the type's keys} into `constraint`.
  virtual void write(JsonOut& constraint) const = 0;
  /// Adds the constraint (one or several) to the solver. Throws Error.
  virtual void add(ConstraintSolver& solver, System& system,
                   const BaumgarteParameters& parameters) const = 0;
  /// As SceneForceSpec::add_to_region.
  virtual bool add_to_region(int model, SculptedRegion& region) const = 0;
};

}  // namespace dnurbs
