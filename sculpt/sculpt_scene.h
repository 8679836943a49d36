#pragma once
// The scene a sculpting session runs: the scene it was started with, with the settings clients
// changed (material, time step) and the points they pinned written into it, through the scene
// file's own keys (docs/scene-format.md), so that the changed scene is checked and built exactly
// as a scene file would be.

#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/io/scene.h"
#include "dnurbs/sculpt/sculpt_request.h"

namespace dnurbs {

/// A setting per SculptSetting (stiffness, tension, rigidity, density, damping, dt); nullopt:
/// the scene's own value is kept.
using SculptSettingOverrides = std::array<std::optional<double>, 6>;

/// A point held where a client pinned it: a point_target constraint.
struct SculptPin {
  int model = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
};

/// True for the model types the material settings apply to (D-NURBS curves, tensor-product and
/// triangular surfaces).
bool sculpt_material_applies(const SceneModel& model);

/// The scene's values of the settings: tension, rigidity, density and damping from its first
/// D-NURBS model (curve: tension, rigidity; surface: a10, b20; both: mass_density,
/// damping_density), dt from the integrator; stiffness is not a scene value (nullopt).
SculptSettingOverrides sculpt_scene_settings(const Scene& scene);

/// `scene` with the overrides applied (tension to a10 and a01, rigidity to b20, b11 and b02 of
/// surfaces, to tension and rigidity of curves; density to mass_density; damping to
/// damping_density; dt to integrator.dt) and the pins appended as point_target constraints.
/// Throws Error (from the scene reader) if the result is not a valid scene.
Scene sculpt_scene(const Scene& scene, const SculptSettingOverrides& overrides,
                   const std::vector<SculptPin>& pins);

}  // namespace dnurbs
