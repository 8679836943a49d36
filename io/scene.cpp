#include "io/scene.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "constraints/target_trajectory.h"
#include "io/json_messages.h"
#include "io/scene_fit.h"
#include "io/scene_materials.h"
#include "core/error.h"

namespace dnurbs {
namespace {

using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json;

// In the order of SceneModel::spec's alternatives
constexpr const char* kModelTypes[] = {"superquadric", "terzopoulos_surface", "pde_surface",
                                       "snake",        "dnurbs_curve",        "dnurbs_surface"};
constexpr const char* kShapeKeys[] = {"a",  "a1", "a2", "a3", "e1",  "e2", "t1",
                                      "t2", "b1", "b2", "b3", "tau", "sx", "sy"};

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string list_of(std::initializer_list<const char*> names) {
  std::string list;
  for (const char* name : names) {
    if (!list.empty()) {
      list += ", ";
    }
    list += name;
  }
  return list;
}

// Reads typed values out of the parsed document; every failure names the source and JSON path.
class Reader {
 public:
  Reader(std::string source, std::filesystem::path directory)
      : source_(std::move(source)), directory_(std::move(directory)) {}

  const std::string& source() const { return source_; }
  const std::filesystem::path& directory() const { return directory_; }

  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    std::string text = source_;
    text += ": ";
    text += path.empty() ? std::string("(top level)") : path;
    text += ": ";
    text += message;
    throw Error(text);
  }

  // Checks that `value` is an object with only the allowed keys
  void object(const Json& value, const std::string& path,
              std::initializer_list<const char*> allowed) const {
    if (!value.is_object()) {
      fail(path, "expected an object, got " + describe_json_value(value));
    }
    for (const auto& item : value.items()) {
      bool known = false;
      for (const char* name : allowed) {
        known = known || item.key() == name;
      }
      if (!known) {
        fail(join(path, item.key()), "unknown key (expected only " + list_of(allowed) + ")");
      }
    }
  }

  const Json* find(const Json& object, const char* key) const {
    const auto found = object.find(key);
    return found == object.end() ? nullptr : &*found;
  }

  const Json& require(const Json& object, const std::string& path, const char* key,
                      const std::string& expected) const {
    const Json* found = find(object, key);
    if (found == nullptr) {
      fail(join(path, key), "missing key (expected " + expected + ")");
    }
    return *found;
  }

  double number(const Json& value, const std::string& path) const {
    if (!value.is_number()) {
      fail(path, "expected a finite number, got " + describe_json_value(value));
    }
    return value.get<double>();
  }

  // A number with a lower bound (strict or not)
  double bounded(const Json& value, const std::string& path, double minimum, bool strict) const {
    const double x = number(value, path);
    if (strict ? !(x > minimum) : !(x >= minimum)) {
      fail(path, std::string("expected a number ") + (strict ? "> " : ">= ") +
                     format_json_number(minimum) + ", got " + format_json_number(x));
    }
    return x;
  }

  // An optional number key: keeps `x` when absent
  void number_key(const Json& object, const std::string& path, const char* key, double& x,
                  std::optional<double> minimum = std::nullopt, bool strict = false) const {
    if (const Json* value = find(object, key)) {
      x = minimum ? bounded(*value, join(path, key), *minimum, strict)
                  : number(*value, join(path, key));
    }
  }

  int integer(const Json& value, const std::string& path, int minimum, int maximum) const {
    const std::string expected =
        "an integer in " + std::to_string(minimum) + ".." + std::to_string(maximum);
    if (!value.is_number_integer()) {
      fail(path, "expected " + expected + ", got " + describe_json_value(value));
    }
    const auto n = value.get<long long>();
    if (n < minimum || n > maximum) {
      fail(path, "expected " + expected + ", got " + describe_json_value(value));
    }
    return static_cast<int>(n);
  }

  void integer_key(const Json& object, const std::string& path, const char* key, int& n,
                   int minimum, int maximum) const {
    if (const Json* value = find(object, key)) {
      n = integer(*value, join(path, key), minimum, maximum);
    }
  }

  void boolean_key(const Json& object, const std::string& path, const char* key, bool& b) const {
    if (const Json* value = find(object, key)) {
      if (!value->is_boolean()) {
        fail(join(path, key), "expected true or false, got " + describe_json_value(*value));
      }
      b = value->get<bool>();
    }
  }

  std::string string(const Json& value, const std::string& path) const {
    if (!value.is_string()) {
      fail(path, "expected a string, got " + describe_json_value(value));
    }
    return value.get<std::string>();
  }

  std::string choice(const Json& value, const std::string& path,
                     std::initializer_list<const char*> options) const {
    const std::string text = value.is_string() ? value.get<std::string>() : std::string();
    for (const char* option : options) {
      if (value.is_string() && text == option) {
        return text;
      }
    }
    fail(path, "expected one of " + list_of(options) + ", got " + describe_json_value(value));
  }

  template <int N>
  Eigen::Matrix<double, N, 1> vector(const Json& value, const std::string& path,
                                     const char* what) const {
    if (!value.is_array() || value.size() != N) {
      fail(path, std::string("expected ") + what + ", got " + describe_json_value(value));
    }
    Eigen::Matrix<double, N, 1> v;
    for (int i = 0; i < N; ++i) {
      v(i) = number(value[static_cast<size_t>(i)], json_index_path(path, static_cast<size_t>(i)));
    }
    return v;
  }

  Eigen::Vector3d point(const Json& value, const std::string& path) const {
    return vector<3>(value, path, "[x, y, z]");
  }

  // A material parameter: [u] (curves) or [u, v]
  Eigen::Vector2d parameter(const Json& value, const std::string& path) const {
    if (!value.is_array() || value.empty() || value.size() > 2) {
      fail(path, "expected a material parameter [u] or [u, v], got " + describe_json_value(value));
    }
    Eigen::Vector2d u = Eigen::Vector2d::Zero();
    for (size_t i = 0; i < value.size(); ++i) {
      u(static_cast<int>(i)) = number(value[i], json_index_path(path, i));
    }
    return u;
  }

  const Json& array(const Json& value, const std::string& path, const std::string& of) const {
    if (!value.is_array()) {
      fail(path, "expected an array of " + of + ", got " + describe_json_value(value));
    }
    return value;
  }

  std::vector<int> indices(const Json& value, const std::string& path) const {
    array(value, path, "indices");
    std::vector<int> result;
    for (size_t i = 0; i < value.size(); ++i) {
      result.push_back(integer(value[i], json_index_path(path, i), 0, 1 << 30));
    }
    return result;
  }

  void times(const Json& object, const std::string& path, std::vector<double>& times,
             size_t value_count) const {
    const std::string times_path = join(path, "times");
    const Json& list = array(require(object, path, "times", "an array of keyframe times"),
                             times_path, "keyframe times");
    if (list.size() < 2) {
      fail(times_path, "expected at least 2 keyframe times, got " + describe_json_value(list));
    }
    for (size_t i = 0; i < list.size(); ++i) {
      times.push_back(number(list[i], json_index_path(times_path, i)));
      if (i > 0 && !(times[i] > times[i - 1])) {
        fail(json_index_path(times_path, i), "expected strictly increasing keyframe times, got " +
                                                 format_json_number(times[i]) + " after " +
                                                 format_json_number(times[i - 1]));
      }
    }
    if (value_count != times.size()) {
      fail(join(path, "values"), "expected " + std::to_string(times.size()) +
                                     " values (one per keyframe time), got " +
                                     std::to_string(value_count));
    }
  }

  VectorSchedule vector_schedule(const Json& value, const std::string& path) const {
    VectorSchedule schedule;
    if (value.is_array()) {
      schedule.values.push_back(point(value, path));
      return schedule;
    }
    if (!value.is_object()) {
      fail(path, "expected [x, y, z] or {\"times\": [...], \"values\": [[x, y, z], ...]}, got " +
                     describe_json_value(value));
    }
    object(value, path, {"times", "values"});
    const std::string values_path = join(path, "values");
    const Json& values = array(require(value, path, "values", "an array of [x, y, z] values"),
                               values_path, "[x, y, z] values");
    for (size_t i = 0; i < values.size(); ++i) {
      schedule.values.push_back(point(values[i], json_index_path(values_path, i)));
    }
    times(value, path, schedule.times, values.size());
    return schedule;
  }

  ScalarSchedule scalar_schedule(const Json& value, const std::string& path) const {
    ScalarSchedule schedule;
    if (value.is_number()) {
      schedule.values.push_back(number(value, path));
      return schedule;
    }
    if (!value.is_object()) {
      fail(path, "expected a number or {\"times\": [...], \"values\": [...]}, got " +
                     describe_json_value(value));
    }
    object(value, path, {"times", "values"});
    const std::string values_path = join(path, "values");
    const Json& values =
        array(require(value, path, "values", "an array of numbers"), values_path, "numbers");
    for (size_t i = 0; i < values.size(); ++i) {
      schedule.values.push_back(number(values[i], json_index_path(values_path, i)));
    }
    times(value, path, schedule.times, values.size());
    return schedule;
  }

 private:
  std::string source_;
  std::filesystem::path directory_;
};

// Model references: an index or a model name
class ModelNames {
 public:
  explicit ModelNames(const std::vector<SceneModel>& models) : models_(models) {}
  int resolve(const Reader& reader, const Json& value, const std::string& path) const {
    const int count = static_cast<int>(models_.size());
    if (value.is_string()) {
      const std::string name = value.get<std::string>();
      for (int i = 0; i < count; ++i) {
        if (models_[static_cast<size_t>(i)].name == name) {
          return i;
        }
      }
      reader.fail(path,
                  "expected the name or index of a model, got unknown model name \"" + name + "\"");
    }
    if (!value.is_number_integer() || value.get<long long>() < 0 ||
        value.get<long long>() >= count) {
      reader.fail(path, "expected a model index in 0.." + std::to_string(count - 1) +
                            " or a model name, got " + describe_json_value(value));
    }
    return value.get<int>();
  }
  int require(const Reader& reader, const Json& object, const std::string& path,
              const char* key) const {
    return resolve(reader, reader.require(object, path, key, "a model index or name"),
                   join(path, key));
  }

 private:
  const std::vector<SceneModel>& models_;
};

// Reads a shape from "shape" (inline) or "shape_file", with the JSON path in messages
template <typename ShapeType>
ShapeType read_shape(const Reader& reader, const Json& model, const std::string& path,
                     std::string& shape_file, const char* type) {
  const Json* inline_shape = reader.find(model, "shape");
  const Json* file = reader.find(model, "shape_file");
  if ((inline_shape == nullptr) == (file == nullptr)) {
    reader.fail(join(path, "shape"),
                std::string("expected exactly one of \"shape\" (a ") + type +
                    " in the shape format of dnurbs eval), \"shape_file\" and \"fit\"");
  }
  std::optional<Shape> shape;
  // A marker source lets the shape parser's "<source>: <path>: ..." become one scene path
  constexpr const char* kMarker = "\x01";
  try {
    if (inline_shape != nullptr) {
      if (!inline_shape->is_object()) {
        reader.fail(join(path, "shape"), std::string("expected a ") + type + " object, got " +
                                             describe_json_value(*inline_shape));
      }
      shape = parse_shape_json(inline_shape->dump(), kMarker);
    } else {
      shape_file = reader.string(*file, join(path, "shape_file"));
      std::filesystem::path file_path = shape_file;
      if (file_path.is_relative()) {
        file_path = reader.directory() / file_path;
      }
      shape = read_shape_file(file_path);
    }
  } catch (const Error& error) {
    std::string message = error.what();
    const std::string prefix = std::string(kMarker) + ": ";
    if (message.starts_with(prefix)) {
      // "<marker>: <shape path>: <expected>" becomes "<path>.shape.<shape path>: <expected>"
      const std::string rest = message.substr(prefix.size());
      const auto colon = rest.find(": ");
      if (colon != std::string::npos) {
        reader.fail(join(path, "shape") + "." + rest.substr(0, colon), rest.substr(colon + 2));
      }
      reader.fail(join(path, "shape"), rest);
    }
    reader.fail(join(path, inline_shape != nullptr ? "shape" : "shape_file"), message);
  }
  if (!std::holds_alternative<ShapeType>(*shape)) {
    reader.fail(join(path, inline_shape != nullptr ? "shape" : "shape_file"),
                std::string("expected a ") + type + " for this model type");
  }
  return std::get<ShapeType>(*shape);
}

void read_dnurbs_settings(const Reader& reader, const Json& model, const std::string& path,
                          SceneDNurbsSettings& settings) {
  if (const Json* weights = reader.find(model, "weights")) {
    settings.free_weights =
        reader.choice(*weights, join(path, "weights"), {"fixed", "free"}) == "free";
  }
  reader.integer_key(model, path, "quadrature_points", settings.quadrature_points, 0, 32);
  reader.number_key(model, path, "minimum_weight", settings.minimum_weight, 0.0, true);
}

// Reads the "fit" object of a model, if present: `dnurbs` selects the D-NURBS keys (degree,
// spans, smoothness, iterations) or the superquadric ones (max_evaluations); `instead_of` are
// the keys that give the shape the fit replaces.
std::optional<SceneFit> read_fit(const Reader& reader, const Json& model, const std::string& path,
                                 bool dnurbs, std::initializer_list<const char*> instead_of) {
  const Json* value = reader.find(model, "fit");
  if (value == nullptr) {
    return std::nullopt;
  }
  const std::string fit_path = join(path, "fit");
  for (const char* key : instead_of) {
    if (reader.find(model, key) != nullptr) {
      reader.fail(fit_path, std::string("expected either \"fit\" or \"") + key +
                                "\", not both (the fit gives the initial shape)");
    }
  }
  if (dnurbs) {
    reader.object(*value, fit_path, {"points", "degree", "spans", "smoothness", "iterations"});
  } else {
    reader.object(*value, fit_path, {"points", "max_evaluations"});
  }
  SceneFit fit;
  fit.points =
      reader.string(reader.require(*value, fit_path, "points", "a file of points or a mesh"),
                    join(fit_path, "points"));
  reader.integer_key(*value, fit_path, "degree", fit.degree, 1, 9);
  reader.integer_key(*value, fit_path, "spans", fit.spans, 1, 1000);
  reader.number_key(*value, fit_path, "smoothness", fit.smoothness, 0.0, false);
  reader.integer_key(*value, fit_path, "iterations", fit.iterations, 1, 100000);
  reader.integer_key(*value, fit_path, "max_evaluations", fit.max_evaluations, 1, 100000000);
  return fit;
}

// The points of a fit, the file resolved against the scene's directory (as "shape_file")
Eigen::MatrixX3d fit_points(const Reader& reader, const std::string& path, const SceneFit& fit) {
  std::filesystem::path file = fit.points;
  if (file.is_relative()) {
    file = reader.directory() / file;
  }
  try {
    return read_fit_points(file);
  } catch (const Error& error) {
    reader.fail(join(join(path, "fit"), "points"), error.what());
  }
}

// Runs a fit, failing with the model's "fit" path if the fitter throws (points errors name
// "fit.points" already)
template <typename Fit>
auto fitted(const Reader& reader, const std::string& path, Fit fit) {
  try {
    return fit();
  } catch (const Error& error) {
    const std::string message = error.what();
    if (message.starts_with(reader.source() + ": ")) {
      throw;
    }
    reader.fail(join(path, "fit"), message);
  }
}

SceneGrid read_grid(const Reader& reader, const Json& model, const std::string& path) {
  const std::string grid_path = join(path, "grid");
  const Json& grid = reader.require(model, path, "grid", "a grid object");
  reader.object(grid, grid_path, {"nodes", "spacing", "origin", "axis_u", "axis_v"});
  SceneGrid result;
  const std::string nodes_path = join(grid_path, "nodes");
  const Json& nodes = reader.require(grid, grid_path, "nodes", "[nodes_u, nodes_v]");
  if (!nodes.is_array() || nodes.size() != 2) {
    reader.fail(nodes_path, "expected [nodes_u, nodes_v], got " + describe_json_value(nodes));
  }
  result.nodes_u = reader.integer(nodes[0], json_index_path(nodes_path, 0), 3, 4096);
  result.nodes_v = reader.integer(nodes[1], json_index_path(nodes_path, 1), 3, 4096);
  result.spacing = reader.bounded(reader.require(grid, grid_path, "spacing", "a spacing > 0"),
                                  join(grid_path, "spacing"), 0.0, true);
  if (const Json* origin = reader.find(grid, "origin")) {
    result.origin = reader.point(*origin, join(grid_path, "origin"));
  }
  if (const Json* axis = reader.find(grid, "axis_u")) {
    result.axis_u = reader.point(*axis, join(grid_path, "axis_u"));
  }
  if (const Json* axis = reader.find(grid, "axis_v")) {
    result.axis_v = reader.point(*axis, join(grid_path, "axis_v"));
  }
  return result;
}

Eigen::Matrix2d read_tensor(const Reader& reader, const Json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 2) {
    reader.fail(path, "expected a 2 x 2 matrix [[m11, m12], [m21, m22]], got " +
                          describe_json_value(value));
  }
  Eigen::Matrix2d m;
  for (size_t r = 0; r < 2; ++r) {
    const Eigen::Vector2d row =
        reader.vector<2>(value[r], json_index_path(path, r), "a row [m1, m2]");
    m.row(static_cast<int>(r)) = row.transpose();
  }
  return m;
}

SceneModel read_model(const Reader& reader, const Json& value, const std::string& path,
                      size_t index) {
  if (!value.is_object()) {
    reader.fail(path, "expected a model object, got " + describe_json_value(value));
  }
  SceneModel model;
  const std::string type =
      reader.choice(reader.require(value, path, "type", "a model type"), join(path, "type"),
                    {"dnurbs_curve", "dnurbs_surface", "superquadric", "terzopoulos_surface",
                     "pde_surface", "snake"});
  model.name = "model" + std::to_string(index);
  if (const Json* name = reader.find(value, "name")) {
    model.name = reader.string(*name, join(path, "name"));
  }
  const std::string material_path = join(path, "material");
  const Json empty = Json::object();
  const Json* material_json = reader.find(value, "material");
  const Json& material = material_json != nullptr ? *material_json : empty;
  auto material_keys = [&](std::initializer_list<const char*> keys) {
    reader.object(material, material_path, keys);
  };
  auto non_negative = [&](const char* key, double& x) {
    reader.number_key(material, material_path, key, x, 0.0, false);
  };
  auto positive = [&](const char* key, double& x) {
    reader.number_key(material, material_path, key, x, 0.0, true);
  };
  std::initializer_list<const char*> common = {"type", "name", "material", "boundary",
                                               "resolution_scale"};
  auto model_keys = [&](std::initializer_list<const char*> extra) {
    std::vector<const char*> all(common);
    all.insert(all.end(), extra);
    // initializer_list cannot be built at run time: check unknown keys here
    for (const auto& item : value.items()) {
      bool known = false;
      for (const char* name : all) {
        known = known || item.key() == name;
      }
      if (!known) {
        std::string list;
        for (const char* name : all) {
          list += list.empty() ? std::string(name) : std::string(", ") + name;
        }
        reader.fail(join(path, item.key()),
                    "unknown key for a " + type + " model (expected only " + list + ")");
      }
    }
  };

  if (type == "dnurbs_curve") {
    model_keys({"shape", "shape_file", "fit", "weights", "quadrature_points", "minimum_weight"});
    double mass_density = 1.0;
    double damping_density = 0.0;
    double tension = 0.0;
    double rigidity = 0.0;
    material_keys({"mass_density", "damping_density", "tension", "rigidity"});
    non_negative("mass_density", mass_density);
    non_negative("damping_density", damping_density);
    non_negative("tension", tension);
    non_negative("rigidity", rigidity);
    SceneDNurbsSettings settings;
    read_dnurbs_settings(reader, value, path, settings);
    std::string file;
    std::optional<SceneFit> fit = read_fit(reader, value, path, true, {"shape", "shape_file"});
    NurbsCurve curve =
        fit ? fitted(reader, path,
                     [&] {
                       return fit_scene_curve(
                           fit_points(reader, path, *fit), *fit,
                           dnurbs_curve_material(mass_density, damping_density, tension, rigidity),
                           dnurbs_settings(settings));
                     })
            : read_shape<NurbsCurve>(reader, value, path, file, "nurbs_curve");
    model.spec = SceneDNurbsCurve{std::move(curve), std::move(file), mass_density, damping_density,
                                  tension,          rigidity,        settings,     std::move(fit)};
  } else if (type == "dnurbs_surface") {
    model_keys({"shape", "shape_file", "fit", "weights", "quadrature_points", "minimum_weight"});
    double mass_density = 1.0;
    double damping_density = 0.0;
    Eigen::Matrix<double, 5, 1> stiffness = Eigen::Matrix<double, 5, 1>::Zero();
    material_keys({"mass_density", "damping_density", "a10", "a01", "b20", "b11", "b02"});
    non_negative("mass_density", mass_density);
    non_negative("damping_density", damping_density);
    non_negative("a10", stiffness(0));
    non_negative("a01", stiffness(1));
    non_negative("b20", stiffness(2));
    non_negative("b11", stiffness(3));
    non_negative("b02", stiffness(4));
    SceneDNurbsSettings settings;
    read_dnurbs_settings(reader, value, path, settings);
    std::string file;
    std::optional<SceneFit> fit = read_fit(reader, value, path, true, {"shape", "shape_file"});
    NurbsSurface surface =
        fit ? fitted(reader, path,
                     [&] {
                       return fit_scene_surface(
                           fit_points(reader, path, *fit), *fit,
                           dnurbs_surface_material(mass_density, damping_density, stiffness),
                           dnurbs_settings(settings));
                     })
            : read_shape<NurbsSurface>(reader, value, path, file, "nurbs_surface");
    model.spec =
        SceneDNurbsSurface{std::move(surface), std::move(file), mass_density,  damping_density,
                           stiffness(0),       stiffness(1),    stiffness(2),  stiffness(3),
                           stiffness(4),       settings,        std::move(fit)};
  } else if (type == "superquadric") {
    model_keys({"shape", "centre", "orientation", "fit", "parts", "mesh_cells", "quadrature_points",
                "regularization"});
    SceneSuperquadric spec;
    spec.fit = read_fit(reader, value, path, false, {"shape", "centre", "orientation"});
    if (spec.fit) {
      fitted(reader, path,
             [&] { fit_scene_superquadric(fit_points(reader, path, *spec.fit), *spec.fit, spec); });
    }
    if (const Json* shape = reader.find(value, "shape")) {
      const std::string shape_path = join(path, "shape");
      reader.object(*shape, shape_path,
                    {kShapeKeys[0], kShapeKeys[1], kShapeKeys[2], kShapeKeys[3], kShapeKeys[4],
                     kShapeKeys[5], kShapeKeys[6], kShapeKeys[7], kShapeKeys[8], kShapeKeys[9],
                     kShapeKeys[10], kShapeKeys[11], kShapeKeys[12], kShapeKeys[13]});
      for (int k = 0; k < 14; ++k) {
        double& x = spec.shape(k);
        if (k < 4) {
          reader.number_key(*shape, shape_path, kShapeKeys[k], x, 0.0, true);
        } else if (k < 6) {
          reader.number_key(*shape, shape_path, kShapeKeys[k], x, 0.1, false);
          if (x > 4.0) {
            reader.fail(join(shape_path, kShapeKeys[k]),
                        "expected a squareness in 0.1..4, got " + format_json_number(x));
          }
        } else {
          reader.number_key(*shape, shape_path, kShapeKeys[k], x);
        }
      }
    }
    if (const Json* centre = reader.find(value, "centre")) {
      spec.centre = reader.point(*centre, join(path, "centre"));
    }
    if (const Json* orientation = reader.find(value, "orientation")) {
      spec.orientation =
          reader.vector<4>(*orientation, join(path, "orientation"), "a quaternion [w, x, y, z]");
      if (std::abs(spec.orientation.norm() - 1.0) > 1e-6) {
        reader.fail(join(path, "orientation"),
                    "expected a unit quaternion [w, x, y, z], got one of norm " +
                        format_json_number(spec.orientation.norm()));
      }
    }
    if (const Json* parts = reader.find(value, "parts")) {
      spec.parts = reader.choice(*parts, join(path, "parts"), {"rigid", "global", "full"});
    }
    if (const Json* cells = reader.find(value, "mesh_cells")) {
      const std::string cells_path = join(path, "mesh_cells");
      if (!cells->is_array() || cells->size() != 2) {
        reader.fail(cells_path, "expected [cells_u, cells_v], got " + describe_json_value(*cells));
      }
      spec.mesh_cells_u = reader.integer((*cells)[0], json_index_path(cells_path, 0), 2, 1024);
      spec.mesh_cells_v = reader.integer((*cells)[1], json_index_path(cells_path, 1), 3, 1024);
    }
    reader.integer_key(value, path, "quadrature_points", spec.quadrature_points, 1, 16);
    reader.number_key(value, path, "regularization", spec.regularization, 0.0, false);
    material_keys(
        {"mass_density", "damping_alpha", "damping_beta", "shape_stiffness", "local_stiffness"});
    positive("mass_density", spec.mass_density);
    non_negative("damping_alpha", spec.damping_alpha);
    non_negative("damping_beta", spec.damping_beta);
    non_negative("shape_stiffness", spec.shape_stiffness);
    if (const Json* local = reader.find(material, "local_stiffness")) {
      spec.local_stiffness = reader.point(*local, join(material_path, "local_stiffness"));
      if ((spec.local_stiffness.array() < 0.0).any()) {
        reader.fail(join(material_path, "local_stiffness"),
                    "expected [membrane_u, membrane_v, spring] >= 0");
      }
    }
    model.spec = spec;
  } else if (type == "terzopoulos_surface") {
    model_keys({"grid", "normal", "delta"});
    SceneTerzopoulosSurface spec;
    spec.grid = read_grid(reader, value, path);
    if (const Json* normal = reader.find(value, "normal")) {
      spec.normal = reader.choice(*normal, join(path, "normal"), {"classic", "christoffel"});
    }
    reader.number_key(value, path, "delta", spec.delta, 0.0, true);
    material_keys({"mass_density", "damping_density", "eta", "xi"});
    positive("mass_density", spec.mass_density);
    non_negative("damping_density", spec.damping_density);
    if (const Json* eta = reader.find(material, "eta")) {
      spec.eta = read_tensor(reader, *eta, join(material_path, "eta"));
    }
    if (const Json* xi = reader.find(material, "xi")) {
      spec.xi = read_tensor(reader, *xi, join(material_path, "xi"));
    }
    model.spec = spec;
  } else if (type == "pde_surface") {
    model_keys({"grid", "regions"});
    ScenePdeSurface spec;
    spec.grid = read_grid(reader, value, path);
    material_keys({"b", "c", "d", "density", "damping", "su0", "su1", "sv0", "sv1"});
    non_negative("b", spec.b);
    non_negative("c", spec.c);
    non_negative("d", spec.d);
    positive("density", spec.density);
    non_negative("damping", spec.damping);
    reader.number_key(material, material_path, "su0", spec.su0);
    reader.number_key(material, material_path, "su1", spec.su1);
    reader.number_key(material, material_path, "sv0", spec.sv0);
    reader.number_key(material, material_path, "sv1", spec.sv1);
    if (const Json* regions = reader.find(value, "regions")) {
      const std::string regions_path = join(path, "regions");
      reader.array(*regions, regions_path, "{\"centre\": [x, y, z], \"radius\": r} regions");
      for (size_t r = 0; r < regions->size(); ++r) {
        const std::string region_path = json_index_path(regions_path, r);
        const Json& region = (*regions)[r];
        reader.object(region, region_path, {"centre", "radius"});
        spec.region_centres.push_back(
            reader.point(reader.require(region, region_path, "centre", "[x, y, z]"),
                         join(region_path, "centre")));
        spec.region_radii.push_back(
            reader.bounded(reader.require(region, region_path, "radius", "a radius > 0"),
                           join(region_path, "radius"), 0.0, true));
      }
    }
    model.spec = spec;
  } else {  // snake
    model_keys({"nodes", "closed"});
    SceneSnake spec;
    const std::string nodes_path = join(path, "nodes");
    const Json& nodes = reader.array(reader.require(value, path, "nodes", "an array of [x, y, z]"),
                                     nodes_path, "[x, y, z] nodes");
    for (size_t i = 0; i < nodes.size(); ++i) {
      spec.nodes.push_back(reader.point(nodes[i], json_index_path(nodes_path, i)));
    }
    reader.boolean_key(value, path, "closed", spec.closed);
    const size_t minimum = spec.closed ? 4 : 3;
    if (spec.nodes.size() < minimum) {
      reader.fail(nodes_path, "expected at least " + std::to_string(minimum) + " nodes for " +
                                  (spec.closed ? "a closed" : "an open") + " snake, got " +
                                  std::to_string(spec.nodes.size()));
    }
    material_keys({"mass_density", "damping_density", "tension", "rigidity"});
    positive("mass_density", spec.mass_density);
    non_negative("damping_density", spec.damping_density);
    non_negative("tension", spec.tension);
    non_negative("rigidity", spec.rigidity);
    model.spec = spec;
  }

  if (const Json* boundary = reader.find(value, "boundary")) {
    const std::string boundary_path = join(path, "boundary");
    reader.object(*boundary, boundary_path,
                  {"clamp_border", "fixed_points", "local_sculpting_margin"});
    reader.boolean_key(*boundary, boundary_path, "clamp_border", model.boundary.clamp_border);
    if (model.boundary.clamp_border && type != "dnurbs_surface" && type != "terzopoulos_surface") {
      reader.fail(join(boundary_path, "clamp_border"),
                  "expected false: only dnurbs_surface and terzopoulos_surface models have a "
                  "border to clamp (this is a " +
                      type + ")");
    }
    if (const Json* fixed = reader.find(*boundary, "fixed_points")) {
      model.boundary.fixed_points = reader.indices(*fixed, join(boundary_path, "fixed_points"));
      if (type == "superquadric" && !model.boundary.fixed_points.empty()) {
        reader.fail(join(boundary_path, "fixed_points"),
                    "expected no fixed points: a superquadric has no control points or nodes");
      }
    }
    if (reader.find(*boundary, "local_sculpting_margin")) {
      if (type != "dnurbs_surface" && type != "dnurbs_curve") {
        reader.fail(join(boundary_path, "local_sculpting_margin"),
                    "expected no local sculpting: only D-NURBS models have control points to "
                    "freeze (this is a " +
                        type + ")");
      }
      reader.integer_key(*boundary, boundary_path, "local_sculpting_margin",
                         model.boundary.local_sculpting_margin, 0, 1000000);
    }
  }
  if (const Json* scale = reader.find(value, "resolution_scale")) {
    model.resolution_scale =
        reader.vector<2>(*scale, join(path, "resolution_scale"), "[scale_u, scale_v]");
    if (!(model.resolution_scale.array() > 0.0).all()) {
      reader.fail(join(path, "resolution_scale"), "expected [scale_u, scale_v] > 0");
    }
  }
  return model;
}

void read_window(const Reader& reader, const Json& value, const std::string& path, double& start,
                 double& end) {
  reader.number_key(value, path, "start", start);
  if (const Json* e = reader.find(value, "end")) {
    end = reader.number(*e, join(path, "end"));
    if (!(end > start)) {
      reader.fail(join(path, "end"), "expected an end time > start (" + format_json_number(start) +
                                         "), got " + format_json_number(end));
    }
  }
}

SceneForce read_force(const Reader& reader, const ModelNames& names, const Json& value,
                      const std::string& path) {
  if (!value.is_object()) {
    reader.fail(path, "expected a force object, got " + describe_json_value(value));
  }
  SceneForce force;
  const std::string type =
      reader.choice(reader.require(value, path, "type", "a force type"), join(path, "type"),
                    {"point", "spring", "control_point", "gravity", "pressure"});
  auto at = [&]() {
    return reader.parameter(reader.require(value, path, "at", "a material parameter [u, v]"),
                            join(path, "at"));
  };
  if (type == "point") {
    reader.object(value, path, {"type", "model", "at", "force", "start", "end"});
    ScenePointForce spec;
    spec.model = names.require(reader, value, path, "model");
    spec.at = at();
    spec.force = reader.vector_schedule(
        reader.require(value, path, "force", "[fx, fy, fz] or keyframes"), join(path, "force"));
    force.spec = spec;
  } else if (type == "spring") {
    reader.object(value, path, {"type", "model", "at", "stiffness", "target", "start", "end"});
    SceneSpringForce spec;
    spec.model = names.require(reader, value, path, "model");
    spec.at = at();
    spec.stiffness = reader.bounded(reader.require(value, path, "stiffness", "a stiffness >= 0"),
                                    join(path, "stiffness"), 0.0, false);
    spec.target = reader.vector_schedule(
        reader.require(value, path, "target", "[x, y, z] or keyframes"), join(path, "target"));
    force.spec = spec;
  } else if (type == "control_point") {
    reader.object(value, path, {"type", "model", "control_points", "force", "start", "end"});
    SceneControlPointForce spec;
    spec.model = names.require(reader, value, path, "model");
    spec.control_points = reader.indices(
        reader.require(value, path, "control_points", "an array of control point indices"),
        join(path, "control_points"));
    spec.force = reader.vector_schedule(
        reader.require(value, path, "force", "[fx, fy, fz] or keyframes"), join(path, "force"));
    force.spec = spec;
  } else if (type == "gravity") {
    reader.object(value, path, {"type", "model", "acceleration", "start", "end"});
    SceneGravity spec;
    if (const Json* model = reader.find(value, "model")) {
      spec.model = names.resolve(reader, *model, join(path, "model"));
    }
    if (const Json* g = reader.find(value, "acceleration")) {
      spec.acceleration = reader.point(*g, join(path, "acceleration"));
    }
    force.spec = spec;
  } else {
    reader.object(value, path, {"type", "model", "pressure", "start", "end"});
    ScenePressure spec;
    spec.model = names.require(reader, value, path, "model");
    spec.pressure = reader.scalar_schedule(
        reader.require(value, path, "pressure", "a number or keyframes"), join(path, "pressure"));
    force.spec = spec;
  }
  read_window(reader, value, path, force.start, force.end);
  return force;
}

SceneConstraint read_constraint(const Reader& reader, const ModelNames& names, const Json& value,
                                const std::string& path) {
  if (!value.is_object()) {
    reader.fail(path, "expected a constraint object, got " + describe_json_value(value));
  }
  SceneConstraint constraint;
  const std::string type =
      reader.choice(reader.require(value, path, "type", "a constraint type"), join(path, "type"),
                    {"point_target", "point_to_point", "hinge", "control_point", "surface_normal",
                     "curve_on_surface"});
  auto parameter = [&](const char* key) {
    return reader.parameter(reader.require(value, path, key, "a material parameter [u, v]"),
                            join(path, key));
  };
  auto axis = [&](const char* key, Eigen::Vector2d& a0, Eigen::Vector2d& a1) {
    const std::string axis_path = join(path, key);
    const Json& pair = reader.require(value, path, key, "two material parameters [[u, v], [u, v]]");
    if (!pair.is_array() || pair.size() != 2) {
      reader.fail(axis_path, "expected two material parameters [[u, v], [u, v]], got " +
                                 describe_json_value(pair));
    }
    a0 = reader.parameter(pair[0], json_index_path(axis_path, 0));
    a1 = reader.parameter(pair[1], json_index_path(axis_path, 1));
  };
  if (type == "point_target") {
    reader.object(value, path, {"type", "model", "at", "target", "alpha", "beta"});
    ScenePointTargetConstraint spec;
    spec.model = names.require(reader, value, path, "model");
    spec.at = parameter("at");
    spec.target = reader.vector_schedule(
        reader.require(value, path, "target", "[x, y, z] or keyframes"), join(path, "target"));
    constraint.spec = spec;
  } else if (type == "point_to_point") {
    reader.object(value, path, {"type", "model_a", "at_a", "model_b", "at_b", "alpha", "beta"});
    ScenePointToPointConstraint spec;
    spec.model_a = names.require(reader, value, path, "model_a");
    spec.at_a = parameter("at_a");
    spec.model_b = names.require(reader, value, path, "model_b");
    spec.at_b = parameter("at_b");
    constraint.spec = spec;
  } else if (type == "hinge") {
    reader.object(value, path, {"type", "model_a", "axis_a", "model_b", "axis_b", "alpha", "beta"});
    SceneHingeConstraint spec;
    spec.model_a = names.require(reader, value, path, "model_a");
    axis("axis_a", spec.axis_a0, spec.axis_a1);
    spec.model_b = names.require(reader, value, path, "model_b");
    axis("axis_b", spec.axis_b0, spec.axis_b1);
    constraint.spec = spec;
  } else if (type == "control_point") {
    reader.object(value, path, {"type", "model", "control_point", "target", "alpha", "beta"});
    SceneControlPointConstraint spec;
    spec.model = names.require(reader, value, path, "model");
    spec.control_point =
        reader.integer(reader.require(value, path, "control_point", "a control point index"),
                       join(path, "control_point"), 0, 1 << 30);
    spec.target =
        reader.point(reader.require(value, path, "target", "[x, y, z]"), join(path, "target"));
    constraint.spec = spec;
  } else if (type == "surface_normal") {
    reader.object(value, path, {"type", "model", "at", "direction", "alpha", "beta"});
    SceneSurfaceNormalConstraint spec;
    spec.model = names.require(reader, value, path, "model");
    spec.at = parameter("at");
    spec.direction = reader.point(reader.require(value, path, "direction", "[x, y, z]"),
                                  join(path, "direction"));
    if (!(spec.direction.norm() > 0.0)) {
      reader.fail(join(path, "direction"), "expected a non-zero direction");
    }
    constraint.spec = spec;
  } else {
    reader.object(value, path,
                  {"type", "curve_model", "surface_model", "samples", "alpha", "beta"});
    SceneCurveOnSurfaceConstraint spec;
    spec.curve_model = names.require(reader, value, path, "curve_model");
    spec.surface_model = names.require(reader, value, path, "surface_model");
    reader.integer_key(value, path, "samples", spec.samples, 1, 10000);
    constraint.spec = spec;
  }
  reader.number_key(value, path, "alpha", constraint.alpha, 0.0, false);
  reader.number_key(value, path, "beta", constraint.beta, 0.0, false);
  return constraint;
}

Scene read_scene(const Reader& reader, const Json& root) {
  reader.object(root, "",
                {"description", "models", "forces", "constraints", "integrator", "run", "probes",
                 "output", "design"});
  Scene scene;
  scene.source = reader.source();
  scene.directory = reader.directory();
  if (const Json* description = reader.find(root, "description")) {
    scene.description = reader.string(*description, "description");
  }
  const Json& models =
      reader.array(reader.require(root, "", "models", "an array of models"), "models", "models");
  if (models.empty()) {
    reader.fail("models", "expected at least one model, got an empty array");
  }
  for (size_t i = 0; i < models.size(); ++i) {
    scene.models.push_back(read_model(reader, models[i], json_index_path("models", i), i));
    for (size_t j = 0; j < i; ++j) {
      if (scene.models[j].name == scene.models[i].name) {
        reader.fail(json_index_path("models", i) + ".name",
                    "expected a unique model name, got \"" + scene.models[i].name +
                        "\" again (models[" + std::to_string(j) + "])");
      }
    }
  }
  const ModelNames names(scene.models);
  if (const Json* forces = reader.find(root, "forces")) {
    reader.array(*forces, "forces", "forces");
    for (size_t i = 0; i < forces->size(); ++i) {
      scene.forces.push_back(read_force(reader, names, (*forces)[i], json_index_path("forces", i)));
    }
  }
  if (const Json* constraints = reader.find(root, "constraints")) {
    reader.array(*constraints, "constraints", "constraints");
    for (size_t i = 0; i < constraints->size(); ++i) {
      scene.constraints.push_back(
          read_constraint(reader, names, (*constraints)[i], json_index_path("constraints", i)));
    }
  }
  if (const Json* integrator = reader.find(root, "integrator")) {
    const std::string path = "integrator";
    reader.object(*integrator, path,
                  {"scheme", "dt", "newton_iterations", "newton_tolerance", "newmark_beta",
                   "newmark_gamma", "max_energy"});
    SceneIntegrator& s = scene.integrator;
    if (const Json* scheme = reader.find(*integrator, "scheme")) {
      s.scheme =
          reader.choice(*scheme, "integrator.scheme", {"central", "implicit-euler", "newmark"});
    }
    reader.number_key(*integrator, path, "dt", s.dt, 0.0, true);
    reader.integer_key(*integrator, path, "newton_iterations", s.newton_iterations, 0, 1000);
    reader.number_key(*integrator, path, "newton_tolerance", s.newton_tolerance, 0.0, false);
    reader.number_key(*integrator, path, "newmark_beta", s.newmark_beta, 0.0, true);
    reader.number_key(*integrator, path, "newmark_gamma", s.newmark_gamma, 0.0, true);
    reader.number_key(*integrator, path, "max_energy", s.max_energy, 0.0, true);
  }
  const Json& run = reader.require(root, "", "run", "{\"steps\": N} or {\"duration\": T}");
  reader.object(run, "run", {"steps", "duration"});
  const Json* steps = reader.find(run, "steps");
  const Json* duration = reader.find(run, "duration");
  if ((steps == nullptr) == (duration == nullptr)) {
    reader.fail("run", "expected exactly one of \"steps\" and \"duration\"");
  }
  if (steps != nullptr) {
    scene.steps = reader.integer(*steps, "run.steps", 1, 100000000);
  } else {
    scene.duration = reader.bounded(*duration, "run.duration", 0.0, true);
    if (scene.duration / scene.integrator.dt > 1e8) {
      reader.fail("run.duration", "expected at most 1e8 steps of integrator.dt, got " +
                                      format_json_number(scene.duration / scene.integrator.dt));
    }
  }
  if (const Json* probes = reader.find(root, "probes")) {
    reader.array(*probes, "probes", "probes");
    for (size_t i = 0; i < probes->size(); ++i) {
      const std::string path = json_index_path("probes", i);
      const Json& probe = (*probes)[i];
      reader.object(probe, path, {"name", "model", "at"});
      SceneProbe p;
      p.name = "probe" + std::to_string(i);
      if (const Json* name = reader.find(probe, "name")) {
        p.name = reader.string(*name, join(path, "name"));
        if (p.name.empty() || p.name.find_first_of(",\"\n\r") != std::string::npos) {
          reader.fail(join(path, "name"),
                      "expected a non-empty name without commas, quotes or line breaks (it "
                      "names CSV columns)");
        }
      }
      p.model = names.require(reader, probe, path, "model");
      p.at = reader.parameter(reader.require(probe, path, "at", "a material parameter [u, v]"),
                              join(path, "at"));
      scene.probes.push_back(p);
    }
  }
  if (const Json* output = reader.find(root, "output")) {
    const std::string path = "output";
    reader.object(*output, path,
                  {"mesh_every", "format", "resolution", "final_mesh", "preview", "log_every",
                   "checkpoint_every", "name", "shape_files"});
    SceneOutput& o = scene.output;
    reader.integer_key(*output, path, "mesh_every", o.mesh_every, 0, 100000000);
    if (const Json* format = reader.find(*output, "format")) {
      o.format = reader.choice(*format, "output.format", {"obj", "stl", "ply", "gltf", "glb"});
    }
    reader.integer_key(*output, path, "resolution", o.resolution, 3, 1024);
    reader.boolean_key(*output, path, "final_mesh", o.final_mesh);
    reader.boolean_key(*output, path, "preview", o.preview);
    reader.boolean_key(*output, path, "shape_files", o.shape_files);
    reader.integer_key(*output, path, "log_every", o.log_every, 1, 100000000);
    reader.integer_key(*output, path, "checkpoint_every", o.checkpoint_every, 0, 100000000);
    if (const Json* name = reader.find(*output, "name")) {
      o.name = reader.string(*name, "output.name");
      if (o.name.empty() || o.name.find_first_of("/\\") != std::string::npos ||
          o.name.starts_with(".")) {
        reader.fail("output.name", "expected a file stem without slashes or a leading dot, got " +
                                       describe_json_value(*name));
      }
    }
    if (o.preview && o.format != "obj") {
      reader.fail("output.preview",
                  "expected false unless output.format is \"obj\" (the "
                  "preview renders the final OBJ mesh)");
    }
    if (o.preview && !o.final_mesh) {
      reader.fail("output.preview", "expected false when output.final_mesh is false");
    }
  }
  if (const Json* design = reader.find(root, "design")) {
    const std::string path = "design";
    reader.object(*design, path,
                  {"algorithm", "variable_tolerance", "energy_tolerance", "constraint_tolerance",
                   "max_evaluations", "max_seconds"});
    SceneDesign& d = scene.design.emplace();
    if (const Json* algorithm = reader.find(*design, "algorithm")) {
      d.algorithm = reader.choice(*algorithm, "design.algorithm", {"slsqp", "auglag_lbfgs"});
    }
    reader.number_key(*design, path, "variable_tolerance", d.variable_tolerance, 0.0, false);
    reader.number_key(*design, path, "energy_tolerance", d.energy_tolerance, 0.0, false);
    reader.number_key(*design, path, "constraint_tolerance", d.constraint_tolerance, 0.0, false);
    reader.integer_key(*design, path, "max_evaluations", d.max_evaluations, 1, 100000000);
    reader.number_key(*design, path, "max_seconds", d.max_seconds, 0.0, false);
  }
  return scene;
}

// Writer ----------------------------------------------------------------------------------------

template <int N>
OrderedJson array_of(const Eigen::Matrix<double, N, 1>& v) {
  OrderedJson a = OrderedJson::array();
  for (int i = 0; i < N; ++i) {
    a.push_back(v(i));
  }
  return a;
}

OrderedJson schedule_json(const VectorSchedule& s) {
  if (s.times.empty()) {
    return array_of<3>(s.values.front());
  }
  OrderedJson values = OrderedJson::array();
  for (const auto& v : s.values) {
    values.push_back(array_of<3>(v));
  }
  return OrderedJson{{"times", s.times}, {"values", values}};
}

OrderedJson schedule_json(const ScalarSchedule& s) {
  if (s.times.empty()) {
    return s.values.front();
  }
  return OrderedJson{{"times", s.times}, {"values", s.values}};
}

OrderedJson parameter_json(const Eigen::Vector2d& u) {
  return OrderedJson{u.x(), u.y()};
}

OrderedJson grid_json(const SceneGrid& g) {
  return OrderedJson{{"nodes", {g.nodes_u, g.nodes_v}},
                     {"spacing", g.spacing},
                     {"origin", array_of<3>(g.origin)},
                     {"axis_u", array_of<3>(g.axis_u)},
                     {"axis_v", array_of<3>(g.axis_v)}};
}

OrderedJson tensor_json(const Eigen::Matrix2d& m) {
  return OrderedJson{{m(0, 0), m(0, 1)}, {m(1, 0), m(1, 1)}};
}

void write_dnurbs_settings(const SceneDNurbsSettings& s, OrderedJson& model) {
  model["weights"] = s.free_weights ? "free" : "fixed";
  model["quadrature_points"] = s.quadrature_points;
  model["minimum_weight"] = s.minimum_weight;
}

OrderedJson fit_json(const SceneFit& fit, bool dnurbs) {
  OrderedJson j;
  j["points"] = fit.points;
  if (dnurbs) {
    j["degree"] = fit.degree;
    j["spans"] = fit.spans;
    j["smoothness"] = fit.smoothness;
    j["iterations"] = fit.iterations;
  } else {
    j["max_evaluations"] = fit.max_evaluations;
  }
  return j;
}

// "fit", "shape_file" or the inline "shape", whichever the model came from
template <typename ShapeType>
void write_shape(const ShapeType& shape, const std::string& file,
                 const std::optional<SceneFit>& fit, OrderedJson& model) {
  if (fit) {
    model["fit"] = fit_json(*fit, true);
  } else if (!file.empty()) {
    model["shape_file"] = file;
  } else {
    model["shape"] = OrderedJson::parse(shape_to_json(Shape(shape)));
  }
}

OrderedJson model_json(const SceneModel& model) {
  OrderedJson j;
  j["name"] = model.name;
  j["type"] = scene_model_type(model);
  if (const auto* curve = std::get_if<SceneDNurbsCurve>(&model.spec)) {
    write_shape(curve->curve, curve->shape_file, curve->fit, j);
    j["material"] = {{"mass_density", curve->mass_density},
                     {"damping_density", curve->damping_density},
                     {"tension", curve->tension},
                     {"rigidity", curve->rigidity}};
    write_dnurbs_settings(curve->settings, j);
  } else if (const auto* surface = std::get_if<SceneDNurbsSurface>(&model.spec)) {
    write_shape(surface->surface, surface->shape_file, surface->fit, j);
    j["material"] = {{"mass_density", surface->mass_density},
                     {"damping_density", surface->damping_density},
                     {"a10", surface->a10},
                     {"a01", surface->a01},
                     {"b20", surface->b20},
                     {"b11", surface->b11},
                     {"b02", surface->b02}};
    write_dnurbs_settings(surface->settings, j);
  } else if (const auto* sq = std::get_if<SceneSuperquadric>(&model.spec)) {
    if (sq->fit) {
      j["fit"] = fit_json(*sq->fit, false);
    } else {
      OrderedJson shape;
      for (int k = 0; k < 14; ++k) {
        shape[kShapeKeys[k]] = sq->shape(k);
      }
      j["shape"] = shape;
      j["centre"] = array_of<3>(sq->centre);
      j["orientation"] = array_of<4>(sq->orientation);
    }
    j["parts"] = sq->parts;
    j["mesh_cells"] = {sq->mesh_cells_u, sq->mesh_cells_v};
    j["quadrature_points"] = sq->quadrature_points;
    j["regularization"] = sq->regularization;
    j["material"] = {{"mass_density", sq->mass_density},
                     {"damping_alpha", sq->damping_alpha},
                     {"damping_beta", sq->damping_beta},
                     {"shape_stiffness", sq->shape_stiffness},
                     {"local_stiffness", array_of<3>(sq->local_stiffness)}};
  } else if (const auto* terzopoulos = std::get_if<SceneTerzopoulosSurface>(&model.spec)) {
    j["grid"] = grid_json(terzopoulos->grid);
    j["normal"] = terzopoulos->normal;
    j["delta"] = terzopoulos->delta;
    j["material"] = {{"mass_density", terzopoulos->mass_density},
                     {"damping_density", terzopoulos->damping_density},
                     {"eta", tensor_json(terzopoulos->eta)},
                     {"xi", tensor_json(terzopoulos->xi)}};
  } else if (const auto* pde = std::get_if<ScenePdeSurface>(&model.spec)) {
    j["grid"] = grid_json(pde->grid);
    j["material"] = {{"b", pde->b},
                     {"c", pde->c},
                     {"d", pde->d},
                     {"density", pde->density},
                     {"damping", pde->damping},
                     {"su0", pde->su0},
                     {"su1", pde->su1},
                     {"sv0", pde->sv0},
                     {"sv1", pde->sv1}};
    OrderedJson regions = OrderedJson::array();
    for (size_t r = 0; r < pde->region_centres.size(); ++r) {
      regions.push_back(
          {{"centre", array_of<3>(pde->region_centres[r])}, {"radius", pde->region_radii[r]}});
    }
    j["regions"] = regions;
  } else {
    const auto& snake = std::get<SceneSnake>(model.spec);
    OrderedJson nodes = OrderedJson::array();
    for (const auto& node : snake.nodes) {
      nodes.push_back(array_of<3>(node));
    }
    j["nodes"] = nodes;
    j["closed"] = snake.closed;
    j["material"] = {{"mass_density", snake.mass_density},
                     {"damping_density", snake.damping_density},
                     {"tension", snake.tension},
                     {"rigidity", snake.rigidity}};
  }
  if (model.boundary.clamp_border || !model.boundary.fixed_points.empty() ||
      model.boundary.local_sculpting_margin >= 0) {
    j["boundary"] = {{"clamp_border", model.boundary.clamp_border},
                     {"fixed_points", model.boundary.fixed_points}};
    if (model.boundary.local_sculpting_margin >= 0) {
      j["boundary"]["local_sculpting_margin"] = model.boundary.local_sculpting_margin;
    }
  }
  if (model.resolution_scale != Eigen::Vector2d::Ones()) {
    j["resolution_scale"] = parameter_json(model.resolution_scale);
  }
  return j;
}

OrderedJson force_json(const SceneForce& force) {
  OrderedJson j;
  if (const auto* point = std::get_if<ScenePointForce>(&force.spec)) {
    j = {{"type", "point"},
         {"model", point->model},
         {"at", parameter_json(point->at)},
         {"force", schedule_json(point->force)}};
  } else if (const auto* spring = std::get_if<SceneSpringForce>(&force.spec)) {
    j = {{"type", "spring"},
         {"model", spring->model},
         {"at", parameter_json(spring->at)},
         {"stiffness", spring->stiffness},
         {"target", schedule_json(spring->target)}};
  } else if (const auto* cp = std::get_if<SceneControlPointForce>(&force.spec)) {
    j = {{"type", "control_point"},
         {"model", cp->model},
         {"control_points", cp->control_points},
         {"force", schedule_json(cp->force)}};
  } else if (const auto* gravity = std::get_if<SceneGravity>(&force.spec)) {
    j = {{"type", "gravity"}};
    if (gravity->model >= 0) {
      j["model"] = gravity->model;
    }
    j["acceleration"] = array_of<3>(gravity->acceleration);
  } else {
    const auto& pressure = std::get<ScenePressure>(force.spec);
    j = {{"type", "pressure"},
         {"model", pressure.model},
         {"pressure", schedule_json(pressure.pressure)}};
  }
  j["start"] = force.start;
  if (std::isfinite(force.end)) {
    j["end"] = force.end;
  }
  return j;
}

OrderedJson constraint_json(const SceneConstraint& constraint) {
  OrderedJson j;
  if (const auto* target = std::get_if<ScenePointTargetConstraint>(&constraint.spec)) {
    j = {{"type", "point_target"},
         {"model", target->model},
         {"at", parameter_json(target->at)},
         {"target", schedule_json(target->target)}};
  } else if (const auto* p2p = std::get_if<ScenePointToPointConstraint>(&constraint.spec)) {
    j = {{"type", "point_to_point"},
         {"model_a", p2p->model_a},
         {"at_a", parameter_json(p2p->at_a)},
         {"model_b", p2p->model_b},
         {"at_b", parameter_json(p2p->at_b)}};
  } else if (const auto* hinge = std::get_if<SceneHingeConstraint>(&constraint.spec)) {
    j = {{"type", "hinge"},
         {"model_a", hinge->model_a},
         {"axis_a", {parameter_json(hinge->axis_a0), parameter_json(hinge->axis_a1)}},
         {"model_b", hinge->model_b},
         {"axis_b", {parameter_json(hinge->axis_b0), parameter_json(hinge->axis_b1)}}};
  } else if (const auto* cp = std::get_if<SceneControlPointConstraint>(&constraint.spec)) {
    j = {{"type", "control_point"},
         {"model", cp->model},
         {"control_point", cp->control_point},
         {"target", array_of<3>(cp->target)}};
  } else if (const auto* normal = std::get_if<SceneSurfaceNormalConstraint>(&constraint.spec)) {
    j = {{"type", "surface_normal"},
         {"model", normal->model},
         {"at", parameter_json(normal->at)},
         {"direction", array_of<3>(normal->direction)}};
  } else {
    const auto& cos = std::get<SceneCurveOnSurfaceConstraint>(constraint.spec);
    j = {{"type", "curve_on_surface"},
         {"curve_model", cos.curve_model},
         {"surface_model", cos.surface_model},
         {"samples", cos.samples}};
  }
  j["alpha"] = constraint.alpha;
  if (constraint.beta >= 0.0) {
    j["beta"] = constraint.beta;
  }
  return j;
}

OrderedJson scene_json(const Scene& scene, bool with_output) {
  OrderedJson root;
  if (with_output && !scene.description.empty()) {
    root["description"] = scene.description;
  }
  root["models"] = OrderedJson::array();
  for (const auto& model : scene.models) {
    root["models"].push_back(model_json(model));
  }
  root["forces"] = OrderedJson::array();
  for (const auto& force : scene.forces) {
    root["forces"].push_back(force_json(force));
  }
  root["constraints"] = OrderedJson::array();
  for (const auto& constraint : scene.constraints) {
    root["constraints"].push_back(constraint_json(constraint));
  }
  const SceneIntegrator& s = scene.integrator;
  root["integrator"] = {{"scheme", s.scheme},
                        {"dt", s.dt},
                        {"newton_iterations", s.newton_iterations},
                        {"newton_tolerance", s.newton_tolerance},
                        {"newmark_beta", s.newmark_beta},
                        {"newmark_gamma", s.newmark_gamma},
                        {"max_energy", s.max_energy}};
  if (scene.steps > 0) {
    root["run"] = {{"steps", scene.steps}};
  } else {
    root["run"] = {{"duration", scene.duration}};
  }
  root["probes"] = OrderedJson::array();
  for (const auto& probe : scene.probes) {
    root["probes"].push_back(
        {{"name", probe.name}, {"model", probe.model}, {"at", parameter_json(probe.at)}});
  }
  if (with_output) {
    const SceneOutput& o = scene.output;
    root["output"] = {{"mesh_every", o.mesh_every},
                      {"format", o.format},
                      {"resolution", o.resolution},
                      {"final_mesh", o.final_mesh},
                      {"preview", o.preview},
                      {"log_every", o.log_every},
                      {"checkpoint_every", o.checkpoint_every},
                      {"name", o.name},
                      {"shape_files", o.shape_files}};
  }
  if (scene.design) {
    const SceneDesign& d = *scene.design;
    root["design"] = {{"algorithm", d.algorithm},
                      {"variable_tolerance", d.variable_tolerance},
                      {"energy_tolerance", d.energy_tolerance},
                      {"constraint_tolerance", d.constraint_tolerance},
                      {"max_evaluations", d.max_evaluations},
                      {"max_seconds", d.max_seconds}};
  }
  return root;
}

}  // namespace

Eigen::Vector3d VectorSchedule::at(double time) const {
  if (times.empty()) {
    return values.front();
  }
  return TargetTrajectory::keyframes(times, values).position(time);
}

double ScalarSchedule::at(double time) const {
  if (times.empty()) {
    return values.front();
  }
  std::vector<Eigen::Vector3d> points;
  points.reserve(values.size());
  for (double v : values) {
    points.emplace_back(v, 0.0, 0.0);
  }
  return TargetTrajectory::keyframes(times, points).position(time).x();
}

std::string scene_model_type(const SceneModel& model) {
  return kModelTypes[model.spec.index()];
}

int Scene::step_count() const {
  if (steps > 0) {
    return steps;
  }
  // duration / dt rounded up, with a margin for the rounding of an exact multiple
  return static_cast<int>(std::ceil(duration / integrator.dt - 1e-9));
}

bool operator==(const SceneDNurbsCurve& a, const SceneDNurbsCurve& b) {
  return shape_to_json(Shape(a.curve)) == shape_to_json(Shape(b.curve)) &&
         a.shape_file == b.shape_file && a.mass_density == b.mass_density &&
         a.damping_density == b.damping_density && a.tension == b.tension &&
         a.rigidity == b.rigidity && a.settings == b.settings && a.fit == b.fit;
}

bool operator==(const SceneDNurbsSurface& a, const SceneDNurbsSurface& b) {
  return shape_to_json(Shape(a.surface)) == shape_to_json(Shape(b.surface)) &&
         a.shape_file == b.shape_file && a.mass_density == b.mass_density &&
         a.damping_density == b.damping_density && a.a10 == b.a10 && a.a01 == b.a01 &&
         a.b20 == b.b20 && a.b11 == b.b11 && a.b02 == b.b02 && a.settings == b.settings &&
         a.fit == b.fit;
}

bool operator==(const SceneModel& a, const SceneModel& b) {
  return a.name == b.name && a.spec == b.spec && a.boundary == b.boundary &&
         a.resolution_scale == b.resolution_scale;
}

bool operator==(const Scene& a, const Scene& b) {
  return a.description == b.description && a.models == b.models && a.forces == b.forces &&
         a.constraints == b.constraints && a.integrator == b.integrator && a.steps == b.steps &&
         a.duration == b.duration && a.probes == b.probes && a.output == b.output &&
         a.design == b.design;
}

Scene parse_scene_json(const std::string& text, const std::string& source,
                       const std::filesystem::path& directory) {
  const Reader reader(source, directory);
  Json root;
  try {
    root = Json::parse(text);
  } catch (const Json::parse_error& error) {
    // nlohmann's message carries the line and column
    std::string message = error.what();
    const auto position = message.find("parse error");
    reader.fail("(document)",
                "expected valid JSON: " +
                    (position == std::string::npos ? message : message.substr(position)));
  }
  return read_scene(reader, root);
}

Scene read_scene_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw make_error(path.string(), ": cannot read the scene file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parse_scene_json(text.str(), path.string(), path.parent_path());
}

std::string scene_to_json(const Scene& scene) {
  return scene_json(scene, true).dump(2) + "\n";
}

std::string scene_state_hash(const Scene& scene) {
  const std::string text = scene_json(scene, false).dump();
  std::uint64_t hash = 14695981039346656037ULL;  // FNV-1a 64 offset basis
  for (const unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ULL;  // FNV prime
  }
  char buffer[17];
  std::snprintf(buffer, sizeof(buffer), "%016llx", static_cast<unsigned long long>(hash));
  return buffer;
}

}  // namespace dnurbs
