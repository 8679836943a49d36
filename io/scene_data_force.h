#pragma once
// The scene force "data_points" (docs/scene-format.md, "forces"): data forces for physics-based
// fitting and tracking (dynamics/core/data_force.h, after Terzopoulos & Metaxas 1991): every
// point pulls the nearest material point of a model with a spring; the points may move by an
// offset schedule.

#include <memory>
#include <string>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/data_force.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

/// "data_points": keys model, points (a file of "x y z" lines or a mesh, as fit.points, or an
/// inline array [[x, y, z], ...]), stiffness (>= 0), offset (a vector schedule added to every
/// point at time t, default none: a cloud that moves), search_segments (2..4096, default 24),
/// start, end. A file is read once, when the scene is read.
struct SceneDataPoints final : SceneForceSpec {
  int model = 0;
  std::string file;         ///< as written in the scene; empty for inline points
  Eigen::MatrixX3d points;  ///< #points by 3
  VectorSchedule offset;
  bool has_offset = false;
  DataForceSettings settings;

  std::unique_ptr<SceneForceSpec> clone() const override;
  std::string type() const override { return "data_points"; }
  void write(JsonOut& json) const override;
  void apply(System& system, double start, double end) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// The reader of io/scene_registry.cpp's force table.
std::unique_ptr<SceneForceSpec> read_data_points(const SceneReader& reader, const ModelNames& names,
                                                 const JsonValue& force, const std::string& path);

}  // namespace dnurbs
