#pragma once
// Scene type "terzopoulos_surface" (docs/scene-format.md): the grid-based Terzopoulos elastic
// surface (dynamics/grid/terzopoulos_surface.h) on a flat grid.

#include <memory>
#include <optional>
#include <string>

#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/io/models/grid_scene_keys.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

struct SceneTerzopoulosSurface final : SceneModelSpec {
  SceneGrid grid;
  TerzopoulosMaterial material;
  TerzopoulosSettings settings;
  std::optional<PlasticFlow> plastic;  ///< "plastic": the rest shape yields

  std::unique_ptr<SceneModelSpec> clone() const override;
  std::string type() const override { return "terzopoulos_surface"; }
  void write(JsonOut& model) const override;
  std::unique_ptr<Model> build() const override;
  /// Measured: a 300 x 300 grid stepped under newmark peaks at 698 MB, 7.7 KB a node (its
  /// matrices and their factor, whose fill grows like n log n on a grid: the estimate takes
  /// 8 KB a node times log(n) / log(9e4) above that size).
  std::pair<double, std::string> memory_estimate() const override;
};

/// Reads the keys of a "terzopoulos_surface" model.
std::unique_ptr<SceneModelSpec> read_terzopoulos_surface_scene(const SceneReader& reader,
                                                               const JsonValue& model,
                                                               const std::string& path);

}  // namespace dnurbs
