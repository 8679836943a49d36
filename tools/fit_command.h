#pragma once
// `dnurbs fit`: fit a superquadric or a D-NURBS surface to points from a file or a mesh.

#include <ostream>
#include <string>
#include <vector>

namespace dnurbs::tools {

extern const char* const kFitHelp;

/// Takes the arguments after "fit"; prints the fitted shape and its errors as JSON to `out`, and
/// the surface fit's progress to `err` (unless --quiet).
/// Throws UsageError for a bad command line and Error for bad data.
int fit_command(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err);

}  // namespace dnurbs::tools
