#pragma once
// NURBS curves and surfaces as Wavefront OBJ free-form geometry (Wavefront OBJ, Appendix B1,
// "Specifying free-form curves/surfaces": the cstype and deg attribute statements, the curv and
// surf element statements, the parm and end body statements, and the v vertex statement).
//
// A cubic B-spline curve through four vertices and a rational biquadratic surface:
//
//   v x y z            # geometric vertex; rational shapes give the weight as a 4th value w
//   ...
//   cstype bspline     # or "cstype rat bspline"
//   deg 3              # "deg p q" for surfaces
//   curv u0 u1 1 2 3 4
//   parm u t0 t1 ... t7
//   end
//
//   cstype rat bspline
//   deg 2 2
//   surf s0 s1 t0 t1 -9 -8 -7 -6 -5 -4 -3 -2 -1
//   parm u ...
//   parm v ...
//   end
//
// Vertex references are 1-based, or negative and relative (-1 is the last v before the
// statement). parm holds the whole knot vector (control points + degree + 1 knots), and the
// curv/surf parameter range is its domain [t_p, t_{m-p}]. A surface lists its control vertices
// with u varying fastest (Appendix B1, "Mathematics for free-form curves/surfaces", "Surface
// vertex data": i = 0..K1 for j = 0, then i = 0..K1 for j = 1, ...), where dnurbs stores control
// point (i, j) at row i * n_v + j.

#include <filesystem>
#include <string>
#include <vector>

#include "dnurbs/nurbs/shape.h"

namespace dnurbs {

/// The most vertices (curv, surf) or knots (parm) one statement may hold.
inline constexpr int kObjMaxValues = 10'000'000;

/// The shapes as OBJ free-form text. Each shape gets its own block of `v x y z [w]` lines (w
/// only for rational shapes, NurbsCurve::is_rational), then `cstype [rat] bspline`, `deg p` or
/// `deg p q`, `curv u0 u1 v...` or `surf s0 s1 t0 t1 v...` with absolute 1-based vertex indices
/// (a surface's n_u x n_v control points with u varying fastest), `parm u ...` (and `parm v ...`)
/// with the whole knot vector, and `end`. Periodic shapes are written in their open form
/// (nurbs/periodic_form.h), since OBJ has no periodic knot vectors. Numbers are written in
/// their shortest form that reads back as the same double, so knots, control points and weights
/// round-trip exactly; a non-rational shape whose weights are all equal but not 1 reads back
/// with weights 1 (the same shape).
std::string shapes_to_obj(const std::vector<Shape>& shapes);

/// Writes shapes_to_obj to a file (through a temporary file and a rename); throws Error if that
/// fails.
void write_obj_freeform_file(const std::filesystem::path& path, const std::vector<Shape>& shapes);

/// The shapes of OBJ text: every curv (3-D curve) and surf statement with cstype bspline or
/// rat bspline becomes a Shape, in file order; shapes in the open form of a periodic shape come
/// back periodic (periodic_form). Weights are the vertices' w (1 when absent) for rat bspline
/// shapes and 1 otherwise, as the specification says. Polygonal and other statements (f, l, p,
/// vt, vn, g, o, s, mtllib, usemtl, ctech, ...) are ignored, so a file with meshes and free-form
/// geometry reads fine; so are body statements outside a curv/surf block (Appendix B1: "they do
/// not have any effect"). A line ending in a backslash continues on the next one; '#' starts a
/// comment. A v line holds x y z, x y z w, or x y z r g b (the vertex colour extension, w = 1).
///
/// Throws Error "<source>: line L: <what>" naming the value for: a malformed or non-finite
/// number; a weight <= 0; a cstype other than bspline and rat bspline (bezier, cardinal, taylor
/// and bmatrix are refused by name); a curv or surf without cstype, or without deg (two degrees
/// for a surf), or with a degree outside 1..kMaxDegree; a vertex index that is 0 or not that of
/// a v line before the statement; a curv/surf without parm u (parm v) or end, or with another
/// curv/surf before its end; a knot count other than control points + degree + 1 in each
/// direction and every knot vector error of KnotVector; a curv/surf parameter range other than
/// the knot vector's domain (to 1e-12 relative: a sub-range would be a trimmed shape, which is
/// not supported); trim, hole, scrv and sp statements in a block (trimmed surfaces are not
/// supported); curv2 (2-D curves); more than kObjMaxValues vertices or knots in one statement.
std::vector<Shape> parse_obj_freeform(const std::string& text,
                                      const std::string& source = "<string>");

/// Reads an OBJ file's free-form shapes; throws Error as parse_obj_freeform does, or if the file
/// cannot be read (core/input_file.h).
std::vector<Shape> read_obj_freeform_file(const std::filesystem::path& path);

/// True if the text has at least one curv or surf statement.
bool has_obj_freeform(const std::string& text);

}  // namespace dnurbs
