#pragma once
// Shape generators for sculpting: straight rods and flat sheets whose control points sit at the
// Greville abscissae, an exact box, cylinder and cone, surfaces of revolution by any angle,
// extrusions, lofts through section curves and span splitting.
//
// The rods and sheets are linear in their parameters, C(u) = start + u t and S(u, v) = origin +
// u e_1 + v e_2, because a B-spline with control values at the Greville abscissae reproduces the
// identity (Piegl & Tiller, The NURBS Book, 2nd ed. 1997, the linear precision of B-splines;
// de Boor, A Practical Guide to Splines, 1978, ch. IX). So the D-NURBS stretching and bending
// energies (Qin & Terzopoulos 1996; Terzopoulos 2003, eq. 1.20) pull on no control point away
// from the border: with the border clamped the shape is at rest. Evenly spaced control points
// over knots with interior values are not linear in u, and such a sheet first slides in its plane.
// Every generated shape, curved ones included, is at rest with itself as the rest shape
// (DNurbsSettings::initial_shape_at_rest, dynamics/dnurbs/dnurbs_model.h).
//
// Shapes with interior knots have them uniformly spaced; the parameter of a rod or sheet is the
// distance along it. The revolved shapes follow the orientation of surface_of_revolution
// (primitive_shapes.h): u along the profile, v counter-clockwise about +z.

#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs {

/// The Greville abscissae xi_i = (t_{i+1} + ... + t_{i+p}) / p, i = 0..n-1, of an open knot
/// vector (n control points, degree p): sum_i xi_i N_{i,p}(u) = u on the domain. Throws Error
/// for a periodic knot vector.
std::vector<double> greville_abscissae(const KnotVector& knots);

/// A straight rod from `start` to `end` (distinct): `control_points` control points (>= degree +
/// 1) of degree `degree` (1..kMaxDegree) at the Greville abscissae of clamped uniform knots over
/// the parameter domain [0, D], so that C(u) = start + (u / D) (end - start). D is `domain` (> 0)
/// or, when not given, the length |end - start| (a parameter is then the distance along the
/// rod). Throws Error naming the value for a bad count, degree, length or domain.
NurbsCurve greville_line(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                         int control_points, int degree,
                         std::optional<double> domain = std::nullopt);

/// The straight profile of a revolved or swung shape, from (x0, 0, z0) to (x1, 0, z1):
/// greville_line with `count` (>= 2) control points of degree min(3, count - 1) over the
/// parameter domain [0, domain] (default: its length). Throws Error naming a bad count.
NurbsCurve straight_profile(double x0, double z0, double x1, double z1, int count,
                            std::optional<double> domain = std::nullopt);

/// A flat sheet S(u, v) = origin + (u size_x / D_x, v size_y / D_y, 0) over the parameter domain
/// [0, D_x] x [0, D_y] (`domain`, or `size` when not given, so that S = origin + (u, v, 0)):
/// control points (control_points.x() along u, .y() along v, each >= degree + 1) at the Greville
/// abscissae of clamped uniform knots of degrees `degree`. Control point (i, j) has index
/// i n_v + j.
NurbsSurface greville_plane(const Eigen::Vector2d& size, const Eigen::Vector2i& control_points,
                            const Eigen::Vector2i& degree,
                            const Eigen::Vector3d& origin = Eigen::Vector3d::Zero(),
                            const std::optional<Eigen::Vector2d>& domain = std::nullopt);

/// The closed surface of an axis-aligned box of edge lengths `size` (all > 0) standing on the
/// plane z = 0, centred on the z axis: bilinear, 4 x 5 control points. u runs from the centre of
/// the bottom face out to its border (u in [0, 1]), up a side face ([1, 2]) and in over the top
/// face ([2, 3]); v runs once around the square section ([0, 4], one unit per side, from the
/// corner (+x, +y)). The first and last rows collapse to the face centres, like a sphere's poles.
NurbsSurface box(const Eigen::Vector3d& size);

/// The open cylinder of radius r and height h about the z axis, standing on z = 0: a straight
/// profile (greville_line of `profile_control_points` and degree min(3, count - 1)) revolved with
/// the rational quadratic circle. Exact: every point is at distance r from the axis.
NurbsSurface cylinder(double radius, double height, int profile_control_points = 4);

/// The cone of base radius r on z = 0 and apex (0, 0, h), without its base disc; as cylinder.
NurbsSurface cone(double radius, double height, int profile_control_points = 4);

/// `profile` (an open curve, u direction) revolved about the z axis by `angle` radians, 0 <
/// angle <= 2 pi, counter-clockwise (v direction): ceil(angle / (pi / 2)) rational quadratic arcs
/// (Piegl & Tiller, A7.1 and A8.1), knots over [0, 1]. The full turn is surface_of_revolution.
/// Points of the profile keep their distance to the axis and their height exactly.
NurbsSurface revolve(const NurbsCurve& profile, double angle);

/// `curve` (u) swept along `direction` (v, non-zero): S(u, v) = C(u) + v d / |d| for v in
/// [0, |d|], degree 1 in v, weights of the curve on both rows. Periodic curves give a tube.
NurbsSurface extrude(const NurbsCurve& curve, const Eigen::Vector3d& direction);

/// The skinned surface through the section curves (u, in order along v): the sections are made
/// compatible (their domains mapped onto the first one's, degrees raised to the highest, knot
/// vectors merged; Piegl & Tiller, section 10.3), then every column of homogeneous control points
/// (w P, w) is interpolated along v at the averaged chord-length parameters of the sections,
/// scaled to [0, 1], by a clamped B-spline of degree min(degree_v, count - 1) with averaged knots
/// (Piegl & Tiller, eqs. 9.5, 9.8). S(u, v_k) is section k for every u. At least two open
/// sections; throws Error naming the section for a periodic or a bad one. When
/// `section_parameters` is given it receives v_k of every section. A loft that would have more
/// than `max_control_points` control points (merged knots times sections) is refused before
/// the sections are refined.
NurbsSurface loft(const std::vector<NurbsCurve>& sections, int degree_v = 3,
                  std::vector<double>* section_parameters = nullptr,
                  long long max_control_points = std::numeric_limits<long long>::max());

/// The same surface with every non-empty knot span split into `parts.x()` (u) and `parts.y()`
/// (v) equal spans by knot insertion (parts >= 1): more control points, the same geometry and
/// parametrization, so a shape at rest stays at rest.
NurbsSurface split_spans(const NurbsSurface& surface, const Eigen::Vector2i& parts);

/// The same for a curve.
NurbsCurve split_spans(const NurbsCurve& curve, int parts);

}  // namespace dnurbs
