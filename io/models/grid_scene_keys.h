#pragma once
// The "grid" key that grid surfaces share (Terzopoulos surface, PDE surface): a regular grid of
// nodes with a flat rest shape origin + i h axis_u + j h axis_v.

#include <string>

#include <Eigen/Core>

#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_writer.h"
#include "dnurbs/surface/grid.h"

namespace dnurbs {

struct SceneGrid {
  int nodes_u = 0;
  int nodes_v = 0;
  double spacing = 0.0;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d axis_v = Eigen::Vector3d::UnitY();

  /// The grid (3 coordinates per node) and its flat rest positions (#nodes by 3).
  Grid grid() const;
  NodePositions rest_positions() const;
};

/// Reads the model's required "grid" object.
SceneGrid read_scene_grid(const SceneReader& reader, const JsonValue& model,
                          const std::string& path);
JsonOut scene_grid_json(const SceneGrid& grid);

}  // namespace dnurbs
