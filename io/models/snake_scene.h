#pragma once
// Scene type "snake" (docs/scene-format.md): a snake (dynamics/grid/snake.h), an open or closed
// chain of nodes with constant tension and rigidity.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/grid/snake.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

struct SceneSnake final : SceneModelSpec {
  std::vector<Eigen::Vector3d> nodes;
  bool closed = false;
  SnakeMaterial material;  ///< constant tension and rigidity (scene files give numbers)

  std::unique_ptr<SceneModelSpec> clone() const override;
  std::string type() const override { return "snake"; }
  void write(JsonOut& model) const override;
  std::unique_ptr<Model> build() const override;
};

/// Reads the keys of a "snake" model.
std::unique_ptr<SceneModelSpec> read_snake_scene(const SceneReader& reader, const JsonValue& model,
                                                 const std::string& path);

}  // namespace dnurbs
