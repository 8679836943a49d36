#pragma once
// Scene type "dnurbs_curve" (docs/scene-format.md): a D-NURBS curve (dynamics/dnurbs/dnurbs_curve.h)
// with its shape, material and settings.

#include <memory>
#include <optional>
#include <string>

#include "dynamics/dnurbs/dnurbs_curve.h"
#include "io/scene_reader.h"
#include "io/scene_spec.h"

namespace dnurbs {

struct SceneDNurbsCurve final : SceneModelSpec {
  std::optional<NurbsCurve> curve;  ///< absent while a fit is pending
  std::string shape_file;  ///< non-empty if the curve came from "shape_file" (written back so)
  DNurbsCurveMaterial material;     ///< constants (scene files give numbers)
  DNurbsSettings settings;
  std::optional<SceneFit> fit;  ///< present if the curve is (to be) fitted ("fit", written back)

  std::unique_ptr<SceneModelSpec> clone() const override;
  std::string type() const override { return "dnurbs_curve"; }
  void write(JsonOut& model) const override;
  std::unique_ptr<Model> build() const override;
  const SceneFit* pending_fit() const override;
  void run_fit(const Eigen::MatrixX3d& points) override;
  /// Fixed weights: free weights.
  std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>> naive_variant()
      const override;
};

/// Reads the keys of a "dnurbs_curve" model.
std::unique_ptr<SceneModelSpec> read_dnurbs_curve_scene(const SceneReader& reader,
                                                        const JsonValue& model,
                                                        const std::string& path);

}  // namespace dnurbs
