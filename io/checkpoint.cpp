#include "dnurbs/io/checkpoint.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"
#include "dnurbs/io/atomic_write.h"
#include "dnurbs/io/json_messages.h"

namespace dnurbs {
namespace {

using Json = nlohmann::json;

void append_vector(std::string& text, const char* key, const Eigen::VectorXd& v) {
  text += "  \"";
  text += key;
  text += "\": [";
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    text += i == 0 ? "" : ", ";
    text += format_json_number(v(i));
  }
  text += "]";
}

[[noreturn]] void fail(const std::string& source, const std::string& path,
                       const std::string& message) {
  std::string text = source;
  text += ": ";
  text += path;
  text += ": ";
  text += message;
  throw Error(text);
}

const Json& require(const Json& root, const std::string& source, const char* key) {
  const auto found = root.find(key);
  if (found == root.end()) {
    fail(source, key, "missing key");
  }
  return *found;
}

Eigen::VectorXd read_vector(const Json& root, const std::string& source, const char* key) {
  const Json& list = require(root, source, key);
  if (!list.is_array()) {
    fail(source, key, "expected an array of finite numbers");
  }
  Eigen::VectorXd v(static_cast<Eigen::Index>(list.size()));
  for (size_t i = 0; i < list.size(); ++i) {
    if (!list[i].is_number() || !std::isfinite(list[i].get<double>())) {
      fail(source, std::string(key) + "[" + std::to_string(i) + "]", "expected a finite number");
    }
    v(static_cast<Eigen::Index>(i)) = list[i].get<double>();
  }
  return v;
}

}  // namespace

std::string checkpoint_to_json(const Checkpoint& checkpoint) {
  std::string text = "{\n  \"format\": \"dnurbs-checkpoint-1\",\n  \"scene\": ";
  text += Json(checkpoint.scene).dump();
  text += ",\n  \"scene_hash\": ";
  text += Json(checkpoint.scene_hash).dump();
  text += ",\n  \"step\": " + std::to_string(checkpoint.step);
  text += ",\n  \"time\": ";
  text += format_json_number(checkpoint.time);
  text += ",\n";
  append_vector(text, "q", checkpoint.coordinates);
  text += ",\n";
  append_vector(text, "qd", checkpoint.velocities);
  text += ",\n  \"accelerations_valid\": ";
  text += checkpoint.accelerations_valid ? "true" : "false";
  text += ",\n";
  append_vector(text, "a",
                checkpoint.accelerations_valid ? checkpoint.accelerations : Eigen::VectorXd());
  if (checkpoint.rest_coordinates.size() > 0) {
    text += ",\n";
    append_vector(text, "rest", checkpoint.rest_coordinates);
  }
  text += "\n}\n";
  return text;
}

Checkpoint parse_checkpoint_json(const std::string& text, const std::string& source) {
  const Json root = parse_json_document(text, source);
  if (!root.is_object()) {
    fail(source, "(top level)", "expected a checkpoint object");
  }
  const Json& format = require(root, source, "format");
  if (format != "dnurbs-checkpoint-1") {
    fail(source, "format", "expected \"dnurbs-checkpoint-1\"");
  }
  Checkpoint checkpoint;
  const Json& scene = require(root, source, "scene");
  const Json& hash = require(root, source, "scene_hash");
  const Json& step = require(root, source, "step");
  const Json& time = require(root, source, "time");
  const Json& valid = require(root, source, "accelerations_valid");
  if (!scene.is_string()) {
    fail(source, "scene", "expected a string");
  }
  if (!hash.is_string()) {
    fail(source, "scene_hash", "expected a string");
  }
  if (!step.is_number_integer() || step.get<long long>() < 0 || step.get<long long>() > 100000000) {
    fail(source, "step", "expected a step count in 0..100000000");
  }
  if (!time.is_number() || !std::isfinite(time.get<double>())) {
    fail(source, "time", "expected a finite number");
  }
  if (!valid.is_boolean()) {
    fail(source, "accelerations_valid", "expected true or false");
  }
  checkpoint.scene = scene.get<std::string>();
  checkpoint.scene_hash = hash.get<std::string>();
  checkpoint.step = step.get<int>();
  checkpoint.time = time.get<double>();
  checkpoint.coordinates = read_vector(root, source, "q");
  checkpoint.velocities = read_vector(root, source, "qd");
  checkpoint.accelerations_valid = valid.get<bool>();
  checkpoint.accelerations = read_vector(root, source, "a");
  if (root.contains("rest")) {
    checkpoint.rest_coordinates = read_vector(root, source, "rest");
  }
  if (checkpoint.accelerations_valid &&
      checkpoint.accelerations.size() != checkpoint.velocities.size()) {
    fail(source, "a", "expected as many accelerations as velocities (qd)");
  }
  return checkpoint;
}

Checkpoint read_checkpoint_file(const std::filesystem::path& path) {
  return parse_checkpoint_json(read_input_file(path, "checkpoint file"), path.string());
}

void write_checkpoint_file(const std::filesystem::path& path, const Checkpoint& checkpoint) {
  write_file_atomically(path, checkpoint_to_json(checkpoint));
}

}  // namespace dnurbs
