#pragma once
// NURBS curves and surfaces in CAD files: STEP (.step, .stp) and IGES (.iges, .igs), through the
// optional component dnurbs::cad (cad/, built when Open CASCADE is found). Without it every
// function here but cad_format_of throws Error saying how to get it.

#include <filesystem>
#include <optional>
#include <vector>

#include "dnurbs/nurbs/shape.h"

namespace dnurbs {

enum class CadFormat { step, iges };

/// The format named by the path's extension, in any case; nothing for any other extension.
std::optional<CadFormat> cad_format_of(const std::filesystem::path& path);

/// True if this dnurbs was built with STEP and IGES exchange.
bool cad_exchange_available();

/// Every curve and surface of a STEP or IGES file, in file order (cad/step_file.h,
/// cad/iges_file.h). Throws Error naming the file for a missing, oversized or unreadable file,
/// an extension that is neither, a file with no curve or surface, and (naming the entity) a
/// trimmed surface or an entity with no exact NURBS form.
std::vector<Shape> read_cad_file(const std::filesystem::path& path);

/// Writes the shapes (at least one) as a STEP or IGES file by the path's extension, through a
/// temporary file and a rename; knots, weights and control points read back exactly.
void write_cad_file(const std::filesystem::path& path, const std::vector<Shape>& shapes);

}  // namespace dnurbs
