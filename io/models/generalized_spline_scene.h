#pragma once
// Scene type "generalized_spline" (docs/scene-format.md): a controlled-continuity spline of order
// n (dynamics/grid/generalized_spline.h; Terzopoulos, Deformable Models, eqs 1.17-1.20) on a
// chain of nodes (a snake of any order) or on a grid (a membrane, a thin plate under tension, or
// higher orders), with constant or per-node weights.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/grid/generalized_spline.h"
#include "dnurbs/io/models/grid_scene_keys.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

struct SceneGeneralizedSpline final : SceneModelSpec {
  std::vector<Eigen::Vector3d> nodes;  ///< a chain's nodes (empty for a grid)
  bool closed = false;                 ///< a closed chain
  std::optional<SceneGrid> grid;       ///< a grid (then no nodes)
  /// The material; each term's weight is a constant or node_weights (scene files give numbers).
  GeneralizedSplineMaterial material;
  bool terms_given = false;  ///< written back only when the scene listed them

  std::unique_ptr<SceneModelSpec> clone() const override;
  std::string type() const override { return "generalized_spline"; }
  void write(JsonOut& model) const override;
  std::unique_ptr<Model> build() const override;
};

/// Reads the keys of a "generalized_spline" model: "nodes" and "closed" (a chain) or "grid",
/// "order", "terms" ([{"j": [ju] or [ju, jv], "weight": w or [w per node]}], default every j of
/// order 1..n at weight 1), "material" (mass_density >= 0, damping_density >= 0, not both 0).
std::unique_ptr<SceneModelSpec> read_generalized_spline_scene(const SceneReader& reader,
                                                              const JsonValue& model,
                                                              const std::string& path);

}  // namespace dnurbs
