#pragma once
// Scene keys that D-NURBS curves and surfaces share: the initial shape ("shape" inline in the
// shape-file format, "shape_file", or "fit"), the settings ("weights", "quadrature_points",
// "minimum_weight") and the thin-plate-under-tension material of surfaces (tensor-product and
// triangular).

#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "dnurbs/dynamics/dnurbs/dnurbs_model.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/io/scene_model_keys.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"
#include "dnurbs/io/scene_writer.h"
#include "dnurbs/io/shape_file.h"

namespace dnurbs {

/// The shape from "shape" (inline) or "shape_file" (resolved against the scene's directory;
/// `shape_file` receives the name as written); `type` names the shape type in messages
/// ("nurbs_curve"). Fails with the JSON path, the shape file's own paths included
/// ("models[0].shape.knots_u: ...").
template <typename ShapeType>
ShapeType read_scene_shape(const SceneReader& reader, const JsonValue& model,
                           const std::string& path, std::string& shape_file, const char* type);

/// Writes "fit", "shape_file" or the inline "shape", whichever the model came from (the shape
/// is only needed without a fit).
void write_scene_shape(const std::optional<Shape>& shape, const std::string& shape_file,
                       const std::optional<SceneFit>& fit, JsonOut& model);

/// "weights" (fixed or free), "quadrature_points", "minimum_weight" and the optional
/// "weight_inertia" and "weight_stiffness" (>= 0; absent: scale-aware) and "rest_shape"
/// ("none" or "initial": DNurbsSettings::initial_shape_at_rest; written only when "initial") and
/// "plastic" ({"yield": >= 0, "rate": > 0}: DNurbsSettings::plastic_flow, refused with
/// "rest_shape": "none")
void read_dnurbs_settings(const SceneReader& reader, const JsonValue& model,
                          const std::string& path, DNurbsSettings& settings);
void write_dnurbs_settings(const DNurbsSettings& settings, JsonOut& model);

/// The "material" keys of D-NURBS surfaces ("mass_density", "damping_density", "a10", "a01",
/// "b20", "b11", "b02", each a number >= 0) into `material`, keeping its value where a key is
/// absent; fails naming the key for an unknown key or a bad value.
void read_dnurbs_surface_material(const SceneReader& reader, const JsonValue& model,
                                  const std::string& path, DNurbsSurfaceMaterial& material);
/// The "material" object of a D-NURBS surface with constant material functions.
JsonOut dnurbs_surface_material_json(const DNurbsSurfaceMaterial& material);

/// The cost report's naive path of a D-NURBS spec (SceneModelSpec::naive_variant): a copy with
/// free weights and the description of the choice, or nullopt when the weights are free already.
/// `Spec` has `settings.weight_mode`.
template <typename Spec>
std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>> free_weights_variant(
    const Spec& spec) {
  if (spec.settings.weight_mode == WeightMode::kFree) {
    return std::nullopt;
  }
  auto naive = std::make_unique<Spec>(spec);
  naive->settings.weight_mode = WeightMode::kFree;
  return std::pair{std::unique_ptr<SceneModelSpec>(std::move(naive)),
                   std::string("fixed weights (naive: free weights)")};
}

}  // namespace dnurbs
