#include "tools/command_line.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

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

std::string json_string(const std::string& text) {
  std::string quoted = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        quoted += "\\\"";
        break;
      case '\\':
        quoted += "\\\\";
        break;
      case '\n':
        quoted += "\\n";
        break;
      case '\t':
        quoted += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escape[8];
          std::snprintf(escape, sizeof(escape), "\\u%04x", static_cast<unsigned>(c));
          quoted += escape;
        } else {
          quoted += c;
        }
    }
  }
  return quoted + "\"";
}

std::string json_double(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.17g", value);
  return buffer;
}

}  // namespace dnurbs::tools
