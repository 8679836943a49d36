#include "dnurbs/io/models/dnurbs_scene_keys.h"

#include <utility>

#include <variant>

#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/scene_model_keys.h"
#include "dnurbs/io/shape_recipe.h"

namespace dnurbs {

namespace {

// The material keys of D-NURBS surfaces and the members they set (Terzopoulos 2003, eq. 1.20).
struct SurfaceMaterialKey {
  const char* key;
  MaterialFunction DNurbsSurfaceMaterial::*member;
};
constexpr SurfaceMaterialKey kSurfaceMaterialKeys[] = {
    {"mass_density", &DNurbsSurfaceMaterial::mass_density},
    {"damping_density", &DNurbsSurfaceMaterial::damping_density},
    {"a10", &DNurbsSurfaceMaterial::a10},
    {"a01", &DNurbsSurfaceMaterial::a01},
    {"b20", &DNurbsSurfaceMaterial::b20},
    {"b11", &DNurbsSurfaceMaterial::b11},
    {"b02", &DNurbsSurfaceMaterial::b02}};

}  // namespace

template <typename ShapeType>
ShapeType read_scene_shape(const SceneReader& reader, const JsonValue& model,
                           const std::string& path, std::string& shape_file, const char* type) {
  const JsonValue* inline_shape = reader.find(model, "shape");
  const JsonValue* file = reader.find(model, "shape_file");
  const JsonValue* recipe = reader.find(model, "make");
  if ((inline_shape != nullptr) + (file != nullptr) + (recipe != nullptr) != 1) {
    reader.fail(join_json_path(path, "shape"),
                std::string("expected exactly one of \"shape\" (a ") + type +
                    " in the shape format of dnurbs eval), \"shape_file\", \"make\" (a shape "
                    "recipe) and \"fit\"");
  }
  std::optional<Shape> shape;
  if (recipe != nullptr) {
    shape = make_shape(reader, *recipe, join_json_path(path, "make"));
    if (!std::holds_alternative<ShapeType>(*shape)) {
      reader.fail(join_json_path(path, "make"),
                  std::string("expected a recipe that makes a ") + type + " for this model type");
    }
    return std::get<ShapeType>(*shape);
  }
  // A marker source lets the shape parser's "<source>: <path>: ..." become one scene path
  constexpr const char* kMarker = "\x01";
  try {
    if (inline_shape != nullptr) {
      if (!inline_shape->is_object()) {
        reader.fail(join_json_path(path, "shape"), std::string("expected a ") + type +
                                                       " object, got " +
                                                       describe_json_value(*inline_shape));
      }
      shape = parse_shape_json(inline_shape->dump(), kMarker);
    } else {
      shape_file = reader.string(*file, join_json_path(path, "shape_file"));
      shape = read_shape_file(reader.resolve(shape_file));
    }
  } catch (const Error& error) {
    std::string message = error.what();
    const std::string prefix = std::string(kMarker) + ": ";
    if (message.starts_with(prefix)) {
      // "<marker>: <shape path>: <expected>" becomes "<path>.shape.<shape path>: <expected>"
      const std::string rest = message.substr(prefix.size());
      const auto colon = rest.find(": ");
      if (colon != std::string::npos) {
        reader.fail(join_json_path(path, "shape") + "." + rest.substr(0, colon),
                    rest.substr(colon + 2));
      }
      reader.fail(join_json_path(path, "shape"), rest);
    }
    reader.fail(join_json_path(path, inline_shape != nullptr ? "shape" : "shape_file"), message);
  }
  if (!std::holds_alternative<ShapeType>(*shape)) {
    reader.fail(join_json_path(path, inline_shape != nullptr ? "shape" : "shape_file"),
                std::string("expected a ") + type + " for this model type");
  }
  return std::get<ShapeType>(*shape);
}

template NurbsCurve read_scene_shape<NurbsCurve>(const SceneReader&, const JsonValue&,
                                                 const std::string&, std::string&, const char*);
template NurbsSurface read_scene_shape<NurbsSurface>(const SceneReader&, const JsonValue&,
                                                     const std::string&, std::string&, const char*);

void write_scene_shape(const std::optional<Shape>& shape, const std::string& shape_file,
                       const std::optional<SceneFit>& fit, JsonOut& model) {
  if (fit) {
    model["fit"] = fit_json(*fit, true);
  } else if (!shape_file.empty()) {
    model["shape_file"] = shape_file;
  } else {
    model["shape"] = JsonOut::parse(shape_to_json(shape.value()));
  }
}

void read_dnurbs_settings(const SceneReader& reader, const JsonValue& model,
                          const std::string& path, DNurbsSettings& settings) {
  if (const JsonValue* weights = reader.find(model, "weights")) {
    settings.weight_mode =
        reader.choice(*weights, join_json_path(path, "weights"), {"fixed", "free"}) == "free"
            ? WeightMode::kFree
            : WeightMode::kFixed;
  }
  reader.integer_key(model, path, "quadrature_points", settings.quadrature_points, 0, 32);
  reader.number_key(model, path, "minimum_weight", settings.minimum_weight, 0.0, true);
  // The weight regularization of free weights (rational_control_net_model.h): absent keys keep
  // the scale-aware default.
  for (const auto& [key, member] :
       {std::pair{"weight_inertia", &DNurbsSettings::weight_inertia},
        std::pair{"weight_stiffness", &DNurbsSettings::weight_stiffness}}) {
    if (reader.find(model, key) != nullptr) {
      double value = 0.0;
      reader.number_key(model, path, key, value, 0.0, false);
      settings.*member = value;
    }
  }
  read_rest_shape_keys(reader, model, path, settings.initial_shape_at_rest, settings.plastic_flow);
}

void write_dnurbs_settings(const DNurbsSettings& settings, JsonOut& model) {
  model["weights"] = settings.weight_mode == WeightMode::kFree ? "free" : "fixed";
  model["quadrature_points"] = settings.quadrature_points;
  model["minimum_weight"] = settings.minimum_weight;
  if (settings.weight_inertia) {
    model["weight_inertia"] = *settings.weight_inertia;
  }
  if (settings.weight_stiffness) {
    model["weight_stiffness"] = *settings.weight_stiffness;
  }
  write_rest_shape_keys(settings.initial_shape_at_rest, settings.plastic_flow, model);
}

void read_dnurbs_surface_material(const SceneReader& reader, const JsonValue& model,
                                  const std::string& path, DNurbsSurfaceMaterial& material) {
  const JsonValue values = model_material(
      reader, model, path, {"mass_density", "damping_density", "a10", "a01", "b20", "b11", "b02"});
  const std::string material_path = join_json_path(path, "material");
  const Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  for (const SurfaceMaterialKey& entry : kSurfaceMaterialKeys) {
    double value = (material.*entry.member)(origin);
    reader.number_key(values, material_path, entry.key, value, 0.0, false);
    material.*entry.member = value;
  }
}

JsonOut dnurbs_surface_material_json(const DNurbsSurfaceMaterial& material) {
  JsonOut values = JsonOut::object();
  const Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  for (const SurfaceMaterialKey& entry : kSurfaceMaterialKeys) {
    values[entry.key] = (material.*entry.member)(origin);
  }
  return values;
}

}  // namespace dnurbs
