#include "dnurbs/io/scene_reader.h"

#include <functional>

#include <utility>

#include "dnurbs/core/content_hash.h"
#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"
#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/output_path.h"

namespace dnurbs {
namespace {

template <typename Names>
std::string list_of(const Names& names) {
  std::string list;
  for (const char* name : names) {
    if (!list.empty()) {
      list += ", ";
    }
    list += name;
  }
  return list;
}

template <typename Names>
bool contains(const Names& names, const std::string& key) {
  for (const char* name : names) {
    if (key == name) {
      return true;
    }
  }
  return false;
}

}  // namespace

std::string join_json_path(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

SceneReader::SceneReader(std::string source, std::filesystem::path directory)
    : source_(std::move(source)), directory_(std::move(directory)) {}

std::filesystem::path SceneReader::resolve(const std::string& file) const {
  std::filesystem::path path = file;
  path = path.is_relative() ? directory_ / path : path;
  std::string digest;
  try {
    digest = content_hash(read_input_file(path, "scene data file"));
  } catch (const Error&) {
    digest = "unreadable";
  }
  input_digests_.push_back(file + "=" + digest);
  return path;
}

void SceneReader::fail(const std::string& path, const std::string& message) const {
  std::string text = source_;
  text += ": ";
  text += path.empty() ? std::string("(top level)") : path;
  text += ": ";
  text += message;
  throw Error(text);
}

void SceneReader::object(const JsonValue& value, const std::string& path,
                         std::initializer_list<const char*> allowed) const {
  object(value, path, std::vector<const char*>(allowed), "");
}

void SceneReader::object(const JsonValue& value, const std::string& path,
                         const std::vector<const char*>& allowed, const std::string& what) const {
  if (!value.is_object()) {
    fail(path, "expected an object, got " + describe_json_value(value));
  }
  const std::string owner = what.empty() ? "" : " for " + what;
  for (const auto& item : value.items()) {
    if (!contains(allowed, item.key())) {
      fail(join_json_path(path, item.key()),
           "unknown key" + owner + " (expected only " + list_of(allowed) + ")");
    }
  }
}

const JsonValue* SceneReader::find(const JsonValue& object, const char* key) const {
  const auto found = object.find(key);
  return found == object.end() ? nullptr : &*found;
}

const JsonValue& SceneReader::require(const JsonValue& object, const std::string& path,
                                      const char* key, const std::string& expected) const {
  const JsonValue* found = find(object, key);
  if (found == nullptr) {
    fail(join_json_path(path, key), "missing key (expected " + expected + ")");
  }
  return *found;
}

double SceneReader::number(const JsonValue& value, const std::string& path) const {
  if (!value.is_number()) {
    fail(path, "expected a finite number, got " + describe_json_value(value));
  }
  return value.get<double>();
}

double SceneReader::bounded(const JsonValue& value, const std::string& path, double minimum,
                            bool strict) const {
  const double x = number(value, path);
  if (strict ? !(x > minimum) : !(x >= minimum)) {
    fail(path, std::string("expected a number ") + (strict ? "> " : ">= ") +
                   format_json_number(minimum) + ", got " + format_json_number(x));
  }
  return x;
}

void SceneReader::number_key(const JsonValue& object, const std::string& path, const char* key,
                             double& x, std::optional<double> minimum, bool strict) const {
  if (const JsonValue* value = find(object, key)) {
    x = minimum ? bounded(*value, join_json_path(path, key), *minimum, strict)
                : number(*value, join_json_path(path, key));
  }
}

int SceneReader::integer(const JsonValue& value, const std::string& path, int minimum,
                         int maximum) const {
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

void SceneReader::integer_key(const JsonValue& object, const std::string& path, const char* key,
                              int& n, int minimum, int maximum) const {
  if (const JsonValue* value = find(object, key)) {
    n = integer(*value, join_json_path(path, key), minimum, maximum);
  }
}

void SceneReader::boolean_key(const JsonValue& object, const std::string& path, const char* key,
                              bool& b) const {
  if (const JsonValue* value = find(object, key)) {
    if (!value->is_boolean()) {
      fail(join_json_path(path, key), "expected true or false, got " + describe_json_value(*value));
    }
    b = value->get<bool>();
  }
}

std::string SceneReader::string(const JsonValue& value, const std::string& path) const {
  if (!value.is_string()) {
    fail(path, "expected a string, got " + describe_json_value(value));
  }
  return value.get<std::string>();
}

std::string SceneReader::name(const JsonValue& value, const std::string& path) const {
  std::string result = string(value, path);
  if (!is_plain_name(result)) {
    fail(path, std::string("expected a name of ") + kPlainNameRule + ", got " +
                   describe_json_value(value));
  }
  return result;
}

std::string SceneReader::choice(const JsonValue& value, const std::string& path,
                                std::initializer_list<const char*> options) const {
  return choice(value, path, std::vector<const char*>(options));
}

std::string SceneReader::choice(const JsonValue& value, const std::string& path,
                                const std::vector<const char*>& options) const {
  if (value.is_string() && contains(options, value.get<std::string>())) {
    return value.get<std::string>();
  }
  fail(path, "expected one of " + list_of(options) + ", got " + describe_json_value(value));
}

void SceneReader::fail_expected(const JsonValue& value, const std::string& path,
                                const char* what) const {
  fail(path, std::string("expected ") + what + ", got " + describe_json_value(value));
}

double SceneReader::element(const JsonValue& array, const std::string& path, int i) const {
  return number(array[static_cast<size_t>(i)], json_index_path(path, static_cast<size_t>(i)));
}

Eigen::Vector3d SceneReader::point(const JsonValue& value, const std::string& path) const {
  return vector<3>(value, path, "[x, y, z]");
}

Eigen::Vector2d SceneReader::parameter(const JsonValue& value, const std::string& path) const {
  if (!value.is_array() || value.empty() || value.size() > 2) {
    fail(path, "expected a material parameter [u] or [u, v], got " + describe_json_value(value));
  }
  Eigen::Vector2d u = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < value.size(); ++i) {
    u(static_cast<int>(i)) = number(value[i], json_index_path(path, i));
  }
  return u;
}

Eigen::Matrix2d SceneReader::matrix2(const JsonValue& value, const std::string& path) const {
  if (!value.is_array() || value.size() != 2) {
    fail(path,
         "expected a 2 x 2 matrix [[m11, m12], [m21, m22]], got " + describe_json_value(value));
  }
  Eigen::Matrix2d m;
  for (size_t r = 0; r < 2; ++r) {
    const Eigen::Vector2d row = vector<2>(value[r], json_index_path(path, r), "a row [m1, m2]");
    m.row(static_cast<int>(r)) = row.transpose();
  }
  return m;
}

const JsonValue& SceneReader::array(const JsonValue& value, const std::string& path,
                                    const std::string& of) const {
  if (!value.is_array()) {
    fail(path, "expected an array of " + of + ", got " + describe_json_value(value));
  }
  return value;
}

std::vector<int> SceneReader::indices(const JsonValue& value, const std::string& path) const {
  array(value, path, "indices");
  std::vector<int> result;
  for (size_t i = 0; i < value.size(); ++i) {
    result.push_back(integer(value[i], json_index_path(path, i), 0, 1 << 30));
  }
  return result;
}

void SceneReader::times(const JsonValue& object, const std::string& path,
                        std::vector<double>& times, size_t value_count) const {
  const std::string times_path = join_json_path(path, "times");
  const JsonValue& list = array(require(object, path, "times", "an array of keyframe times"),
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
    fail(join_json_path(path, "values"), "expected " + std::to_string(times.size()) +
                                             " values (one per keyframe time), got " +
                                             std::to_string(value_count));
  }
}

Interpolation SceneReader::interpolation(const JsonValue& value, const std::string& path) const {
  for (const Interpolation kind :
       {Interpolation::kCubic, Interpolation::kMonotone, Interpolation::kLinear}) {
    if (value.is_string() && value.get<std::string>() == interpolation_name(kind)) {
      return kind;
    }
  }
  fail(path, "expected \"cubic\", \"monotone\" or \"linear\", got " + describe_json_value(value));
}

template <typename Schedule, typename ReadValue>
Schedule SceneReader::schedule(const JsonValue& value, const std::string& path, bool constant,
                               const char* expected, const char* of,
                               const ReadValue& read_value) const {
  Schedule schedule;
  if (constant) {
    schedule.values.push_back(read_value(value, path));
    return schedule;
  }
  if (!value.is_object()) {
    fail(path, std::string("expected ") + expected + ", got " + describe_json_value(value));
  }
  object(value, path, {"times", "values", "interpolation"});
  if (value.contains("interpolation")) {
    schedule.interpolation =
        interpolation(value["interpolation"], join_json_path(path, "interpolation"));
  }
  const std::string values_path = join_json_path(path, "values");
  const JsonValue& values =
      array(require(value, path, "values", std::string("an array of ") + of), values_path, of);
  for (size_t i = 0; i < values.size(); ++i) {
    schedule.values.push_back(read_value(values[i], json_index_path(values_path, i)));
  }
  times(value, path, schedule.times, values.size());
  return schedule;
}

VectorSchedule SceneReader::vector_schedule(const JsonValue& value, const std::string& path) const {
  return schedule<VectorSchedule>(
      value, path, value.is_array(),
      "[x, y, z] or {\"times\": [...], \"values\": [[x, y, z], ...]}", "[x, y, z] values",
      [this](const JsonValue& v, const std::string& p) { return point(v, p); });
}

ScalarSchedule SceneReader::scalar_schedule(const JsonValue& value, const std::string& path) const {
  return schedule<ScalarSchedule>(
      value, path, value.is_number(), "a number or {\"times\": [...], \"values\": [...]}",
      "numbers", [this](const JsonValue& v, const std::string& p) { return number(v, p); });
}

int ModelNames::resolve(const SceneReader& reader, const JsonValue& value,
                        const std::string& path) const {
  if (value.is_string()) {
    const std::string name = value.get<std::string>();
    for (int i = 0; i < count(); ++i) {
      if (names_[static_cast<size_t>(i)] == name) {
        return i;
      }
    }
    reader.fail(path,
                "expected the name or index of a model, got unknown model name \"" + name + "\"");
  }
  if (!value.is_number_integer() || value.get<long long>() < 0 ||
      value.get<long long>() >= count()) {
    reader.fail(path, "expected a model index in 0.." + std::to_string(count() - 1) +
                          " or a model name, got " + describe_json_value(value));
  }
  return value.get<int>();
}

int ModelNames::require(const SceneReader& reader, const JsonValue& object, const std::string& path,
                        const char* key) const {
  return resolve(reader, reader.require(object, path, key, "a model index or name"),
                 join_json_path(path, key));
}

}  // namespace dnurbs
