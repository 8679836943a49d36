#pragma once
// Small helpers shared by the dnurbs subcommands: usage errors and argument parsing.

#include <stdexcept>
#include <string>
#include <vector>

namespace dnurbs::tools {

/// A bad command line (unknown flag, missing or malformed argument): exit code 2.
class UsageError : public std::runtime_error {
 public:
  explicit UsageError(const std::string& message) : std::runtime_error(message) {}
};

/// Exit codes of the dnurbs command.
inline constexpr int kExitOk = 0;
inline constexpr int kExitError = 1;  ///< bad input file or failed processing
inline constexpr int kExitUsage = 2;  ///< bad command line

/// True if `arguments` holds -h or --help.
bool wants_help(const std::vector<std::string>& arguments);

/// The value after flag `arguments[index]`, advancing index; throws UsageError if there is none.
const std::string& flag_value(const std::vector<std::string>& arguments, size_t& index);

/// The whole text as a finite double; throws UsageError naming `what` otherwise.
double parse_double(const std::string& text, const std::string& what);

/// The whole text as an integer in minimum..maximum; throws UsageError naming `what` otherwise.
int parse_int(const std::string& text, const std::string& what, int minimum, int maximum);

/// Comma-separated finite doubles ("0.3,0.7"); throws UsageError naming `what` otherwise.
std::vector<double> parse_doubles(const std::string& text, const std::string& what);

/// The text as a JSON string literal (quotes and escapes).
std::string json_string(const std::string& text);

/// The number with 17 significant digits (%.17g), so that it reads back exactly.
std::string json_double(double value);

}  // namespace dnurbs::tools
