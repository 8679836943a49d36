#pragma once
// Coordinates that a scene prescribes over time instead of integrating them (the keyed parameters
// of a deformation field model, io/models/deformation_field_scene.h): the model holds them fixed
// (eliminated from every solve, Model::fix_coordinate) and the scene sets their values before
// each step, so they follow their schedules exactly at every step's time. A prescribed
// coordinate's motion reaches the others through its value only: the step sees it at rest
// (velocity and acceleration zero), so the inertial coupling M_dyn,keyed q''_keyed is left out.

#include <vector>

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/io/scene.h"

namespace dnurbs {

/// Sets every coordinate that models[i].spec->prescribed_coordinates(time) names in model i of
/// `system` (built from `models` in their order) and its velocity to zero; returns whether any
/// was set (the state jumped: an energy budget must start again there).
bool prescribe_scene_coordinates(const std::vector<SceneModel>& models, System& system,
                                 double time);

}  // namespace dnurbs
