#pragma once
// Small helpers shared by the dnurbs subcommands: usage errors and argument parsing.

#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

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

/// Prints a JSON document (the output of eval, fit and design) with an indent of 2 and a final
/// line break; numbers are the shortest decimals that read back as the same doubles. Throws
/// Error for a non-finite number (JSON has none), naming its key.
void print_json(std::ostream& out, const nlohmann::ordered_json& document);

}  // namespace dnurbs::tools
