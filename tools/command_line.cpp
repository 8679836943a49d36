#include "tools/command_line.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>

#include "dnurbs/core/error.h"

namespace dnurbs::tools {

namespace {

// The whole text as a finite double, or nothing.
std::optional<double> read_finite_double(const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE ||
      !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

// The whole text as a decimal integer, or nothing.
std::optional<long> read_integer(const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE) {
    return std::nullopt;
  }
  return value;
}

// "text" for a message
std::string in_quotes(const std::string& text) {
  return "\"" + text + "\"";
}

// The whole text as a finite double; throws UsageError naming `what` otherwise.
double parse_double(const std::string& text, const std::string& what) {
  const std::optional<double> value = read_finite_double(text);
  if (!value) {
    throw UsageError(what + ": expected a finite number, got " + in_quotes(text));
  }
  return *value;
}

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

bool parse_command_line(CLI::App& app, const std::vector<std::string>& arguments, const char* help,
                        std::ostream& out) {
  // -h and --help act as soon as they are read, before the values of the other options are
  // checked (CLI11's own help flag waits for those checks)
  app.set_help_flag();
  app.add_flag_callback("-h,--help", [] { throw CLI::CallForHelp(); })->trigger_on_parse();
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

CLI::Validator integer_in(int minimum, int maximum) {
  const std::string range = std::to_string(minimum) + ".." + std::to_string(maximum);
  return {[minimum, maximum, range](std::string& text) {
            const std::optional<long> value = read_integer(text);
            if (!value || *value < minimum || *value > maximum) {
              return "expected an integer in " + range + ", got " + in_quotes(text);
            }
            text = std::to_string(*value);  // in decimal for CLI11, which reads "010" as octal
            return std::string();
          },
          "INT in " + range};
}

const CLI::Validator& finite_number() {
  static const CLI::Validator validator(
      [](const std::string& text) {
        return read_finite_double(text) ? std::string()
                                        : "expected a finite number, got " + in_quotes(text);
      },
      "FINITE");
  return validator;
}

CLI::Validator positive_number(double maximum) {
  std::ostringstream expected;
  if (maximum < std::numeric_limits<double>::max()) {
    expected << "a number in (0, " << maximum << "]";
  } else {
    expected << "a finite number > 0";
  }
  return {[maximum, expected = expected.str()](const std::string& text) {
            const std::optional<double> value = read_finite_double(text);
            return value && *value > 0.0 && *value <= maximum
                       ? std::string()
                       : "expected " + expected + ", got " + in_quotes(text);
          },
          "POSITIVE"};
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

void print_json(std::ostream& out, const nlohmann::ordered_json& document) {
  check_finite(document, "");
  // Bytes that are not UTF-8 (a file name) become U+FFFD rather than an exception
  out << document.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
}

}  // namespace dnurbs::tools
