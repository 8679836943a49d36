#pragma once
// Scene keys that D-NURBS curves and surfaces share: the initial shape ("shape" inline in the
// shape-file format, "shape_file", or "fit") and the settings ("weights", "quadrature_points",
// "minimum_weight").

#include <optional>
#include <string>

#include "dynamics/dnurbs/dnurbs_model.h"
#include "io/scene_model_keys.h"
#include "io/scene_reader.h"
#include "io/scene_spec.h"
#include "io/scene_writer.h"
#include "io/shape_file.h"

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

/// "weights" (fixed or free), "quadrature_points" and "minimum_weight" into `settings`.
void read_dnurbs_settings(const SceneReader& reader, const JsonValue& model,
                          const std::string& path, DNurbsSettings& settings);
void write_dnurbs_settings(const DNurbsSettings& settings, JsonOut& model);

}  // namespace dnurbs
