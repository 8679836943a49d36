#pragma once
// Small helpers shared by the dnurbs subcommands: usage errors and the command-line parsing of
// every subcommand with CLI11 (Debian's libcli11-dev, header-only).

#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
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

/// Parses `arguments` (the words after the command's name) into the options and positionals a
/// command added to `app` with CLI11 (typed values, checks, repeated and missing options).
/// Returns false after writing the command's `help` text to `out` for -h or --help, which wins
/// over any error in the rest of the line; throws UsageError with CLI11's message, which names
/// the option and the value, for a bad command line.
bool parse_command_line(CLI::App& app, const std::vector<std::string>& arguments, const char* help,
                        std::ostream& out);

/// A CLI11 transform (Option::transform, which may rewrite the value) that checks that an
/// option's value is a decimal integer in minimum..maximum and hands it on in decimal: "010"
/// is 10, not CLI11's octal 8.
CLI::Validator integer_in(int minimum, int maximum);

/// A CLI11 check that an option's value is a finite number (CLI11 reads "nan" and "inf").
const CLI::Validator& finite_number();

/// A CLI11 check that an option's value is a finite number > 0 and at most `maximum`.
CLI::Validator positive_number(double maximum = std::numeric_limits<double>::max());

/// Comma-separated finite doubles ("0.3,0.7"); throws UsageError naming `what` otherwise.
std::vector<double> parse_doubles(const std::string& text, const std::string& what);

/// Prints a JSON document (the output of eval, fit and design) with an indent of 2 and a final
/// line break; numbers are the shortest decimals that read back as the same doubles. Throws
/// Error for a non-finite number (JSON has none), naming its key.
void print_json(std::ostream& out, const nlohmann::ordered_json& document);

}  // namespace dnurbs::tools
