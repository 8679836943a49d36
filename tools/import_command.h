#pragma once
// `dnurbs import PART OUT.json [--index K]`: the curves and surfaces of a STEP or IGES file
// (io/cad_file.h) or of OBJ free-form geometry (io/obj_freeform.h) as shape files, one per shape.

#include <ostream>
#include <string>
#include <vector>

namespace dnurbs::tools {

extern const char* const kImportHelp;

/// Takes the arguments after "import"; writes OUT.json for a file of one shape (or for shape K
/// with --index K), else OUT-0.json, OUT-1.json, ... beside OUT.json, and reports each on `out`.
/// Throws UsageError for a bad command line and Error for a file that cannot be read.
int import_command(const std::vector<std::string>& arguments, std::ostream& out);

}  // namespace dnurbs::tools
