#include "dnurbs/io/json_messages.h"

#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"

namespace dnurbs {

std::string format_json_number(double value) {
  if (value == 0.0 && std::signbit(value)) {
    return "-0.0";  // "-0" would read back as the integer 0
  }
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
      // A short, printable, escaped excerpt (core/input_file.h)
      return "string \"" + printable_excerpt(value.get<std::string>()) + "\"";
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

namespace {

// "line L, column C" of byte `offset` of `text` (1-based, columns in bytes)
std::string text_position(const std::string& text, std::size_t offset) {
  std::size_t line = 1;
  std::size_t column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

}  // namespace

nlohmann::json parse_json_document(const std::string& text, const std::string& source) {
  std::string detail;
  try {
    // nlohmann keeps the last of repeated keys silently: a file that says two things is refused
    std::vector<std::set<std::string>> keys;  // of each object being read
    std::string repeated;
    const nlohmann::json::parser_callback_t callback =
        [&](int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
          if (event == nlohmann::json::parse_event_t::object_start) {
            keys.emplace_back();
          } else if (event == nlohmann::json::parse_event_t::object_end && !keys.empty()) {
            keys.pop_back();
          } else if (event == nlohmann::json::parse_event_t::key && !keys.empty() &&
                     !keys.back().insert(parsed.get<std::string>()).second && repeated.empty()) {
            repeated = parsed.get<std::string>();
          }
          return true;
        };
    nlohmann::json result = nlohmann::json::parse(text, callback);
    if (repeated.empty()) {
      return result;
    }
    detail = "every key once in an object, got " + describe_json_value(repeated) + " twice";
    throw Error(source + ": (document): expected " + detail);
  } catch (const nlohmann::json::parse_error& error) {
    // "[json.exception.parse_error.101] parse error at line L, column C: <what>"
    detail = error.what();
    const auto at = detail.find("at line ");
    detail = at == std::string::npos ? detail : detail.substr(at + 3);
  } catch (const nlohmann::json::exception& error) {
    // "[json.exception.out_of_range.406] number overflow parsing '1e999'": no position; the
    // token is quoted, so find it in the text (the first occurrence that is a whole token)
    detail = error.what();
    const auto bracket = detail.find("] ");
    detail = bracket == std::string::npos ? detail : detail.substr(bracket + 2);
    const auto open = detail.find('\'');
    const auto close = detail.rfind('\'');
    if (open != std::string::npos && close > open + 1) {
      const std::string token = detail.substr(open + 1, close - open - 1);
      const auto number_char = [](char c) {
        return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E';
      };
      for (auto at = text.find(token); at != std::string::npos; at = text.find(token, at + 1)) {
        const std::size_t end = at + token.size();
        if ((at == 0 || !number_char(text[at - 1])) &&
            (end >= text.size() || !number_char(text[end]))) {
          detail = text_position(text, at) + ": " + detail + " (beyond the range of a double)";
          break;
        }
      }
    }
  }
  throw Error(source + ": (document): expected valid JSON at " + detail);
}

std::string json_index_path(const std::string& path, std::size_t index) {
  std::string result = path;
  result += '[';
  result += std::to_string(index);
  result += ']';
  return result;
}

}  // namespace dnurbs
