#pragma once
// Knot insertion and knot refinement of NURBS curves and surfaces (Piegl & Tiller, The NURBS
// Book, A5.1 and A5.4), done on homogeneous control points (w P, w) so that rational shapes stay
// exactly the same. Open and periodic knot vectors are both supported.
//
// The file also holds the homogeneous "control rows" view of a curve or of one direction of a
// surface that knot removal and degree elevation share with it.

#include <vector>

#include <Eigen/Core>

#include "dnurbs/nurbs/knot_vector.h"
#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs {

/// Parametric direction of a tensor-product surface.
enum class SurfaceDirection { kU, kV };

/// Control points of a curve, or of a surface seen as a curve along one direction whose
/// "points" are whole rows of the control net.
///
/// `rows` is #control points along the direction by (block_count * block_size). Block b of row i
/// is control point i of the b-th curve: (x, y, z) for a polynomial shape (block_size 3) or the
/// homogeneous (w x, w y, w z, w) for a rational one (block_size 4). A surface along u has one
/// block per v index j (block j of row i is control point (i, j)); along v, one block per u
/// index i (block i of row j is control point (i, j)).
struct ControlRows {
  Eigen::MatrixXd rows;
  int block_size = 3;
  /// Weight shared by every control point of a polynomial shape (block_size 3); unused otherwise.
  double common_weight = 1.0;
};

/// Control rows of a curve: n by 3 (polynomial) or n by 4 (rational, homogeneous).
ControlRows control_rows(const NurbsCurve& curve);
/// Control rows of a surface along `direction`: n_u by 3 n_v (or 4 n_v) along u, n_v by 3 n_u
/// (or 4 n_u) along v.
ControlRows control_rows(const NurbsSurface& surface, SurfaceDirection direction);
/// The curve with knot vector `knots` whose control rows are `rows` (rows.rows.rows() must be
/// knots.control_point_count()). Throws Error if a weight is not positive.
NurbsCurve curve_from_control_rows(KnotVector knots, const ControlRows& rows);
/// The surface that has `knots` along `direction`, the knots of `surface` along the other
/// direction, and control rows `rows` along `direction`.
NurbsSurface surface_from_control_rows(const NurbsSurface& surface, SurfaceDirection direction,
                                       KnotVector knots, const ControlRows& rows);

/// A knot vector with the control rows that go with it (knots.control_point_count() rows).
struct KnotsAndRows {
  KnotVector knots;
  Eigen::MatrixXd rows;
};

/// refine_knots on control rows: `rows` is knots.control_point_count() by #columns (any
/// columns: points, homogeneous points or whole rows of a net). Returns the refined knot vector
/// and rows. Throws Error like refine_knots.
KnotsAndRows refine_control_rows(const KnotVector& knots, const Eigen::MatrixXd& rows,
                                 const std::vector<double>& new_knots);

/// Piegl & Tiller A5.1: inserts the knot u `times` times; the curve does not change.
///
/// Open curves: u must lie in the domain [t_p, t_{m-p}]; the result has n + times control points.
/// Periodic curves: u wraps into the period (KnotVector::wrap_to_period, so the seam given as
/// the period end t_{p+n} is inserted as the knot t_p); the cyclic control polygon of n points gets
/// n + times points (for one insertion the p - 1 points P_{k-p+1}..P_{k-1}, indices mod n, of the
/// span k containing u are replaced by p new ones) and the knot vector is
/// KnotVector::periodic(p, period knots with u inserted).
/// Throws Error naming the value if u is outside the domain (open) or not finite, if times < 1,
/// or if the multiplicity of u would exceed the degree.
NurbsCurve insert_knot(const NurbsCurve& curve, double u, int times = 1);

/// Piegl & Tiller A5.4 (open curves; periodic curves insert one knot at a time): inserts every
/// knot of the non-decreasing list `new_knots` (a knot listed twice is inserted twice).
/// Throws Error naming the value for a decreasing list, a knot outside the domain (open), or a
/// resulting multiplicity above the degree. An empty list returns the curve unchanged.
NurbsCurve refine_knots(const NurbsCurve& curve, const std::vector<double>& new_knots);

/// insert_knot applied to every row (direction kU: to the knots along u of every curve of fixed
/// v index) or every column (kV) of the control net; the surface does not change.
NurbsSurface insert_knot(const NurbsSurface& surface, SurfaceDirection direction, double u,
                         int times = 1);

/// refine_knots applied along `direction` to the whole control net.
NurbsSurface refine_knots(const NurbsSurface& surface, SurfaceDirection direction,
                          const std::vector<double>& new_knots);

}  // namespace dnurbs
