#pragma once
// `dnurbs eval`: points and derivatives of a shape file at given parameters, as JSON.

#include <ostream>
#include <string>
#include <vector>

namespace dnurbs::tools {

/// Help text of `dnurbs eval` (documents the output format).
extern const char* const kEvalHelp;

/// Runs `dnurbs eval` with the arguments after "eval"; prints the JSON to `out`.
/// Throws UsageError for a bad command line and Error for a bad file or parameter.
int eval_command(const std::vector<std::string>& arguments, std::ostream& out);

}  // namespace dnurbs::tools
