#pragma once
// Swung NURBS surfaces (Woodward, Cross-sectional design of B-spline surfaces, Computers &
// Graphics 11(2) 1987; Qin & Terzopoulos, Dynamic NURBS swung surfaces for physics-based shape
// design, CAD 27(2) 1995): a profile curve p(u) in the xz plane swung along a trajectory curve
// t(v) in the xy plane,
//
//   s(u, v) = (alpha p_x(u) t_x(v), alpha p_x(u) t_y(v), p_z(u)).
//
// With a circle as trajectory this is a surface of revolution; other trajectories give
// non-circular cross sections scaled by the profile. Both curves are NURBS, open or periodic.

#include <Eigen/Core>

#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs {

/// A swung surface s(u, v) = (alpha p_x(u) t_x(v), alpha p_x(u) t_y(v), p_z(u)).
///
/// Storage of the planar curves: both are NurbsCurve (3-D) whose off-plane coordinate is exactly
/// zero, checked at construction: every control point of the profile has y = 0 (the curve lies
/// in the xz plane), every control point of the trajectory has z = 0 (the xy plane). u is the
/// profile's parameter, v the trajectory's; a periodic curve makes the surface closed in that
/// direction (a periodic trajectory: closed around the axis, a periodic profile: a torus).
/// A swung surface is a value: copy it freely.
class SwungSurface {
 public:
  /// Throws Error naming the control point and value if the profile leaves the xz plane or the
  /// trajectory the xy plane, and naming alpha if it is zero or not finite.
  SwungSurface(NurbsCurve profile, NurbsCurve trajectory, double alpha = 1.0);

  /// The profile p(u) in the xz plane (y = 0) and the trajectory t(v) in the xy plane (z = 0).
  const NurbsCurve& profile() const { return profile_; }
  const NurbsCurve& trajectory() const { return trajectory_; }
  /// The constant scale of the swing (a shape constant, not a coordinate).
  double alpha() const { return alpha_; }

  /// Parametric domains: [u_start, u_end] of the profile, [v_start, v_end] of the trajectory.
  double u_start() const { return profile_.knots().domain_start(); }
  double u_end() const { return profile_.knots().domain_end(); }
  double v_start() const { return trajectory_.knots().domain_start(); }
  double v_end() const { return trajectory_.knots().domain_end(); }

  Eigen::Vector3d point(double u, double v) const;
  /// S^(k,l) = d^(k+l) s / du^k dv^l for k + l <= order (order 0..kMaxDerivativeOrder):
  ///   S^(k,l) = (alpha p_x^(k) t_x^(l), alpha p_x^(k) t_y^(l), [l == 0] p_z^(k)).
  void derivatives(double u, double v, int order, SurfaceDerivatives& result) const;
  SurfaceDerivatives derivatives(double u, double v, int order) const;

  /// Unit normal (S_u x S_v)/|S_u x S_v|. Since S_u x S_v = alpha p_x m with
  ///   m = (-p_z' t_y', p_z' t_x', alpha p_x' (t_x t_y' - t_y t_x')),
  /// the normal is sign(alpha p_x) m/|m|, which stays defined where the profile meets the axis
  /// (p_x = 0, a collapsed pole like a sphere's): there the sign is the limit from inside the
  /// domain, sign(alpha p_x') (and its opposite at the end of the profile's domain), as
  /// NurbsSurface::unit_normal does. Throws Error where m vanishes or p_x = p_x' = 0.
  Eigen::Vector3d unit_normal(double u, double v) const;

  /// The same surface as a tensor-product NURBS: degrees and knots of the profile (u) and the
  /// trajectory (v), control point (i, j) = (alpha X_i T_j.x, alpha X_i T_j.y, Z_i) and weight
  /// w_i W_j for profile control points (X_i, 0, Z_i) with weights w_i and trajectory control
  /// points T_j with weights W_j. It is exact: the tensor-product numerator is
  /// (alpha A_x(u) B(v), A_z(u) W(v)) and its denominator w(u) W(v), with A, w (B, W) the
  /// homogeneous numerator and denominator of the profile (trajectory).
  NurbsSurface to_nurbs_surface() const;

 private:
  NurbsCurve profile_;
  NurbsCurve trajectory_;
  double alpha_ = 1.0;
};

}  // namespace dnurbs
