#pragma once
// Scene type "pde_surface" (docs/scene-format.md): the dynamic PDE surface
// (dynamics/grid/pde_surface.h) on a flat grid, with its deformation regions: a centre and a
// deformation radius or a box, each with an optional force region (force radius and force) whose
// centre may move on keyframes (dynamics/grid/pde_force_region.h); a keyable material, a start
// frame and resets (Romero 2005, section 5.2.1.2: the tool's elastic node; SceneModelControls).

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dnurbs/dynamics/grid/pde_surface.h"
#include "dnurbs/io/models/grid_scene_keys.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"
#include "dnurbs/io/schedule.h"

namespace dnurbs {

/// One entry of "regions": a deformation region around `centre` of `radius` (a moving one sweeps
/// its path, swept_deformation_regions) or a fixed `box`, and its force region.
struct ScenePdeRegion {
  VectorSchedule centre;                   ///< "centre": [x, y, z] or keyframes
  double radius = 0.0;                     ///< "radius": deformation radius (0 for a box)
  std::optional<Eigen::AlignedBox3d> box;  ///< "box": {"min": [x, y, z], "max": [x, y, z]}
  std::optional<double> force_radius;      ///< "force_radius": the force region
  VectorSchedule force;                    ///< "force": on each node of the force region
};

/// The default material (PdeSurfaceMaterial{}) as constant schedules.
std::array<ScalarSchedule, kPdeMaterialParameterCount> default_pde_material();

struct ScenePdeSurface final : SceneModelSpec {
  SceneGrid grid;
  /// "material": b, c, d, density, damping, su0, su1, sv0, sv1 (the order of
  /// pde_material_parameters), each a number or keyframes (io/schedule.h), applied at the start
  /// of every frame (controls()).
  std::array<ScalarSchedule, kPdeMaterialParameterCount> material = default_pde_material();
  std::vector<ScenePdeRegion> regions;  ///< "regions"
  std::optional<PlasticFlow> plastic;   ///< "plastic": the rest shape yields
  int start_frame = 0;                  ///< "start_frame": held at the initial state until then
  std::vector<int> reset_frames;        ///< "reset": a frame or ascending frames
  /// The cost report's naive path (not a key): every grid node simulated, the forces kept.
  bool whole_grid = false;

  std::unique_ptr<SceneModelSpec> clone() const override;
  std::string type() const override { return "pde_surface"; }
  void write(JsonOut& model) const override;
  /// The surface with the material at time 0.
  std::unique_ptr<Model> build() const override;
  /// The material's values at `time` (keyframes interpolated, unchecked).
  PdeSurfaceMaterial material_at(double time) const;
  /// The keyed material (its values checked against the keys' ranges at each time asked),
  /// start_frame and reset_frames.
  SceneModelControls controls() const override;
  /// The library's deformation regions of `regions` (none with whole_grid).
  std::vector<DeformationRegion> deformation_regions() const;
  /// The force regions (pde_force_region) of the regions that have a force radius.
  void add_model_forces(System& system, int model) const override;
  /// Deformation regions: every grid node.
  std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>> naive_variant()
      const override;
};

/// Reads the keys of a "pde_surface" model.
std::unique_ptr<SceneModelSpec> read_pde_surface_scene(const SceneReader& reader,
                                                       const JsonValue& model,
                                                       const std::string& path);

}  // namespace dnurbs
