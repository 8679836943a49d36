#include "dnurbs/io/models/deformation_field_scene.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/scene_model_keys.h"
#include "dnurbs/nurbs/gauss_legendre.h"

namespace dnurbs {
namespace {

JsonOut field_json(const SceneVectorField& field) {
  JsonOut json = {{"type", field.type}};
  if (field.type == "uniform") {
    json["vector"] = json_array<3>(field.vector);
  } else if (field.type == "plane") {
    json["origin"] = json_array<3>(field.vector);
    json["u_axis"] = json_array<3>(field.u_axis);
    json["v_axis"] = json_array<3>(field.v_axis);
  } else if (field.type == "gaussian") {
    json["vector"] = json_array<3>(field.vector);
    json["centre"] = parameter_json(field.centre);
    json["radius"] = field.radius;
  } else {
    json["file"] = field.file;
  }
  return json;
}

SceneVectorField read_field(const SceneReader& reader, const JsonValue& value,
                            const std::string& path) {
  reader.object(value, path,
                {"type", "vector", "origin", "u_axis", "v_axis", "centre", "radius", "file"});
  SceneVectorField field;
  field.type = reader.choice(
      reader.require(value, path, "type", "uniform, plane, gaussian or geometry_image"),
      join_json_path(path, "type"), {"uniform", "plane", "gaussian", "geometry_image"});
  const auto vector_key = [&](const char* key, Eigen::Vector3d& v) {
    if (const JsonValue* x = reader.find(value, key)) {
      v = reader.point(*x, join_json_path(path, key));
    }
  };
  if (field.type == "uniform") {
    reader.object(value, path, {"type", "vector"});
    field.vector = reader.point(reader.require(value, path, "vector", "[x, y, z]"),
                                join_json_path(path, "vector"));
  } else if (field.type == "plane") {
    reader.object(value, path, {"type", "origin", "u_axis", "v_axis"});
    vector_key("origin", field.vector);
    vector_key("u_axis", field.u_axis);
    vector_key("v_axis", field.v_axis);
  } else if (field.type == "gaussian") {
    reader.object(value, path, {"type", "vector", "centre", "radius"});
    field.vector = reader.point(reader.require(value, path, "vector", "[x, y, z]"),
                                join_json_path(path, "vector"));
    if (const JsonValue* centre = reader.find(value, "centre")) {
      field.centre = reader.parameter(*centre, join_json_path(path, "centre"));
    }
    reader.number_key(value, path, "radius", field.radius, 0.0, true);
  } else {
    reader.object(value, path, {"type", "file"});
    const std::string file_path = join_json_path(path, "file");
    field.file =
        reader.string(reader.require(value, path, "file", "a geometry image file"), file_path);
    try {
      field.image = std::make_shared<const SampledVectorField>(
          read_face_geometry_image(reader.resolve(field.file).string()).samples);
    } catch (const Error& error) {
      reader.fail(file_path, error.what());
    }
  }
  return field;
}

SceneFieldStage read_stage(const SceneReader& reader, const JsonValue& value,
                           const std::string& path) {
  reader.object(value, path, {"type", "field", "parameter"});
  SceneFieldStage stage;
  stage.constant =
      reader.choice(reader.require(value, path, "type", "constant or add_vector"),
                    join_json_path(path, "type"), {"constant", "add_vector"}) == "constant";
  stage.field = read_field(reader, reader.require(value, path, "field", "a vector field object"),
                           join_json_path(path, "field"));
  if (const JsonValue* parameter = reader.find(value, "parameter")) {
    const std::string parameter_path = join_json_path(path, "parameter");
    if (stage.constant) {
      reader.fail(parameter_path, "a constant stage has no parameter (p = V, eqs. 2-3)");
    }
    stage.parameter = reader.name(*parameter, parameter_path);
  }
  return stage;
}

SceneFieldParameter read_parameter(const SceneReader& reader, const JsonValue& value,
                                   const std::string& path) {
  reader.object(value, path, {"name", "stiffness", "initial", "keyed"});
  SceneFieldParameter parameter;
  parameter.name =
      reader.name(reader.require(value, path, "name", "a name"), join_json_path(path, "name"));
  if (const JsonValue* keyed = reader.find(value, "keyed")) {
    for (const char* key : {"stiffness", "initial"}) {
      if (reader.find(value, key) != nullptr) {
        reader.fail(join_json_path(path, key),
                    "a keyed parameter follows its schedule: no \"" + std::string(key) + "\"");
      }
    }
    parameter.keyed = true;
    parameter.schedule = reader.scalar_schedule(*keyed, join_json_path(path, "keyed"));
  }
  reader.number_key(value, path, "stiffness", parameter.stiffness, 0.0, false);
  reader.number_key(value, path, "initial", parameter.initial);
  return parameter;
}

// The coordinate of each parameter: its place among the face's parameters, or in the list
void assign_coordinates(const SceneReader& reader, const std::string& path,
                        SceneDeformationField& spec) {
  const std::string list_path = join_json_path(path, "parameters");
  for (size_t i = 0; i < spec.parameters.size(); ++i) {
    SceneFieldParameter& parameter = spec.parameters[i];
    const std::string name_path = join_json_path(json_index_path(list_path, i), "name");
    for (size_t j = 0; j < i; ++j) {
      if (spec.parameters[j].name == parameter.name) {
        reader.fail(name_path, "parameter \"" + parameter.name + "\" is listed twice");
      }
    }
    if (!spec.face_model) {
      parameter.coordinate = static_cast<int>(i);
      continue;
    }
    const std::vector<std::string>& names = spec.face_model->parameter_names();
    const auto found = std::find(names.begin(), names.end(), parameter.name);
    if (found == names.end()) {
      std::string expected;
      for (const std::string& name : names) {
        expected += (expected.empty() ? "" : ", ") + name;
      }
      reader.fail(name_path, "the face has no parameter \"" + parameter.name +
                                 "\" (expected one of " + expected + ")");
    }
    parameter.coordinate = static_cast<int>(found - names.begin());
  }
  if (spec.face_model) {
    return;
  }
  // Stages name declared parameters, and every declared parameter moves some stage (else its
  // row of M is zero)
  for (size_t s = 0; s < spec.stages.size(); ++s) {
    const std::string& name = spec.stages[s].parameter;
    if (!name.empty() && std::none_of(spec.parameters.begin(), spec.parameters.end(),
                                      [&](const auto& p) { return p.name == name; })) {
      reader.fail(join_json_path(json_index_path(join_json_path(path, "stages"), s), "parameter"),
                  "no parameter \"" + name + "\" in \"parameters\"");
    }
  }
  for (size_t i = 0; i < spec.parameters.size(); ++i) {
    const std::string& name = spec.parameters[i].name;
    if (std::none_of(spec.stages.begin(), spec.stages.end(),
                     [&](const auto& stage) { return stage.parameter == name; })) {
      reader.fail(join_json_path(json_index_path(list_path, i), "name"),
                  "parameter \"" + name + "\" moves no add_vector stage");
    }
  }
}

void read_settings(const SceneReader& reader, const JsonValue& model, const std::string& path,
                   DeformationFieldSettings& settings) {
  const JsonValue material =
      model_material(reader, model, path, {"mass_density", "damping_density"});
  const std::string material_path = join_json_path(path, "material");
  reader.number_key(material, material_path, "mass_density", settings.mass_density, 0.0, true);
  reader.number_key(material, material_path, "damping_density", settings.damping_density, 0.0,
                    false);
  if (const JsonValue* quadrature = reader.find(model, "quadrature")) {
    const std::string quadrature_path = join_json_path(path, "quadrature");
    reader.object(*quadrature, quadrature_path, {"cells", "points"});
    if (const JsonValue* cells = reader.find(*quadrature, "cells")) {
      const std::string cells_path = join_json_path(quadrature_path, "cells");
      const JsonValue& pair = reader.array(*cells, cells_path, "[cells_u, cells_v]");
      if (pair.size() != 2) {
        reader.fail(cells_path,
                    "expected [cells_u, cells_v], got " + std::to_string(pair.size()) + " numbers");
      }
      settings.quadrature_cells_u = reader.integer(pair[0], json_index_path(cells_path, 0), 1, 256);
      settings.quadrature_cells_v = reader.integer(pair[1], json_index_path(cells_path, 1), 1, 256);
    }
    reader.integer_key(*quadrature, quadrature_path, "points", settings.quadrature_points, 1,
                       kMaxGaussPoints);
  }
  reader.number_key(model, path, "max_error", settings.tessellation_max_error, 0.0, false);
  reader.integer_key(model, path, "max_level", settings.tessellation_max_level, 0, 30);
}

}  // namespace

VectorField SceneVectorField::function() const {
  if (type == "uniform") {
    return [v = vector](double, double) { return Eigen::Vector3d(v); };
  }
  if (type == "plane") {
    return [o = vector, a = u_axis, b = v_axis](double u, double v) -> Eigen::Vector3d {
      return o + u * a + v * b;
    };
  }
  if (type == "gaussian") {
    return [v = vector, c = centre, r = radius](double u, double w) -> Eigen::Vector3d {
      return v * std::exp(-(Eigen::Vector2d(u, w) - c).squaredNorm() / (r * r));
    };
  }
  return [samples = image](double u, double v) { return (*samples)(u, v); };
}

std::unique_ptr<SceneModelSpec> SceneDeformationField::clone() const {
  return std::make_unique<SceneDeformationField>(*this);
}

void SceneDeformationField::write(JsonOut& model) const {
  if (face_model) {
    model["face"] = face;
  } else {
    model["domain"] = {domain.u_min, domain.u_max, domain.v_min, domain.v_max};
    JsonOut list = JsonOut::array();
    for (const SceneFieldStage& stage : stages) {
      JsonOut json = {{"type", stage.constant ? "constant" : "add_vector"},
                      {"field", field_json(stage.field)}};
      if (!stage.parameter.empty()) {
        json["parameter"] = stage.parameter;
      }
      list.push_back(json);
    }
    model["stages"] = list;
  }
  JsonOut list = JsonOut::array();
  for (const SceneFieldParameter& parameter : parameters) {
    JsonOut json = {{"name", parameter.name}};
    if (parameter.keyed) {
      json["keyed"] = schedule_json(parameter.schedule);
    } else {
      json["stiffness"] = parameter.stiffness;
      json["initial"] = parameter.initial;
    }
    list.push_back(json);
  }
  model["parameters"] = list;
  model["material"] = {{"mass_density", settings.mass_density},
                       {"damping_density", settings.damping_density}};
  model["quadrature"] = {{"cells", {settings.quadrature_cells_u, settings.quadrature_cells_v}},
                         {"points", settings.quadrature_points}};
  model["max_error"] = settings.tessellation_max_error;
  model["max_level"] = settings.tessellation_max_level;
}

std::unique_ptr<Model> SceneDeformationField::build() const {
  DeformationField field;
  if (face_model) {
    field = face_model->field();
  } else {
    // Stage parameters by name: coordinate k is parameters[k] (assign_coordinates)
    for (const SceneFieldStage& stage : stages) {
      if (stage.constant) {
        field.constant(stage.field.function());
      } else if (stage.parameter.empty()) {
        field.add_vector(stage.field.function());
      } else {
        const auto found = std::find_if(parameters.begin(), parameters.end(),
                                        [&](const auto& p) { return p.name == stage.parameter; });
        field.add_vector(stage.field.function(), found->coordinate);
      }
    }
  }
  const int count = field.parameter_count();
  // Face parameters the scene does not list stay at rest (fixed at 0)
  std::vector<bool> fixed(static_cast<size_t>(count), true);
  Eigen::VectorXd initial = Eigen::VectorXd::Zero(count);
  DeformationFieldSettings model_settings = settings;
  model_settings.stiffness = Eigen::VectorXd::Zero(count);
  for (const SceneFieldParameter& parameter : parameters) {
    const auto k = static_cast<size_t>(parameter.coordinate);
    fixed[k] = parameter.keyed;
    initial(parameter.coordinate) =
        parameter.keyed ? parameter.schedule.at(0.0) : parameter.initial;
    model_settings.stiffness(parameter.coordinate) = parameter.keyed ? 0.0 : parameter.stiffness;
  }
  auto model = std::make_unique<DeformationFieldModel>(
      field, std::nullopt, face_model ? face_model->domain() : domain, initial, model_settings);
  for (int k = 0; k < count; ++k) {
    if (fixed[static_cast<size_t>(k)]) {
      model->fix_coordinate(k);
    }
  }
  return model;
}

std::vector<std::pair<int, double>> SceneDeformationField::prescribed_coordinates(
    double time) const {
  std::vector<std::pair<int, double>> values;
  for (const SceneFieldParameter& parameter : parameters) {
    if (parameter.keyed) {
      values.emplace_back(parameter.coordinate, parameter.schedule.at(time));
    }
  }
  return values;
}

std::unique_ptr<SceneModelSpec> read_deformation_field_scene(const SceneReader& reader,
                                                             const JsonValue& model,
                                                             const std::string& path) {
  check_model_keys(
      reader, model, path, "deformation_field",
      {"face", "stages", "domain", "parameters", "quadrature", "max_error", "max_level"});
  auto spec = std::make_unique<SceneDeformationField>();
  const JsonValue* face = reader.find(model, "face");
  const JsonValue* stages = reader.find(model, "stages");
  if ((face == nullptr) == (stages == nullptr)) {
    reader.fail(path, "expected exactly one of \"face\" (a geometry image file) and \"stages\"");
  }
  if (face != nullptr) {
    const std::string face_path = join_json_path(path, "face");
    if (reader.find(model, "domain") != nullptr) {
      reader.fail(join_json_path(path, "domain"), "a face is over the unit square: no domain");
    }
    spec->face = reader.string(*face, face_path);
    try {
      spec->face_model = std::make_shared<const DeformableFace>(
          DeformableFace::read(reader.resolve(spec->face).string()));
    } catch (const Error& error) {
      reader.fail(face_path, error.what());
    }
  } else {
    if (const JsonValue* domain = reader.find(model, "domain")) {
      const std::string domain_path = join_json_path(path, "domain");
      const Eigen::Vector4d d =
          reader.vector<4>(*domain, domain_path, "[u_min, u_max, v_min, v_max]");
      spec->domain.u_min = d(0);
      spec->domain.u_max = d(1);
      spec->domain.v_min = d(2);
      spec->domain.v_max = d(3);
      try {
        spec->domain.validate();
      } catch (const Error& error) {
        reader.fail(domain_path, error.what());
      }
    }
    const std::string stages_path = join_json_path(path, "stages");
    const JsonValue& list = reader.array(*stages, stages_path, "stages");
    for (size_t i = 0; i < list.size(); ++i) {
      spec->stages.push_back(read_stage(reader, list[i], json_index_path(stages_path, i)));
    }
  }
  const std::string parameters_path = join_json_path(path, "parameters");
  const JsonValue& list =
      reader.array(reader.require(model, path, "parameters", "an array of parameters"),
                   parameters_path, "parameters");
  if (list.empty()) {
    reader.fail(parameters_path, "expected at least one parameter");
  }
  for (size_t i = 0; i < list.size(); ++i) {
    spec->parameters.push_back(
        read_parameter(reader, list[i], json_index_path(parameters_path, i)));
  }
  assign_coordinates(reader, path, *spec);
  read_settings(reader, model, path, spec->settings);
  return spec;
}

}  // namespace dnurbs
