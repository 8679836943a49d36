#pragma once
// `dnurbs info`: what a scene holds and what a step of it costs.

#include <ostream>
#include <string>
#include <vector>

namespace dnurbs::tools {

extern const char* const kInfoHelp;

/// Takes the arguments after "info"; prints the report to `out`. Throws UsageError for a bad
/// command line and Error for a bad scene.
int info_command(const std::vector<std::string>& arguments, std::ostream& out);

}  // namespace dnurbs::tools
