#pragma once
// Shape files of triangular NURBS surfaces (Qin & Terzopoulos, "Triangular NURBS and their
// dynamic generalizations", Computer Aided Geometric Design 14, 1997): the triangulation of the
// parametric domain, the degree, the knot clouds, the control points and the weights as JSON.
//
// {"type": "triangular_nurbs", "degree": n,
//  "vertices": [[u, v], ...],                   #V domain vertices
//  "triangles": [[i, j, k], ...],               #T triangles, counter-clockwise
//  "knot_clouds": [[[u, v], ... n knots], ...]  per vertex i the knots t_{i,1..n} (t_{i,0} is
//                                               the vertex itself); optional: absent, the
//                                               standard placement (standard_knot_clouds)
//  "control_points": [[x, y, z], ...],          #T (n + 1)(n + 2) / 2, in the basis numbering:
//                                               triangle I's B-splines I (n+1)(n+2)/2 + b for the
//                                               multi-indices (n,0,0), (n-1,1,0), (n-1,0,1), ...
//  "weights": [w, ...]}                         optional (all 1), one per control point, > 0
//
// Every failure names the source and the JSON path ("tri.json: control_points[4][2]: expected
// a finite number, got string \"a\""); what the library rejects (a clockwise triangle, knot
// clouds that violate the DMS conditions) is wrapped with the key it came from.

#include <filesystem>
#include <string>

#include "dnurbs/io/scene_reader.h"
#include "dnurbs/nurbs/triangular_nurbs_surface.h"

namespace dnurbs {

/// The "type" string of triangular NURBS shape files.
inline constexpr const char* kTriangularShapeType = "triangular_nurbs";

/// Reads a triangular_nurbs object at JSON path `path` (empty: the top level) of a document
/// that `reader` names; throws Error "<source>: <path>.<key>: <what was expected>".
TriangularNurbsSurface read_triangular_shape(const SceneReader& reader, const JsonValue& shape,
                                             const std::string& path);

/// Parses shape JSON text; `source` names it in messages.
TriangularNurbsSurface parse_triangular_shape_json(const std::string& text,
                                                   const std::string& source = "<string>");

/// Reads a shape file; throws Error as parse_triangular_shape_json, or if it cannot be read.
TriangularNurbsSurface read_triangular_shape_file(const std::filesystem::path& path);

/// The surface as JSON text (numbers round-trip exactly; weights omitted when all are 1; the
/// knot clouds always written).
std::string triangular_shape_to_json(const TriangularNurbsSurface& surface);

/// Writes triangular_shape_to_json to a file (through a temporary file and a rename).
void write_triangular_shape_file(const std::filesystem::path& path,
                                 const TriangularNurbsSurface& surface);

/// True if the file holds a JSON object whose "type" is "triangular_nurbs" (for commands that
/// accept every shape file type); false for other types and for files that cannot be read or
/// parsed (the shape's own reader then reports why).
bool is_triangular_shape_file(const std::filesystem::path& path);

}  // namespace dnurbs
