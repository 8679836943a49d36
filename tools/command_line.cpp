#include "tools/command_line.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "dnurbs/core/error.h"

namespace dnurbs::tools {

bool parse_command_line(CLI::App& app, const std::vector<std::string>& arguments, const char* help,
                        std::ostream& out) {
  // CLI11 takes the arguments last first
  std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    out << help;
    return false;
  } catch (const CLI::ParseError& error) {
    throw UsageError(error.what());
  }
  return true;
}

const CLI::Validator& finite_number() {
  static const CLI::Validator validator(
      [](const std::string& text) {
        const double value = std::strtod(text.c_str(), nullptr);
        return std::isfinite(value) ? std::string() : "expected a finite number, got " + text;
      },
      "FINITE");
  return validator;
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
