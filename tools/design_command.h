#pragma once
// `dnurbs design`: the static, energy-minimizing shape of a scene's models under its forces and
// constraints (design/energy_minimization.h), written as shape files and an OBJ mesh.

#include <ostream>
#include <string>
#include <vector>

namespace dnurbs::tools {

extern const char* const kDesignHelp;

/// Takes the arguments after "design"; prints the iterations, energy, constraint violation,
/// NLopt status and written files as JSON to `out`, and the progress (evaluations, their rate and
/// the energy) to `err` unless --quiet. Returns kExitError if NLopt failed. Throws
/// UsageError for a bad command line and Error for a bad scene or a failed write.
int design_command(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err);

}  // namespace dnurbs::tools
