#pragma once
// Reading scene files: typed values out of the parsed JSON document, every failure an Error
// "<source>: <json path>: <what was expected>, got <what was there>". The scene dispatcher and the
// readers of every model, force and constraint type (io/scene_registry.h) share it, so that all
// keys are checked and named the same way.

#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "dnurbs/io/schedule.h"

namespace dnurbs {

/// A parsed JSON value of a scene file.
using JsonValue = nlohmann::json;

/// `path.key`, or `key` at the top level.
std::string join_json_path(const std::string& path, const std::string& key);

/// Reads typed values; every failure names the source and the JSON path.
class SceneReader {
 public:
  /// `directory`: where relative file names of the scene (shape_file, fit.points) resolve.
  SceneReader(std::string source, std::filesystem::path directory);

  const std::string& source() const { return source_; }
  const std::filesystem::path& directory() const { return directory_; }
  /// `file` resolved against directory() when relative. Every data file of a scene is found
  /// through here, so it also records "<file>=<content hash of its bytes>" (or
  /// "<file>=unreadable"; the file's own reader then names the failure) in input_digests().
  std::filesystem::path resolve(const std::string& file) const;
  /// The records of resolve(), in call order.
  const std::vector<std::string>& input_digests() const { return input_digests_; }

  /// Throws Error "<source>: <path>: <message>" ("(top level)" for the empty path).
  [[noreturn]] void fail(const std::string& path, const std::string& message) const;

  /// Checks that `value` is an object with only the allowed keys.
  void object(const JsonValue& value, const std::string& path,
              std::initializer_list<const char*> allowed) const;
  /// The same with the keys in a vector, and `what` naming the object in the message ("a
  /// snake model": "unknown key for a snake model (expected only ...)"; empty: "unknown key
  /// (expected only ...)").
  void object(const JsonValue& value, const std::string& path,
              const std::vector<const char*>& allowed, const std::string& what) const;
  /// The key's value, or nullptr when absent.
  const JsonValue* find(const JsonValue& object, const char* key) const;
  /// The key's value; fails "missing key (expected <expected>)" when absent.
  const JsonValue& require(const JsonValue& object, const std::string& path, const char* key,
                           const std::string& expected) const;

  double number(const JsonValue& value, const std::string& path) const;
  /// A number with a lower bound (strict or not).
  double bounded(const JsonValue& value, const std::string& path, double minimum,
                 bool strict) const;
  /// An optional number key: keeps `x` when absent.
  void number_key(const JsonValue& object, const std::string& path, const char* key, double& x,
                  std::optional<double> minimum = std::nullopt, bool strict = false) const;
  int integer(const JsonValue& value, const std::string& path, int minimum, int maximum) const;
  void integer_key(const JsonValue& object, const std::string& path, const char* key, int& n,
                   int minimum, int maximum) const;
  void boolean_key(const JsonValue& object, const std::string& path, const char* key,
                   bool& b) const;
  std::string string(const JsonValue& value, const std::string& path) const;
  /// A string that is a plain name (io/output_path.h: is_plain_name): the names of models,
  /// probes and outputs, which become file names, CSV columns and names inside mesh files.
  std::string name(const JsonValue& value, const std::string& path) const;
  /// One of `options`.
  std::string choice(const JsonValue& value, const std::string& path,
                     std::initializer_list<const char*> options) const;
  std::string choice(const JsonValue& value, const std::string& path,
                     const std::vector<const char*>& options) const;

  /// N numbers; `what` names the expected form in the message ("[x, y, z]").
  template <int N>
  Eigen::Matrix<double, N, 1> vector(const JsonValue& value, const std::string& path,
                                     const char* what) const {
    if (!value.is_array() || value.size() != N) {
      fail_expected(value, path, what);
    }
    Eigen::Matrix<double, N, 1> v;
    for (int i = 0; i < N; ++i) {
      v(i) = element(value, path, i);
    }
    return v;
  }
  Eigen::Vector3d point(const JsonValue& value, const std::string& path) const;
  /// A material parameter: [u] (curves) or [u, v].
  Eigen::Vector2d parameter(const JsonValue& value, const std::string& path) const;
  /// A 2 x 2 matrix [[m11, m12], [m21, m22]].
  Eigen::Matrix2d matrix2(const JsonValue& value, const std::string& path) const;
  const JsonValue& array(const JsonValue& value, const std::string& path,
                         const std::string& of) const;
  std::vector<int> indices(const JsonValue& value, const std::string& path) const;
  VectorSchedule vector_schedule(const JsonValue& value, const std::string& path) const;
  ScalarSchedule scalar_schedule(const JsonValue& value, const std::string& path) const;

 private:
  [[noreturn]] void fail_expected(const JsonValue& value, const std::string& path,
                                  const char* what) const;
  double element(const JsonValue& array, const std::string& path, int i) const;
  void times(const JsonValue& object, const std::string& path, std::vector<double>& times,
             size_t value_count) const;
  /// "cubic", "monotone" or "linear" (a schedule's "interpolation").
  Interpolation interpolation(const JsonValue& value, const std::string& path) const;
  /// A schedule: a constant (when `constant`) or keyframes {"times": [...], "values": [...],
  /// "interpolation": ... (optional)}, each value read by read_value(json, path); `expected` and
  /// `of` name them in messages.
  template <typename Schedule, typename ReadValue>
  Schedule schedule(const JsonValue& value, const std::string& path, bool constant,
                    const char* expected, const char* of, const ReadValue& read_value) const;

  std::string source_;
  std::filesystem::path directory_;
  // Written by resolve(): the readers of every scene part take the reader by const reference
  mutable std::vector<std::string> input_digests_;
};

/// Model references of forces, constraints and probes: an index or a model name.
class ModelNames {
 public:
  explicit ModelNames(std::vector<std::string> names) : names_(std::move(names)) {}
  int count() const { return static_cast<int>(names_.size()); }
  /// The index `value` refers to; fails naming `path` for an unknown name or index.
  int resolve(const SceneReader& reader, const JsonValue& value, const std::string& path) const;
  /// The model at key `key` of `object` (required).
  int require(const SceneReader& reader, const JsonValue& object, const std::string& path,
              const char* key) const;

 private:
  std::vector<std::string> names_;
};

}  // namespace dnurbs
