#include "dnurbs/io/models/swung_surface_scene.h"

#include <array>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/models/dnurbs_scene_keys.h"
#include "dnurbs/io/scene_model_keys.h"
#include "dnurbs/io/scene_registry.h"
#include "dnurbs/io/shape_file.h"
#include "dnurbs/nurbs/swung_refinement.h"
#include "dnurbs/nurbs/swung_shapes.h"

namespace dnurbs {
namespace {

// The prototype kinds and the keys each reads besides "kind".
struct PrototypeKind {
  const char* kind;
  std::vector<const char*> keys;
};
const std::vector<PrototypeKind>& prototype_kinds() {
  static const std::vector<PrototypeKind> kinds = {
      {"sphere", {"radius"}},
      {"torus", {"major_radius", "minor_radius"}},
      {"cylinder", {"radius", "height", "profile_control_points"}},
      {"cone", {"radius", "height", "profile_control_points"}},
      {"hat", {"brim_radius", "crown_radius", "height"}},
      {"open_profile", {"start", "end", "profile_control_points"}},
  };
  return kinds;
}

const PrototypeKind& prototype_kind(const std::string& kind) {
  for (const PrototypeKind& entry : prototype_kinds()) {
    if (kind == entry.kind) {
      return entry;
    }
  }
  throw make_error("unknown swung prototype kind \"", kind, "\"");
}

// The prototypes' dimensions that are numbers > 0.
constexpr std::array<std::pair<const char*, double SceneSwungPrototype::*>, 6> kPrototypeNumbers{{
    {"radius", &SceneSwungPrototype::radius},
    {"major_radius", &SceneSwungPrototype::major_radius},
    {"minor_radius", &SceneSwungPrototype::minor_radius},
    {"height", &SceneSwungPrototype::height},
    {"brim_radius", &SceneSwungPrototype::brim_radius},
    {"crown_radius", &SceneSwungPrototype::crown_radius},
}};

JsonOut prototype_json(const SceneSwungPrototype& prototype) {
  JsonOut json;
  json["kind"] = prototype.kind;
  for (const std::string key : prototype_kind(prototype.kind).keys) {
    if (key == "start" || key == "end") {
      json[key] = json_array<2>(key == "start" ? prototype.start : prototype.end);
    } else if (key == "profile_control_points") {
      json[key] = prototype.profile_control_points;
    }
    for (const auto& [name, value] : kPrototypeNumbers) {
      if (key == name) {
        json[key] = prototype.*value;
      }
    }
  }
  return json;
}

SceneSwungPrototype read_prototype(const SceneReader& reader, const JsonValue& value,
                                   const std::string& path) {
  if (!value.is_object()) {
    reader.fail(path, "expected a prototype object {\"kind\": ..., ...}, got " +
                          describe_json_value(value));
  }
  SceneSwungPrototype prototype;
  std::vector<const char*> kinds;
  for (const PrototypeKind& entry : prototype_kinds()) {
    kinds.push_back(entry.kind);
  }
  prototype.kind = reader.choice(reader.require(value, path, "kind", "a prototype kind"),
                                 join_json_path(path, "kind"), kinds);
  std::vector<const char*> allowed = prototype_kind(prototype.kind).keys;
  allowed.push_back("kind");
  reader.object(value, path, allowed, "a " + prototype.kind + " prototype");
  for (const auto& [key, member] : kPrototypeNumbers) {
    reader.number_key(value, path, key, prototype.*member, 0.0, true);
  }
  reader.integer_key(value, path, "profile_control_points", prototype.profile_control_points, 2,
                     10000);
  for (const auto& [key, target] :
       {std::pair{"start", &prototype.start}, std::pair{"end", &prototype.end}}) {
    if (const JsonValue* point = reader.find(value, key)) {
      *target = reader.vector<2>(*point, join_json_path(path, key), "[x, z]");
    }
  }
  return prototype;
}

// One curve, "profile" or "trajectory": {"shape": <nurbs_curve>} or {"shape_file": "..."}.
NurbsCurve read_curve(const SceneReader& reader, const JsonValue& model, const std::string& path,
                      const char* name, std::string& shape_file) {
  const std::string curve_path = join_json_path(path, name);
  const JsonValue& curve =
      reader.require(model, path, name, "{\"shape\": <nurbs_curve>} or {\"shape_file\": \"...\"}");
  reader.object(curve, curve_path, {"shape", "shape_file"});
  if ((reader.find(curve, "shape") == nullptr) == (reader.find(curve, "shape_file") == nullptr)) {
    reader.fail(curve_path,
                "expected exactly one of \"shape\" (a nurbs_curve in the shape format "
                "of dnurbs eval) and \"shape_file\"");
  }
  return read_scene_shape<NurbsCurve>(reader, curve, curve_path, shape_file, "nurbs_curve");
}

// "profile", "trajectory" and "alpha": the swung surface of two curves; a curve out of its
// plane or a bad alpha fails naming its key.
SwungSurface read_curves(const SceneReader& reader, const JsonValue& model, const std::string& path,
                         SceneSwungSurface& spec) {
  NurbsCurve profile = read_curve(reader, model, path, "profile", spec.profile_file);
  NurbsCurve trajectory = read_curve(reader, model, path, "trajectory", spec.trajectory_file);
  double alpha = 1.0;
  reader.number_key(model, path, "alpha", alpha);
  const bool profile_planar = profile.control_points().col(1).cwiseAbs().maxCoeff() == 0.0;
  try {
    return SwungSurface(std::move(profile), std::move(trajectory), alpha);
  } catch (const Error& error) {
    const char* key = !(std::isfinite(alpha) && alpha != 0.0) ? "alpha"
                      : profile_planar                        ? "trajectory"
                                                              : "profile";
    reader.fail(join_json_path(path, key), error.what());
  }
}

void read_settings(const SceneReader& reader, const JsonValue& model, const std::string& path,
                   DNurbsSwungSettings& settings) {
  DNurbsSettings common;
  common.weight_mode = settings.weight_mode;
  common.quadrature_points = settings.quadrature_points;
  common.minimum_weight = settings.minimum_weight;
  read_dnurbs_settings(reader, model, path, common);
  settings.weight_mode = common.weight_mode;
  settings.quadrature_points = common.quadrature_points;
  settings.minimum_weight = common.minimum_weight;
  reader.boolean_key(model, path, "geometric_stiffness", settings.geometric_stiffness);
  reader.boolean_key(model, path, "separable_assembly", settings.separable_assembly);
  reader.number_key(model, path, "weight_inertia", settings.weight_inertia, 0.0, false);
  read_rest_shape_keys(reader, model, path, settings.initial_shape_at_rest, settings.plastic_flow);
}

void write_settings(const DNurbsSwungSettings& settings, JsonOut& model) {
  DNurbsSettings common;
  common.weight_mode = settings.weight_mode;
  common.quadrature_points = settings.quadrature_points;
  common.minimum_weight = settings.minimum_weight;
  write_dnurbs_settings(common, model);
  model["geometric_stiffness"] = settings.geometric_stiffness;
  model["separable_assembly"] = settings.separable_assembly;
  model["weight_inertia"] = settings.weight_inertia;
  write_rest_shape_keys(settings.initial_shape_at_rest, settings.plastic_flow, model);
}

}  // namespace

SwungSurface SceneSwungPrototype::surface() const {
  if (kind == "sphere") {
    return swung_sphere(radius);
  }
  if (kind == "torus") {
    return swung_torus(major_radius, minor_radius);
  }
  if (kind == "cylinder") {
    return swung_cylinder(radius, height, profile_control_points);
  }
  if (kind == "cone") {
    return swung_cone(radius, height, profile_control_points);
  }
  if (kind == "hat") {
    return swung_hat(brim_radius, crown_radius, height);
  }
  if (kind == "open_profile") {
    return swung_open_profile(start.x(), start.y(), end.x(), end.y(), profile_control_points);
  }
  throw make_error("unknown swung prototype kind \"", kind, "\"");
}

std::unique_ptr<SceneModelSpec> SceneSwungSurface::clone() const {
  return std::make_unique<SceneSwungSurface>(*this);
}

void SceneSwungSurface::write(JsonOut& model) const {
  if (prototype) {
    model["prototype"] = prototype_json(*prototype);
  } else {
    for (const auto& [key, curve, file] :
         {std::tuple{"profile", &surface.profile(), &profile_file},
          std::tuple{"trajectory", &surface.trajectory(), &trajectory_file}}) {
      JsonOut json;
      write_scene_shape(Shape(*curve), *file, std::nullopt, json);
      model[key] = json;
    }
    model["alpha"] = surface.alpha();
  }
  model["refine"] = {refine.x(), refine.y()};
  model["fix_profile"] = fix_profile;
  model["fix_trajectory"] = fix_trajectory;
  model["fix_poles"] = fix_poles;
  model["material"] = dnurbs_surface_material_json(material);
  write_settings(settings, model);
}

SwungSurface SceneSwungSurface::refined_surface() const {
  return refine_swung_surface(surface, refine.x(), refine.y());
}

std::unique_ptr<Model> SceneSwungSurface::build() const {
  auto model = std::make_unique<DNurbsSwungSurface>(refined_surface(), material, settings);
  if (fix_poles) {
    model->fix_poles();
  }
  if (fix_profile) {
    model->fix_profile();
  }
  if (fix_trajectory) {
    model->fix_trajectory();
  }
  return model;
}

std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>>
SceneSwungSurface::naive_variant() const {
  // The twin as a "dnurbs_surface" scene model, read by that type's own reader.
  const NurbsSurface twin = refined_surface().to_nurbs_surface();
  JsonOut json;
  json["type"] = "dnurbs_surface";
  json["shape"] = JsonOut::parse(shape_to_json(Shape(twin)));
  json["material"] = dnurbs_surface_material_json(material);
  DNurbsSettings common;
  common.weight_mode = settings.weight_mode;
  common.minimum_weight = settings.minimum_weight;
  write_dnurbs_settings(common, json);
  write_rest_shape_keys(settings.initial_shape_at_rest, settings.plastic_flow, json);
  const SceneReader reader("<tensor-product twin of a swung_surface>", ".");
  std::unique_ptr<SceneModelSpec> naive = find_type(scene_model_types(), "dnurbs_surface")
                                              .read(reader, JsonValue::parse(json.dump()), "twin");
  return std::pair{std::move(naive),
                   "swung profile and trajectory coordinates (naive: the tensor-product D-NURBS "
                   "surface of the same shape, " +
                       std::to_string(twin.control_point_count_u()) + " x " +
                       std::to_string(twin.control_point_count_v()) + " control points)"};
}

std::unique_ptr<SceneModelSpec> read_swung_surface_scene(const SceneReader& reader,
                                                         const JsonValue& model,
                                                         const std::string& path) {
  check_model_keys(
      reader, model, path, "swung_surface",
      {"prototype", "profile", "trajectory", "alpha", "refine", "fix_profile", "fix_trajectory",
       "fix_poles", "weights", "quadrature_points", "minimum_weight", "geometric_stiffness",
       "separable_assembly", "weight_inertia", "rest_shape", "plastic"});
  auto spec = std::make_unique<SceneSwungSurface>();
  // Material (the keys of "dnurbs_surface") ---------------------------------------------------
  read_dnurbs_surface_material(reader, model, path, spec->material);
  read_settings(reader, model, path, spec->settings);

  // The shape: a prototype, or the two curves --------------------------------------------------
  const JsonValue* prototype = reader.find(model, "prototype");
  if (prototype != nullptr) {
    for (const char* key : {"profile", "trajectory", "alpha"}) {
      if (reader.find(model, key) != nullptr) {
        reader.fail(join_json_path(path, key),
                    std::string("expected no \"") + key +
                        "\" with a \"prototype\" (the prototype gives the curves and alpha = 1)");
      }
    }
    const std::string prototype_path = join_json_path(path, "prototype");
    spec->prototype = read_prototype(reader, *prototype, prototype_path);
    try {
      spec->surface = spec->prototype->surface();
    } catch (const Error& error) {
      reader.fail(prototype_path, error.what());
    }
  } else {
    if (reader.find(model, "profile") == nullptr && reader.find(model, "trajectory") == nullptr) {
      reader.fail(join_json_path(path, "prototype"),
                  "missing key (expected a \"prototype\" object, or the \"profile\" and "
                  "\"trajectory\" curves)");
    }
    spec->surface = read_curves(reader, model, path, *spec);
  }

  // Refinement and curve fixes -----------------------------------------------------------------
  if (const JsonValue* refine = reader.find(model, "refine")) {
    const std::string refine_path = join_json_path(path, "refine");
    const JsonValue& counts =
        reader.array(*refine, refine_path, "[profile, trajectory] knot counts");
    if (counts.size() != 2) {
      reader.fail(refine_path, "expected [profile, trajectory] knots per span, got " +
                                   describe_json_value(*refine));
    }
    for (int k = 0; k < 2; ++k) {
      spec->refine[k] = reader.integer(counts[static_cast<size_t>(k)],
                                       json_index_path(refine_path, static_cast<size_t>(k)), 0, 64);
    }
  }
  reader.boolean_key(model, path, "fix_profile", spec->fix_profile);
  reader.boolean_key(model, path, "fix_trajectory", spec->fix_trajectory);
  reader.boolean_key(model, path, "fix_poles", spec->fix_poles);
  return spec;
}

}  // namespace dnurbs
