#include "dnurbs/io/scene_controls.h"

#include <algorithm>
#include <string>

#include "dnurbs/core/error.h"

namespace dnurbs {

SceneControls::SceneControls(const Scene& scene, const System& system)
    : model_count_(system.model_count()),
      steps_per_frame_(scene.substeps > 0 ? scene.substeps : 1),
      dt_(scene.integrator.dt),
      initial_rest_(system.flowing_rest_coordinates()) {
  for (int i = 0; i < model_count_; ++i) {
    SceneModelControls controls = scene.models[static_cast<size_t>(i)].spec->controls();
    if (!controls.material && controls.start_frame == 0 && controls.reset_frames.empty()) {
      continue;
    }
    if (controls.material) {
      // Every value the run will take, now, naming the key (a cubic spline through keyframes in
      // range can leave the range between them)
      for (int frame = 0; frame <= scene.step_count() / steps_per_frame_; ++frame) {
        try {
          controls.material(frame_time(frame));
        } catch (const SceneKeyError& error) {
          throw make_error(scene.source, ": models[", i, "]", error.key(), ": at frame ", frame,
                           ", ", error.what());
        }
      }
    }
    controlled_.push_back({i, std::move(controls), system.coordinates(i), system.velocities(i)});
  }
}

bool SceneControls::held(const Controlled& controlled, int step) const {
  return step < controlled.controls.start_frame * steps_per_frame_;
}

bool SceneControls::all_held(int step) const {
  return model_count_ > 0 && static_cast<int>(controlled_.size()) == model_count_ &&
         std::all_of(controlled_.begin(), controlled_.end(),
                     [&](const Controlled& controlled) { return held(controlled, step); });
}

bool SceneControls::hold(System& system, int step) const {
  bool any = false;
  for (const Controlled& controlled : controlled_) {
    if (held(controlled, step)) {
      reset(system, controlled);
      any = true;
    }
  }
  return any;
}

void SceneControls::reset(System& system, const Controlled& controlled) const {
  system.set_coordinates(controlled.model, controlled.coordinates);
  system.set_velocities(controlled.model, controlled.velocities);
  if (initial_rest_.size() == 0) {
    return;
  }
  // The model's own part of the stacked plastic rest shapes
  Eigen::Index offset = 0;
  for (int i = 0; i < controlled.model; ++i) {
    offset += system.model(i).flowing_rest_coordinates().size();
  }
  const Eigen::Index size = system.model(controlled.model).flowing_rest_coordinates().size();
  Eigen::VectorXd rest = system.flowing_rest_coordinates();
  rest.segment(offset, size) = initial_rest_.segment(offset, size);
  system.restore_flowing_rest_coordinates(rest);
}

bool SceneControls::set_materials(System& system, int frame) const {
  bool changed = false;
  for (const Controlled& controlled : controlled_) {
    if (controlled.controls.material) {
      changed = system.set_material_parameters(controlled.model,
                                               controlled.controls.material(frame_time(frame))) ||
                changed;
    }
  }
  return changed;
}

bool SceneControls::begin_frame(System& system, int step) const {
  if (controlled_.empty() || step % steps_per_frame_ != 0) {
    return false;
  }
  const int frame = step / steps_per_frame_;
  bool changed = false;
  for (const Controlled& controlled : controlled_) {
    const std::vector<int>& resets = controlled.controls.reset_frames;
    if (std::binary_search(resets.begin(), resets.end(), frame)) {
      reset(system, controlled);
      changed = true;
    }
  }
  return set_materials(system, frame) || changed;
}

void SceneControls::restore(System& system, int step) const {
  set_materials(system, step / steps_per_frame_);
}

}  // namespace dnurbs
