#pragma once
// Keys that several model types of scene files share: the keys every model has ("type", "name",
// "material", "boundary", "resolution_scale", read by the dispatcher), the "material" object and
// the "fit" object (a model's initial shape fitted to points, io/scene_fit.h).

#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"
#include "dnurbs/io/scene_writer.h"

namespace dnurbs {

/// Checks that `model` has only the common keys and the type's own keys `own`; fails "unknown
/// key for a <type> model (expected only ...)".
void check_model_keys(const SceneReader& reader, const JsonValue& model, const std::string& path,
                      const std::string& type, std::initializer_list<const char*> own);

/// The model's "material" object, an empty object when absent, after checking that it has
/// only the keys `allowed`.
JsonValue model_material(const SceneReader& reader, const JsonValue& model, const std::string& path,
                         const std::vector<const char*>& allowed);

/// The "fit" object of a model, if present: `dnurbs` selects the D-NURBS keys (degree, spans,
/// smoothness, iterations) or the superquadric ones (max_evaluations); `instead_of` are the keys
/// that give the shape the fit replaces (fails if one of them is present too).
std::optional<SceneFit> read_fit(const SceneReader& reader, const JsonValue& model,
                                 const std::string& path, bool dnurbs,
                                 std::initializer_list<const char*> instead_of);
/// The "fit" object as written back.
JsonOut fit_json(const SceneFit& fit, bool dnurbs);

}  // namespace dnurbs
