#pragma once
// `dnurbs make KIND OUT.json [--KEY VALUE ...]`: a shape file from a shape recipe
// (io/shape_recipe.h), the same generators scenes reach through a model's "make" key.

#include <ostream>
#include <string>
#include <vector>

namespace dnurbs::tools {

extern const char* const kMakeHelp;

/// Takes the arguments after "make"; writes the shape file and reports it on `out`. Throws
/// UsageError for a bad command line and Error for a recipe a generator rejects.
int make_command(const std::vector<std::string>& arguments, std::ostream& out);

}  // namespace dnurbs::tools
