#include "io/json_messages.h"

#include <cstdio>

namespace dnurbs {

std::string format_json_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.17g", value);
  return buffer;
}

std::string describe_json_value(const nlohmann::json& value) {
  using Json = nlohmann::json;
  switch (value.type()) {
    case Json::value_t::null:
      return "null";
    case Json::value_t::boolean:
      return value.get<bool>() ? "true" : "false";
    case Json::value_t::string: {
      std::string text = value.get<std::string>();
      if (text.size() > 40) {
        text.resize(40);
        text += "...";
      }
      std::string result = "string \"";
      result += text;
      result += '"';
      return result;
    }
    case Json::value_t::array: {
      std::string result = "an array of ";
      result += std::to_string(value.size());
      result += " values";
      return result;
    }
    case Json::value_t::object:
      return "an object";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float: {
      std::string result = "number ";
      result += format_json_number(value.get<double>());
      return result;
    }
    default:
      return "a value of an unsupported kind";
  }
}

std::string json_index_path(const std::string& path, std::size_t index) {
  std::string result = path;
  result += '[';
  result += std::to_string(index);
  result += ']';
  return result;
}

}  // namespace dnurbs
