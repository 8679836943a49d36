#include "dnurbs/sculpt/sculpt_request.h"

#include <array>
#include <cmath>
#include <initializer_list>
#include <utility>

#include <nlohmann/json.hpp>

#include "dnurbs/io/json_messages.h"

namespace dnurbs {
namespace {

using Json = nlohmann::json;

constexpr std::array<SculptSettingRange, 6> kSettingRanges = {{
    {"stiffness", 0.0, 1e6, true},
    {"tension", 0.0, 1e4, false},
    {"rigidity", 0.0, 1e4, false},
    {"density", 0.0, 1e4, true},
    {"damping", 0.0, 1e4, false},
    {"dt", 1e-4, 0.1, false},
}};

struct TypeKeys {
  const char* name;
  SculptRequestType type;
  std::initializer_list<const char*> keys;  // besides "type" and "id"
};

const std::array<TypeKeys, 14>& request_types() {
  static const std::array<TypeKeys, 14> types = {{
      {"grab", SculptRequestType::kGrab, {"model", "at", "target"}},
      {"push", SculptRequestType::kPush, {"model", "at", "force"}},
      {"move", SculptRequestType::kMove, {"drag", "target", "force", "at"}},
      {"release", SculptRequestType::kRelease, {"drag"}},
      {"pin", SculptRequestType::kPin, {"model", "at"}},
      {"set", SculptRequestType::kSet, {"key", "value"}},
      {"play", SculptRequestType::kPlay, {}},
      {"pause", SculptRequestType::kPause, {}},
      {"step", SculptRequestType::kStep, {}},
      {"reset", SculptRequestType::kReset, {}},
      {"undo", SculptRequestType::kUndo, {}},
      {"save", SculptRequestType::kSave, {}},
      {"query", SculptRequestType::kQuery, {"model", "at"}},
      {"shape", SculptRequestType::kShape, {"model"}},
  }};
  return types;
}

// Reads the keys of one message, failing with the message's type and id in the error.
class RequestReader {
 public:
  RequestReader(const Json& message, SculptRequest& request)
      : message_(message), request_(request) {}

  [[noreturn]] void fail(const std::string& text) const {
    throw SculptRequestError(request_.name.empty() ? text : request_.name + ": " + text,
                             request_.name, request_.id);
  }

  const Json* find(const char* key) const {
    const auto it = message_.find(key);
    return it == message_.end() ? nullptr : &*it;
  }

  const Json& require(const char* key) const {
    const Json* value = find(key);
    if (value == nullptr) {
      fail(std::string("missing key \"") + key + "\"");
    }
    return *value;
  }

  double number(const Json& value, const std::string& key) const {
    if (!value.is_number()) {
      fail(key + ": expected a number, got " + describe_json_value(value));
    }
    const double x = value.get<double>();
    if (!std::isfinite(x)) {
      fail(key + ": expected a finite number, got " + format_json_number(x));
    }
    return x;
  }

  long long integer(const Json& value, const std::string& key, long long min, long long max) const {
    if (!value.is_number_integer()) {
      fail(key + ": expected an integer, got " + describe_json_value(value));
    }
    const long long x = value.get<long long>();
    if (x < min || x > max) {
      fail(key + ": expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
           "], got " + std::to_string(x));
    }
    return x;
  }

  // A JSON array of `size` finite numbers.
  Eigen::VectorXd numbers(const Json& value, const std::string& key, int size) const {
    if (!value.is_array() || value.size() != static_cast<std::size_t>(size)) {
      fail(key + ": expected an array of " + std::to_string(size) + " numbers, got " +
           describe_json_value(value));
    }
    Eigen::VectorXd result(size);
    for (int i = 0; i < size; ++i) {
      result(i) = number(value[static_cast<std::size_t>(i)], json_index_path(key, i));
    }
    return result;
  }

 private:
  const Json& message_;
  SculptRequest& request_;
};

void read_model_and_point(const RequestReader& reader, const SculptRequestLimits& limits,
                          bool needs_point, SculptRequest& request) {
  const long long models = static_cast<long long>(limits.models.size());
  request.model = static_cast<int>(reader.integer(reader.require("model"), "model", 0, models - 1));
  if (!needs_point) {
    return;
  }
  const SculptRequestLimits::ModelLimits& model =
      limits.models[static_cast<std::size_t>(request.model)];
  const int n = model.parametric_dimension;
  const Eigen::VectorXd at = reader.numbers(reader.require("at"), "at", n);
  Eigen::Vector2d u = Eigen::Vector2d::Zero();
  u.head(n) = at;
  for (int k = 0; k < n; ++k) {
    if (u(k) < model.min(k) || u(k) > model.max(k)) {
      reader.fail(json_index_path("at", static_cast<std::size_t>(k)) + ": " +
                  format_json_number(u(k)) + " is outside the domain [" +
                  format_json_number(model.min(k)) + ", " + format_json_number(model.max(k)) +
                  "] of model " + std::to_string(request.model));
    }
  }
  request.at = u;
}

Eigen::Vector3d vector3(const RequestReader& reader, const char* key) {
  return reader.numbers(reader.require(key), key, 3);
}

void read_set(const RequestReader& reader, SculptRequest& request) {
  const Json& key = reader.require("key");
  std::string names;
  for (std::size_t i = 0; i < kSettingRanges.size(); ++i) {
    if (key.is_string() && key.get<std::string>() == kSettingRanges[i].name) {
      request.setting = static_cast<SculptSetting>(i);
      const SculptSettingRange& range = kSettingRanges[i];
      const double value = reader.number(reader.require("value"), "value");
      if (value < range.min || (range.open_min && value == range.min) || value > range.max) {
        reader.fail(std::string("value: ") + range.name + " must be in " +
                    (range.open_min ? "(" : "[") + format_json_number(range.min) + ", " +
                    format_json_number(range.max) + "], got " + format_json_number(value));
      }
      request.value = value;
      return;
    }
    names += (i == 0 ? "" : ", ") + std::string(kSettingRanges[i].name);
  }
  reader.fail("key: expected one of " + names + ", got " + describe_json_value(key));
}

void read_move(const RequestReader& reader, SculptRequest& request) {
  request.drag = static_cast<int>(reader.integer(reader.require("drag"), "drag", 0, 1LL << 30));
  const Json* target = reader.find("target");
  const Json* force = reader.find("force");
  if ((target == nullptr) == (force == nullptr)) {
    reader.fail("expected exactly one of \"target\" (a spring) and \"force\" (a push)");
  }
  if (target != nullptr) {
    request.target = reader.numbers(*target, "target", 3);
  } else {
    request.force = reader.numbers(*force, "force", 3);
  }
  if (const Json* at = reader.find("at")) {
    // The domain check needs the drag's model: the session checks it (it knows the drag).
    const Eigen::VectorXd u = reader.numbers(*at, "at", static_cast<int>(at->size()));
    if (u.size() < 1 || u.size() > 2) {
      reader.fail("at: expected [u] or [u, v], got " + describe_json_value(*at));
    }
    request.at = Eigen::Vector2d(u(0), u.size() == 2 ? u(1) : 0.0);
  }
}

}  // namespace

const SculptSettingRange& sculpt_setting_range(SculptSetting setting) {
  return kSettingRanges.at(static_cast<std::size_t>(setting));
}

SculptRequest parse_sculpt_request(std::string_view text, const SculptRequestLimits& limits) {
  SculptRequest request;
  if (text.size() > limits.max_bytes) {
    throw SculptRequestError("message of " + std::to_string(text.size()) +
                                 " bytes refused: at most " + std::to_string(limits.max_bytes),
                             "", std::nullopt);
  }
  const Json message = Json::parse(text, nullptr, false);
  if (message.is_discarded() || !message.is_object()) {
    throw SculptRequestError(message.is_discarded()
                                 ? "expected a JSON object, got malformed JSON"
                                 : "expected a JSON object, got " + describe_json_value(message),
                             "", std::nullopt);
  }
  RequestReader reader(message, request);
  if (const Json* id = reader.find("id")) {
    request.id = reader.integer(*id, "id", 0, 1LL << 52);
  }
  const Json& type = reader.require("type");
  const TypeKeys* keys = nullptr;
  for (const TypeKeys& candidate : request_types()) {
    if (type.is_string() && type.get<std::string>() == candidate.name) {
      keys = &candidate;
    }
  }
  if (keys == nullptr) {
    reader.fail("type: unknown message type " + describe_json_value(type));
  }
  request.type = keys->type;
  request.name = keys->name;
  for (const auto& [key, value] : message.items()) {
    bool known = key == "type" || key == "id";
    for (const char* allowed : keys->keys) {
      known = known || key == allowed;
    }
    if (!known) {
      reader.fail("unknown key \"" + key.substr(0, 64) + "\"");
    }
  }
  switch (request.type) {
    case SculptRequestType::kGrab:
      read_model_and_point(reader, limits, true, request);
      request.target = vector3(reader, "target");
      break;
    case SculptRequestType::kPush:
      read_model_and_point(reader, limits, true, request);
      request.force = vector3(reader, "force");
      break;
    case SculptRequestType::kPin:
    case SculptRequestType::kQuery:
      read_model_and_point(reader, limits, true, request);
      break;
    case SculptRequestType::kShape:
      read_model_and_point(reader, limits, false, request);
      break;
    case SculptRequestType::kMove:
      read_move(reader, request);
      break;
    case SculptRequestType::kRelease:
      request.drag = static_cast<int>(reader.integer(reader.require("drag"), "drag", 0, 1LL << 30));
      break;
    case SculptRequestType::kSet:
      read_set(reader, request);
      break;
    default:
      break;
  }
  return request;
}

}  // namespace dnurbs
