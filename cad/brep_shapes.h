#pragma once
// NURBS shapes out of, and into, an Open CASCADE boundary representation (TopoDS_Shape): what a
// STEP or IGES file holds once Open CASCADE has read it, and what it writes.

#include <TopoDS_Shape.hxx>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dnurbs/nurbs/shape.h"

namespace dnurbs {

/// The shapes of a boundary representation, faces first (in exploration order), then the
/// edges that bound no face (free curves).
///
/// A face gives its surface over the face's parameter rectangle: a B-spline surface as it is
/// (or its exact segment when the rectangle is smaller than its domain), any other surface of
/// Open CASCADE (plane, cylinder, cone, sphere, torus, revolution, extrusion, Bezier) converted
/// to its exact NURBS form over that rectangle. A face bounded by anything other than the border
/// of its parameter rectangle (a trimming curve, a hole) is refused: dnurbs has no trimmed
/// surfaces. An edge gives its curve over the edge's range, segmented or converted the same way.
/// Edges of zero length (a sphere's poles) are skipped.
///
/// Throws Error "<source>: face K <label> (<Open CASCADE type>): <why>" (or "edge K") for a
/// trimmed face, a surface or curve with no exact NURBS form (an offset surface) or a degree
/// above kMaxDegree; `label`, when given, names the face or edge as its file does ("#123
/// (StepShape_AdvancedFace)").
///
/// `file_geometry`, when given, returns a face's or edge's NURBS geometry as its file holds it
/// (or nothing, to use Open CASCADE's): for readers whose conversion is not exact.
using BrepLabel = std::function<std::string(const TopoDS_Shape&)>;
using BrepGeometry = std::function<std::optional<Shape>(const TopoDS_Shape&)>;
std::vector<Shape> shapes_from_brep(const TopoDS_Shape& brep, const std::string& source,
                                    const BrepLabel& label = {},
                                    const BrepGeometry& file_geometry = {});

/// The shapes as one compound: a face over the whole domain for each surface, an edge over the
/// whole domain for each curve, in order. Periodic shapes stay periodic.
TopoDS_Shape brep_from_shapes(const std::vector<Shape>& shapes);

}  // namespace dnurbs
