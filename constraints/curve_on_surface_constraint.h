#pragma once
// A curve held on a surface by samples whose surface parameters follow the motion (Terzopoulos
// 2003, eqs. 1.39-1.40): each sample's foot point (u_k, v_k) on the surface is re-found at every
// evaluation as the nearest surface point, so the curve may slide over the surface and only its
// distance from it is constrained. The older curve_on_surface_constraints
// (surface_constraints.h) glues samples to surface points frozen when it is created.
//
// One row per curve parameter t_k: the signed normal distance
//   g_k(q) = n . (c(t_k) - s(u_k, v_k)),  n = (S_u x S_v) / |S_u x S_v| at the foot point,
// whose magnitude is the distance |c - s| when the foot point is interior (then c - s is
// normal to the surface). Derivatives, with r = c - s, w = L_c qd - L_s qd:
//   C_q  = n^T [L_c, -L_s]  (exact, not an approximation: dg = dn.r + n.(dc - ds - S_u du -
//          S_v dv), where n.S_u = n.S_v = 0 and dn.r = g dn.n = 0 since r = g n and |n| = 1;
//          so the foot point's motion drops out at any interior foot point, on or off the
//          surface),
//   Cdot = n . w,
//   sigma = -(ndot.w + n.(Ldot_c qd - Ldot_s qd) - n.(Sdot_u udot + Sdot_v vdot)),
// with Sdot_u = J_u qd and the foot point's velocity from the derivative of the stationarity
// conditions S_u.r = S_v.r = 0:
//   H [udot, vdot]^T = [Sdot_u.r + S_u.w, Sdot_v.r + S_v.w]^T,
//   H = [[S_u.S_u - S_uu.r, S_u.S_v - S_uv.r], [S_u.S_v - S_uv.r, S_v.S_v - S_vv.r]],
// and ndot = (I - n n^T) Ndot / |N|, Ndot = (Sdot_u + S_uu udot + S_uv vdot) x S_v +
// S_u x (Sdot_v + S_uv udot + S_vv vdot).
//
// A foot point on the boundary of an open direction stays there: its parameter in that
// direction is held (udot = 0 or vdot = 0). There the rows above are exact only where the curve
// point lies on the surface (r = 0), because dn.r no longer vanishes; Baumgarte keeps r small.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/constraints/constraint.h"

namespace dnurbs {

/// The curve model `curve_model` held on the surface model `surface_model` at the curve
/// parameters t_k (`curve_parameters`, at least 2, strictly increasing, inside the curve's
/// domain), one row per parameter (see the file comment). Both models need an exact NURBS shape
/// (Model::exact_shape: D-NURBS curves and surfaces). Each evaluation projects every sample onto
/// the surface at the given coordinates (SurfaceProjector: the globally nearest point), so the
/// constraint is a function of q alone and keeps no state between steps. The curve's motion
/// along the surface is free (give it damping). Samples beyond the curve's own freedom normal
/// to the surface (about its control point count) are met by bending the surface to the curve:
/// the rows stay independent but the multipliers grow (examples/scenes/curve_following_sheet,
/// 6 control points: kinetic energy 0.13, 0.17 and 0.39 at t = 0.3 with 6, 8 and 10 samples).
class CurveOnSurfaceConstraint : public Constraint {
 public:
  CurveOnSurfaceConstraint(int curve_model, int surface_model,
                           std::vector<double> curve_parameters);
  std::unique_ptr<Constraint> clone() const override;
  int row_count() const override { return static_cast<int>(curve_parameters_.size()); }
  std::string description() const override;
  void check(const System& system) const override;
  void evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd, double time,
                ConstraintRows& rows) const override;

  int curve_model() const { return curve_model_; }
  int surface_model() const { return surface_model_; }
  const std::vector<double>& curve_parameters() const { return curve_parameters_; }

 private:
  int curve_model_;
  int surface_model_;
  std::vector<double> curve_parameters_;
};

/// A CurveOnSurfaceConstraint at `sample_count` (>= 2) curve parameters spread evenly over the
/// curve's domain, ends included. Throws Error for a model index out of range or a model without
/// the exact shape.
CurveOnSurfaceConstraint evenly_sampled_curve_on_surface(const System& system, int curve_model,
                                                         int surface_model, int sample_count);

/// Signed distances of the curve model's points c(t) at `curve_parameters` (#t) from the surface
/// model, at the system's current state: |c - s| at the nearest surface point s, signed by
/// n.(c - s) (a smooth function of t where the foot points are interior). Returns #t values.
Eigen::VectorXd curve_to_surface_distances(const System& system, int curve_model, int surface_model,
                                           const std::vector<double>& curve_parameters);

}  // namespace dnurbs
