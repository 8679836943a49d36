#include "dnurbs/io/shape_recipe.h"

#include <algorithm>
#include <functional>
#include <numbers>
#include <optional>
#include <string_view>
#include <variant>

#include "dnurbs/core/error.h"
#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/shape_file.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "dnurbs/nurbs/shape_generators.h"

namespace dnurbs {
namespace {

// Generous for sculpting (a 316 x 316 sheet), small enough that a scene cannot ask for gigabytes.
constexpr int kMaxControlPoints = 100000;
constexpr int kMaxPerDirection = 1000;
constexpr int kMaxSplit = 64;
// A loft interpolates its sections with a dense system of this order at the most.
constexpr size_t kMaxSections = 1000;
// Recipes nest through their curves; a hostile document must not recurse without bound.
constexpr int kMaxNesting = 8;

// Fails at `path` if a recipe would make more than kMaxControlPoints control points.
void check_control_point_count(const SceneReader& reader, const std::string& path,
                               long long count) {
  if (count > kMaxControlPoints) {
    reader.fail(path, "the recipe makes " + std::to_string(count) +
                          " control points, more than the limit of " +
                          std::to_string(kMaxControlPoints));
  }
}

Shape make_nested_shape(const SceneReader& reader, const JsonValue& recipe, const std::string& path,
                        int depth);

// Reads the keys of one recipe; every builder below takes one.
class RecipeKeys {
 public:
  RecipeKeys(const SceneReader& reader, const JsonValue& recipe, std::string path, int depth)
      : reader_(reader), recipe_(recipe), path_(std::move(path)), depth_(depth) {}

  const SceneReader& reader() const { return reader_; }
  std::string path(const char* key) const { return join_json_path(path_, key); }
  const JsonValue* find(const char* key) const { return reader_.find(recipe_, key); }

  double positive(const char* key, double fallback) const {
    const JsonValue* value = find(key);
    return value == nullptr ? fallback : reader_.bounded(*value, path(key), 0.0, true);
  }
  int integer(const char* key, int fallback, int minimum, int maximum) const {
    const JsonValue* value = find(key);
    return value == nullptr ? fallback : reader_.integer(*value, path(key), minimum, maximum);
  }
  bool flag(const char* key) const {
    bool value = false;
    reader_.boolean_key(recipe_, path_, key, value);
    return value;
  }
  Eigen::Vector3d point(const char* key, const Eigen::Vector3d& fallback) const {
    const JsonValue* value = find(key);
    return value == nullptr ? fallback : reader_.point(*value, path(key));
  }
  // [x, y] of numbers > 0
  Eigen::Vector2d positive_pair(const char* key, const Eigen::Vector2d& fallback) const {
    const JsonValue* value = find(key);
    if (value == nullptr) {
      return fallback;
    }
    Eigen::Vector2d pair = reader_.vector<2>(*value, path(key), "[x, y]");
    for (int i = 0; i < 2; ++i) {
      if (!(pair[i] > 0.0)) {
        reader_.fail(json_index_path(path(key), static_cast<size_t>(i)),
                     "expected a number > 0, got " + format_json_number(pair[i]));
      }
    }
    return pair;
  }
  // [n_u, n_v] of integers in minimum..maximum
  Eigen::Vector2i integer_pair(const char* key, const Eigen::Vector2i& fallback, int minimum,
                               int maximum) const {
    const JsonValue* value = find(key);
    if (value == nullptr) {
      return fallback;
    }
    if (!value->is_array() || value->size() != 2) {
      reader_.fail(path(key), "expected [n_u, n_v], got " + describe_json_value(*value));
    }
    return {reader_.integer((*value)[0], json_index_path(path(key), 0), minimum, maximum),
            reader_.integer((*value)[1], json_index_path(path(key), 1), minimum, maximum)};
  }
  // A curve: an inline nurbs_curve, a shape file name or a nested recipe
  NurbsCurve curve(const JsonValue& value, const std::string& at) const;
  NurbsCurve curve(const char* key) const {
    return curve(reader_.require(recipe_, path_, key,
                                 "a nurbs_curve, a shape file name or a recipe {\"kind\": ...}"),
                 path(key));
  }

 private:
  const SceneReader& reader_;
  const JsonValue& recipe_;
  std::string path_;
  int depth_;
};

struct RecipeKind {
  const char* kind;
  std::vector<const char*> keys;  // besides kind, split and translate
  std::function<Shape(const RecipeKeys&)> build;
};

constexpr double kFullTurnDegrees = 360.0;

const std::vector<RecipeKind>& recipe_table() {
  static const std::vector<RecipeKind> table = {
      {"line",
       {"start", "end", "control_points", "degree", "domain"},
       [](const RecipeKeys& k) -> Shape {
         std::optional<double> domain;
         if (k.find("domain") != nullptr) {
           domain = k.positive("domain", 1);
         }
         return greville_line(k.point("start", Eigen::Vector3d::Zero()),
                              k.point("end", Eigen::Vector3d::UnitX()),
                              k.integer("control_points", 4, 2, kMaxPerDirection),
                              k.integer("degree", 3, 1, kMaxDegree), domain);
       }},
      {"plane",
       {"size", "control_points", "degree", "origin", "domain"},
       [](const RecipeKeys& k) -> Shape {
         std::optional<Eigen::Vector2d> domain;
         if (k.find("domain") != nullptr) {
           domain = k.positive_pair("domain", {1, 1});
         }
         const Eigen::Vector2i counts =
             k.integer_pair("control_points", {4, 4}, 2, kMaxPerDirection);
         // Refused before it is built
         check_control_point_count(k.reader(), k.path("control_points"), counts.x() * counts.y());
         return greville_plane(k.positive_pair("size", {1, 1}), counts,
                               k.integer_pair("degree", {3, 3}, 1, kMaxDegree),
                               k.point("origin", Eigen::Vector3d::Zero()), domain);
       }},
      {"box",
       {"size"},
       [](const RecipeKeys& k) -> Shape { return box(k.point("size", Eigen::Vector3d::Ones())); }},
      {"cylinder",
       {"radius", "height", "profile_control_points"},
       [](const RecipeKeys& k) -> Shape {
         return cylinder(k.positive("radius", 1), k.positive("height", 1),
                         k.integer("profile_control_points", 4, 2, kMaxPerDirection));
       }},
      {"cone",
       {"radius", "height", "profile_control_points"},
       [](const RecipeKeys& k) -> Shape {
         return cone(k.positive("radius", 1), k.positive("height", 1),
                     k.integer("profile_control_points", 4, 2, kMaxPerDirection));
       }},
      {"sphere",
       {"radius"},
       [](const RecipeKeys& k) -> Shape { return sphere(k.positive("radius", 1)); }},
      {"torus",
       {"major_radius", "minor_radius", "periodic"},
       [](const RecipeKeys& k) -> Shape {
         const double major = k.positive("major_radius", 1);
         const double minor = k.positive("minor_radius", 0.25);
         return k.flag("periodic") ? periodic_torus(major, minor) : torus(major, minor);
       }},
      {"revolve",
       {"profile", "angle_degrees"},
       [](const RecipeKeys& k) -> Shape {
         const double degrees = k.positive("angle_degrees", kFullTurnDegrees);
         if (degrees > kFullTurnDegrees) {
           k.reader().fail(k.path("angle_degrees"),
                           "expected at most 360, got " + format_json_number(degrees));
         }
         const double angle = degrees == kFullTurnDegrees
                                  ? 2 * std::numbers::pi
                                  : degrees * std::numbers::pi / kFullTurnDegrees * 2;
         return revolve(k.curve("profile"), angle);
       }},
      {"extrude",
       {"curve", "direction"},
       [](const RecipeKeys& k) -> Shape {
         return extrude(k.curve("curve"), k.point("direction", Eigen::Vector3d::UnitZ()));
       }},
      {"loft",
       {"sections", "degree"},
       [](const RecipeKeys& k) -> Shape {
         const JsonValue* sections = k.find("sections");
         if (sections == nullptr) {
           k.reader().fail(k.path("sections"), "missing key (expected an array of >= 2 curves)");
         }
         const JsonValue& list = k.reader().array(*sections, k.path("sections"), "curves");
         if (list.size() < 2) {
           k.reader().fail(k.path("sections"),
                           "expected an array of >= 2 curves, got " + describe_json_value(list));
         }
         if (list.size() > kMaxSections) {
           k.reader().fail(k.path("sections"), "expected at most " + std::to_string(kMaxSections) +
                                                   " curves, got " + describe_json_value(list));
         }
         std::vector<NurbsCurve> curves;
         for (size_t i = 0; i < list.size(); ++i) {
           curves.push_back(k.curve(list[i], json_index_path(k.path("sections"), i)));
         }
         return loft(curves, k.integer("degree", 3, 1, kMaxDegree), nullptr, kMaxControlPoints);
       }},
  };
  return table;
}

NurbsCurve RecipeKeys::curve(const JsonValue& value, const std::string& at) const {
  std::optional<Shape> shape;
  if (value.is_string()) {
    const std::string file = reader_.string(value, at);
    try {
      shape = read_shape_file(reader_.resolve(file));
    } catch (const Error& error) {
      reader_.fail(at, error.what());
    }
  } else if (value.is_object() && value.contains("kind")) {
    shape = make_nested_shape(reader_, value, at, depth_ + 1);
  } else if (value.is_object()) {
    try {
      shape = parse_shape_json(value.dump(), "curve");
    } catch (const Error& error) {
      reader_.fail(at, error.what());
    }
  } else {
    reader_.fail(at, "expected a nurbs_curve, a shape file name or a recipe {\"kind\": ...}, got " +
                         describe_json_value(value));
  }
  if (!std::holds_alternative<NurbsCurve>(*shape)) {
    reader_.fail(at, "expected a curve, got a surface");
  }
  return std::get<NurbsCurve>(*shape);
}

const std::vector<const char*>& recipe_kinds() {
  static const std::vector<const char*> kinds = [] {
    std::vector<const char*> names;
    for (const RecipeKind& kind : recipe_table()) {
      names.push_back(kind.kind);
    }
    return names;
  }();
  return kinds;
}

Shape make_nested_shape(const SceneReader& reader, const JsonValue& recipe, const std::string& path,
                        int depth) {
  if (depth > kMaxNesting) {
    reader.fail(path, "recipes nested more than " + std::to_string(kMaxNesting) + " deep");
  }
  if (!recipe.is_object()) {
    reader.fail(path,
                "expected a shape recipe {\"kind\": ...}, got " + describe_json_value(recipe));
  }
  const std::string kind = reader.choice(reader.require(recipe, path, "kind", "a generator name"),
                                         join_json_path(path, "kind"), recipe_kinds());
  const RecipeKind& entry = *std::find_if(recipe_table().begin(), recipe_table().end(),
                                          [&](const RecipeKind& k) { return kind == k.kind; });
  std::vector<const char*> allowed = {"kind", "split", "translate"};
  allowed.insert(allowed.end(), entry.keys.begin(), entry.keys.end());
  reader.object(recipe, path, allowed, "a \"" + kind + "\" recipe");
  const RecipeKeys keys(reader, recipe, path, depth);
  Shape shape = [&] {
    try {
      return entry.build(keys);
    } catch (const Error& error) {
      const std::string message = error.what();
      if (message.starts_with(reader.source() + ": ")) {
        throw;  // already names its path
      }
      reader.fail(path, message);
    }
  }();
  // The count is checked before splitting, which would allocate the split net
  const auto check_count = [&](long long count) { check_control_point_count(reader, path, count); };
  const auto added = [](const KnotVector& knots, int parts) {
    return knots.control_point_count() + static_cast<long long>(parts - 1) *
                                             static_cast<long long>(knots.non_empty_spans().size());
  };
  if (auto* surface = std::get_if<NurbsSurface>(&shape)) {
    check_count(surface->control_point_count());
    if (reader.find(recipe, "split") != nullptr) {
      const Eigen::Vector2i parts = keys.integer_pair("split", {1, 1}, 1, kMaxSplit);
      check_count(added(surface->knots_u(), parts.x()) * added(surface->knots_v(), parts.y()));
      *surface = split_spans(*surface, parts);
    }
  } else {
    auto& curve = std::get<NurbsCurve>(shape);
    check_count(curve.control_point_count());
    if (const JsonValue* split = reader.find(recipe, "split")) {
      const int parts = reader.integer(*split, keys.path("split"), 1, kMaxSplit);
      check_count(added(curve.knots(), parts));
      curve = split_spans(curve, parts);
    }
  }
  if (reader.find(recipe, "translate") != nullptr) {
    const Eigen::RowVector3d offset = keys.point("translate", Eigen::Vector3d::Zero()).transpose();
    std::visit(
        [&](auto& s) {
          Eigen::MatrixX3d points = s.control_points();
          points.rowwise() += offset;
          s.set_control_points(points);
        },
        shape);
  }
  return shape;
}

}  // namespace

const std::vector<const char*>& shape_recipe_kinds() {
  return recipe_kinds();
}

const std::vector<const char*>& shape_recipe_keys() {
  static const std::vector<const char*> keys = [] {
    std::vector<const char*> names;
    const auto add = [&](const char* key) {
      if (std::none_of(names.begin(), names.end(),
                       [&](const char* name) { return std::string_view(name) == key; })) {
        names.push_back(key);
      }
    };
    for (const RecipeKind& kind : recipe_table()) {
      std::for_each(kind.keys.begin(), kind.keys.end(), add);
    }
    add("split");
    add("translate");
    return names;
  }();
  return keys;
}

Shape make_shape(const SceneReader& reader, const JsonValue& recipe, const std::string& path) {
  return make_nested_shape(reader, recipe, path, 0);
}

}  // namespace dnurbs
