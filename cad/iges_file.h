#pragma once
// NURBS curves and surfaces in IGES 5.3 files through Open CASCADE's IGES translator: rational
// B-spline curves (entity 126) and surfaces (entity 128).

#include <filesystem>
#include <string>
#include <vector>

#include "dnurbs/nurbs/shape.h"

namespace dnurbs {

/// The shapes as IGES text, each a bare entity 126 or 128 over its whole domain, reals with 17
/// significant digits (Open CASCADE's default of 10 would move them by up to 5e-11 relative).
/// Periodic shapes are written in their open form (closed, unclamped; nurbs/periodic_form.h)
/// and read back periodic.
std::string iges_text(const std::vector<Shape>& shapes);

/// Every shape of an IGES file. Entities 126 and 128 that are roots of the file are read as
/// they are (their knots, weights and control points, with the entity's transformation
/// applied; a curve's parameter range short of its knot vector's domain gives the exact segment,
/// a surface's is refused as trimmed); any
/// other root goes through Open CASCADE's transfer and shapes_from_brep (faces of trimmed
/// surfaces, entities 144 and 143, are refused unless their boundary is the border of the
/// parameter rectangle). Throws Error naming the file, and the entity ("D45
/// (IGESGeom_TrimmedSurface)") for one that is refused.
std::vector<Shape> read_iges_file(const std::filesystem::path& path);

}  // namespace dnurbs
