#pragma once
// NURBS curves and surfaces in STEP files (ISO 10303-21 text, AP214 geometry) through Open
// CASCADE's STEP translator: B_SPLINE_CURVE_WITH_KNOTS and B_SPLINE_SURFACE_WITH_KNOTS, rational
// ones with RATIONAL_B_SPLINE_CURVE / _SURFACE weights.

#include <filesystem>
#include <string>
#include <vector>

#include "dnurbs/nurbs/shape.h"

namespace dnurbs {

/// The shapes as STEP text: each surface a face over its whole domain, each curve an edge, all
/// in one shape representation. Reals are written with 17 significant digits, so that knots,
/// weights and control points read back as the same doubles (Open CASCADE's default of 12 would
/// move them by up to 5e-13 relative). Periodic shapes are written in their open form (closed
/// and unclamped, nurbs/periodic_form.h; STEP has no periodic B-spline) and read back periodic.
std::string step_text(const std::vector<Shape>& shapes);

/// Every face and free edge of a STEP file as a NURBS shape (shapes_from_brep: untrimmed faces
/// only, analytic geometry converted exactly). Throws Error naming the file, and the entity
/// ("#123 (StepShape_AdvancedFace)") for one that is trimmed, has no exact NURBS form or cannot
/// be transferred.
std::vector<Shape> read_step_file(const std::filesystem::path& path);

}  // namespace dnurbs
