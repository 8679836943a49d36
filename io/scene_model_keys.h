#pragma once
// Keys that several model types of scene files share: the keys every model has ("type", "name",
// "material", "boundary", "resolution_scale", read by the dispatcher), the "material" object and
// the "fit" object (a model's initial shape fitted to points, io/scene_fit.h) and the "plastic"
// object of the models whose rest shape yields.

#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "dnurbs/dynamics/core/plastic_flow.h"
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

/// The model's "plastic" object, if present: {"yield": >= 0, "rate": > 0}, the yield rule of a
/// rest shape (dynamics/core/plastic_flow.h); fails naming the key otherwise.
std::optional<PlasticFlow> read_plastic_flow(const SceneReader& reader, const JsonValue& model,
                                             const std::string& path);
/// The "plastic" object as written back.
JsonOut plastic_flow_json(const PlasticFlow& flow);

/// The rest shape keys of the rational control-net models (rational_control_net_model.h) and of
/// the swung D-NURBS surfaces (dnurbs_swung_surface.h):
/// "rest_shape" ("none" or "initial": initial_shape_at_rest) and "plastic" (read_plastic_flow),
/// which a "rest_shape": "none" refuses. Absent keys leave the values as they are.
void read_rest_shape_keys(const SceneReader& reader, const JsonValue& model,
                          const std::string& path, bool& initial_shape_at_rest,
                          std::optional<PlasticFlow>& plastic_flow);
/// Writes "rest_shape" (only when "initial") and "plastic" (when set).
void write_rest_shape_keys(bool initial_shape_at_rest,
                           const std::optional<PlasticFlow>& plastic_flow, JsonOut& model);

}  // namespace dnurbs
