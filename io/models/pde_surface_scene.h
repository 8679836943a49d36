#pragma once
// Scene type "pde_surface" (docs/scene-format.md): the dynamic PDE surface
// (dynamics/grid/pde_surface.h) on a flat grid, with its deformation regions.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dnurbs/dynamics/grid/pde_surface.h"
#include "dnurbs/io/models/grid_scene_keys.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

struct ScenePdeSurface final : SceneModelSpec {
  SceneGrid grid;
  PdeSurfaceMaterial material;
  std::vector<DeformationRegion> regions;  ///< "regions": centre and radius
  std::optional<PlasticFlow> plastic;      ///< "plastic": the rest shape yields

  std::unique_ptr<SceneModelSpec> clone() const override;
  std::string type() const override { return "pde_surface"; }
  void write(JsonOut& model) const override;
  std::unique_ptr<Model> build() const override;
  /// Deformation regions: every grid node.
  std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>> naive_variant()
      const override;
};

/// Reads the keys of a "pde_surface" model.
std::unique_ptr<SceneModelSpec> read_pde_surface_scene(const SceneReader& reader,
                                                       const JsonValue& model,
                                                       const std::string& path);

}  // namespace dnurbs
