#include "tools/command_line.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "dnurbs/core/error.h"

namespace dnurbs::tools {

bool wants_help(const std::vector<std::string>& arguments) {
  for (const auto& argument : arguments) {
    if (argument == "-h" || argument == "--help") {
      return true;
    }
  }
  return false;
}

const std::string& flag_value(const std::vector<std::string>& arguments, size_t& index) {
  if (index + 1 >= arguments.size()) {
    throw UsageError(arguments[index] + " needs a value");
  }
  return arguments[++index];
}

double parse_double(const std::string& text, const std::string& what) {
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE ||
      !std::isfinite(value)) {
    throw UsageError(what + ": expected a finite number, got \"" + text + "\"");
  }
  return value;
}

int parse_int(const std::string& text, const std::string& what, int minimum, int maximum) {
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || value < minimum ||
      value > maximum) {
    throw UsageError(what + ": expected an integer in " + std::to_string(minimum) + ".." +
                     std::to_string(maximum) + ", got \"" + text + "\"");
  }
  return static_cast<int>(value);
}

std::vector<double> parse_doubles(const std::string& text, const std::string& what) {
  std::vector<double> values;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    values.push_back(parse_double(text.substr(start, comma - start), what));
    if (comma == std::string::npos) {
      return values;
    }
    start = comma + 1;
  }
}

namespace {

// Throws Error naming the JSON path of the first non-finite number under `value`.
void check_finite(const nlohmann::ordered_json& value, const std::string& path) {
  if (value.is_number_float() && !std::isfinite(value.get<double>())) {
    throw make_error(path, " is ", value.get<double>(), ", not a finite number (JSON has none)");
  }
  if (value.is_object()) {
    for (const auto& [key, child] : value.items()) {
      check_finite(child, path.empty() ? key : path + "." + key);
    }
  } else if (value.is_array()) {
    for (size_t i = 0; i < value.size(); ++i) {
      check_finite(value[i], path + "[" + std::to_string(i) + "]");
    }
  }
}

}  // namespace

void print_json(std::ostream& out, const nlohmann::ordered_json& document) {
  check_finite(document, "");
  // Bytes that are not UTF-8 (a file name) become U+FFFD rather than an exception
  out << document.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
}

}  // namespace dnurbs::tools
