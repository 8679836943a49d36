#pragma once
// Scene type "dnurbs_surface" (docs/scene-format.md): a tensor-product D-NURBS surface (dynamics/dnurbs/dnurbs_surface.h)
// with its shape, material and settings.

#include <memory>
#include <optional>
#include <string>

#include "dynamics/dnurbs/dnurbs_surface.h"
#include "io/scene_reader.h"
#include "io/scene_spec.h"

namespace dnurbs {

struct SceneDNurbsSurface final : SceneModelSpec {
  std::optional<NurbsSurface> surface;  ///< absent while a fit is pending
  std::string shape_file;  ///< non-empty if the surface came from "shape_file" (written back so)
  DNurbsSurfaceMaterial material;     ///< constants (scene files give numbers)
  DNurbsSettings settings;
  std::optional<SceneFit> fit;  ///< present if the surface is (to be) fitted ("fit", written back)

  std::unique_ptr<SceneModelSpec> clone() const override;
  std::string type() const override { return "dnurbs_surface"; }
  void write(JsonOut& model) const override;
  std::unique_ptr<Model> build() const override;
  const SceneFit* pending_fit() const override;
  void run_fit(const Eigen::MatrixX3d& points) override;
  /// Fixed weights: free weights.
  std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>> naive_variant()
      const override;
};

/// Reads the keys of a "dnurbs_surface" model.
std::unique_ptr<SceneModelSpec> read_dnurbs_surface_scene(const SceneReader& reader,
                                                        const JsonValue& model,
                                                        const std::string& path);

}  // namespace dnurbs
