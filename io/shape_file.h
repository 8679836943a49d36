#pragma once
// Shape files: one NURBS curve or surface as JSON.
//
// Curve:   {"type": "nurbs_curve", "degree": p, "knots": [...], "control_points": [[x, y, z], ...],
//           "weights": [...], "periodic": false}
// Surface: {"type": "nurbs_surface", "degree_u": p, "degree_v": q, "knots_u": [...],
//           "knots_v": [...], "control_points": [[[x, y, z], ...], ...], "weights": [[...], ...],
//           "periodic_u": false, "periodic_v": false}
//
// The surface's outer arrays run along u: control_points[i][j] is control point (i, j).
// "weights" is optional (all 1). With "periodic": true (or "periodic_u"/"periodic_v") the knots
// are one period's knots t_p..t_{p+n} (KnotVector::periodic) and the control points the n
// distinct ones; otherwise the knots are the whole open vector (n + p + 1 values).

#include <filesystem>
#include <string>

#include "dnurbs/nurbs/shape.h"

namespace dnurbs {

/// Parses shape JSON text. `source` names the text in messages (usually the file name).
/// Throws Error "<source>: <json path>: <what was expected>" for unparseable JSON (with line and
/// column), a missing, unknown or mistyped key, a non-finite or non-numeric number, ragged
/// arrays, counts that do not match the degree and knots, weights <= 0, and (wrapped, with the
/// key) every knot or weight error of the library.
Shape parse_shape_json(const std::string& text, const std::string& source = "<string>");

/// Reads a shape file; throws Error as parse_shape_json does, or if the file cannot be read. A
/// file of exchange_shapes (STEP, IGES, OBJ free-form) holding exactly one curve or surface
/// reads as that shape; one holding several is refused, naming the count.
Shape read_shape_file(const std::filesystem::path& path);

/// Every curve and surface of an exchange file, by its extension: STEP or IGES (.step, .stp,
/// .iges, .igs; io/cad_file.h) or OBJ free-form geometry (.obj; io/obj_freeform.h), or the one
/// shape of a shape file (any other extension). Throws Error naming the file if it holds none.
std::vector<Shape> read_exchange_shapes(const std::filesystem::path& path);

/// One line for people: "nurbs_surface, 9 x 7 control points, degrees 3 x 2" or "nurbs_curve,
/// 8 control points, degree 3", with ", rational" and ", periodic" (", periodic in u") when so.
std::string shape_summary(const Shape& shape);

/// The shape as JSON text (numbers round-trip exactly; weights are omitted when all are 1).
std::string shape_to_json(const Shape& shape);

/// Writes shape_to_json to a file (through a temporary file and a rename); throws Error if that
/// fails.
void write_shape_file(const std::filesystem::path& path, const Shape& shape);

}  // namespace dnurbs
