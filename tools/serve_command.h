#pragma once
// `dnurbs serve`: interactive sculpting in the browser (docs/serve.md). Runs a scene (or the
// built-in sculpting demo) and serves the sculpting page and its WebSocket until SIGINT/SIGTERM.

#include <ostream>
#include <string>
#include <vector>

namespace dnurbs::tools {

extern const char* const kServeHelp;

/// Takes the arguments after "serve". Prints the address it listens on as its first line to
/// `out`, then serves until SIGINT or SIGTERM; returns 0. Throws UsageError for a bad command
/// line and Error for a bad scene or an address it cannot bind.
int serve_command(const std::vector<std::string>& arguments, std::ostream& out);

}  // namespace dnurbs::tools
