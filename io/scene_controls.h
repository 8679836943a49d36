#pragma once
// The models' controls in a running scene (SceneModelControls, io/scene_spec.h): keyed materials,
// start frames and resets, after the elastic node of Romero 2005's PDE tool. SceneSimulation calls
// them around its steps.
//
// Frames are the run's: `substeps` steps when the run is in frames, one step otherwise.
// - Keyed materials take their value at the start of each frame (time frame * substeps * dt) and
//   keep it through the frame's sub-steps, as the tool does: its keyable attributes "only will be
//   visible when the elasticNode is updated. And this only happens when the time line changes, it
//   is, the frame changes" (section 5.2.1.2), and the node calls the solver with the values it read
//   until the frame's 1/24 s has elapsed (section 5.3). Time is the scene's: keys, forces and
//   moving centres keep their times whatever the start frame and resets.
// - Start frame: "The simulation will start from this frame. No computations are made before"
//   (section 5.2.1.2); before it the node outputs the input mesh (section 5.1). So a model with
//   start_frame S stays at its initial state, unstepped, through frames 0..S, logged and meshed
//   like any other frame, and steps from frame S on. When every model is held, a step only
//   advances the time.
// - Reset: the tool resets "the scenario" to the input mesh when the time line is at or before the
//   start frame again (section 5.1). A reset frame F does that on a running scene: at frame F (the
//   frame's log row and mesh included) the model is back at its initial positions, zero velocities
//   and initial rest shape, and steps on from there.

#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

class SceneControls {
 public:
  SceneControls() = default;
  /// The controls of every model of `scene`, the models of `system` (same order) at their
  /// initial state, which holds and resets return to. Evaluates every keyed material at the start
  /// of every frame up to the end of the run: throws Error "<source>: models[i].material.<key>:
  /// ..." when one is out of its range.
  SceneControls(const Scene& scene, const System& system);

  /// True if every model is held in the step from step `step` (the run steps nothing then).
  bool all_held(int step) const;
  /// After the step from step `step`: the models held in it back at their initial state; true if
  /// there was one.
  bool hold(System& system, int step) const;
  /// At step `step` (0, or after a step): when a frame starts there, models whose reset frame it
  /// is go back to their initial state, and keyed materials take the frame's values
  /// (System::set_material_parameters). True if a state or a material changed.
  bool begin_frame(System& system, int step) const;
  /// The keyed materials of the frame that step `step` lies in (a restored or continued state).
  void restore(System& system, int step) const;

 private:
  struct Controlled {
    int model = 0;
    SceneModelControls controls;
    Eigen::VectorXd coordinates;  // the initial state
    Eigen::VectorXd velocities;
  };
  double frame_time(int frame) const { return static_cast<double>(frame) * steps_per_frame_ * dt_; }
  bool held(const Controlled& controlled, int step) const;
  void reset(System& system, const Controlled& controlled) const;
  bool set_materials(System& system, int frame) const;

  std::vector<Controlled> controlled_;  // the models with a control
  int model_count_ = 0;
  int steps_per_frame_ = 1;
  double dt_ = 0.0;
  Eigen::VectorXd initial_rest_;  // System::flowing_rest_coordinates at the start
};

}  // namespace dnurbs
