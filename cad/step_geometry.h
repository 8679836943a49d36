#pragma once
// B-spline geometry read straight from STEP entities (ISO 10303-42 B_SPLINE_CURVE_WITH_KNOTS,
// B_SPLINE_SURFACE_WITH_KNOTS and their rational complex forms), for the faces and edges whose
// geometry Open CASCADE 7.6's STEP reader changes: it turns a closed unclamped B-spline into a
// periodic one, and for a seam knot of multiplicity above 1 it numbers the poles from the wrong
// one (a different curve; seen on its own files).

#include <Standard_Handle.hxx>
#include <Standard_Transient.hxx>

#include <optional>

#include "dnurbs/nurbs/shape.h"

namespace dnurbs {

/// The shape held by the B-spline geometry of a STEP face (FACE_SURFACE, ADVANCED_FACE) or edge
/// (EDGE_CURVE, its SURFACE_CURVE or SEAM_CURVE unwrapped to the 3-D curve), or of a curve
/// entity itself (a free curve of a GEOMETRIC_CURVE_SET, a TRIMMED_CURVE unwrapped to its basis
/// curve), exactly as written:
/// knots from the knot list and multiplicities, control points times `length_factor` (the
/// file's length unit in millimetres), weights of a rational complex entity; an open form of a
/// periodic shape (nurbs/periodic_form.h) comes back periodic. Nothing for any other entity or
/// geometry (Open CASCADE's conversion is then exact). Throws Error for data no NURBS can hold
/// (a degree above kMaxDegree, knots that decrease, counts that disagree).
std::optional<Shape> step_bspline_geometry(const Handle(Standard_Transient) & entity,
                                           double length_factor);

}  // namespace dnurbs
