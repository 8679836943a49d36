#pragma once
// Tensor-product D-NURBS surfaces (Terzopoulos 2003, eq. 1.27): control points and, optionally,
// weights are generalized coordinates; the elastic potential is the thin plate under tension
// (Terzopoulos 2003 eq 1.20).

#include <memory>

#include "dnurbs/dynamics/dnurbs/dnurbs_model.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs {

/// Material of a D-NURBS surface, per unit parametric area (constants or functions of (u, v)).
struct DNurbsSurfaceMaterial {
  MaterialFunction mass_density = 1.0;     ///< mu (>= 0)
  MaterialFunction damping_density = 0.0;  ///< gamma (>= 0)
  MaterialFunction a10 = 0.0;              ///< weight of |x_u|^2 (tension along u)
  MaterialFunction a01 = 0.0;              ///< weight of |x_v|^2 (tension along v)
  MaterialFunction b20 = 0.0;              ///< weight of |x_uu|^2 (rigidity)
  MaterialFunction b11 = 0.0;              ///< 2 b11 weighs |x_uv|^2 (twist rigidity)
  MaterialFunction b02 = 0.0;              ///< weight of |x_vv|^2
};

/// A D-NURBS surface as a Model. Control point (i, j) is node i * count_v + j (u index outer,
/// as in NurbsSurface); q = [P_0, P_1, ...] (3 N) or [P_0, w_0, ...] (4 N) for N control points.
///   M = integral mu J^T J du dv,  D = integral gamma J^T J du dv,
///   K = integral a10 Ju^T Ju + a01 Jv^T Jv + b20 Juu^T Juu + 2 b11 Juv^T Juv + b02 Jvv^T Jvv.
class DNurbsSurface : public DNurbsModel {
 public:
  /// Throws Error naming the value for bad material values, weights or settings.
  explicit DNurbsSurface(const NurbsSurface& surface, const DNurbsSurfaceMaterial& material = {},
                         const DNurbsSettings& settings = {});

  std::unique_ptr<Model> clone() const override { return std::make_unique<DNurbsSurface>(*this); }

  /// The NURBS surface at coordinates q.
  NurbsSurface surface(ConstVectorRef q) const;
  const NurbsSurface& initial_surface() const { return surface_; }
  /// Fixes every control point on the border of the control net (i = 0, i = m, j = 0, j = n).
  void fix_border() override;

  /// nurbs_parameter_domain of the surface at q (seams and poles detected).
  ParameterDomain parameter_domain(ConstVectorRef q) const override;
  /// The NURBS surface at q with its exact normals (pole limits included).
  ParametricSurface parametric_surface(ConstVectorRef q) const override;
  /// The NURBS surface at q.
  std::optional<Shape> exact_shape(ConstVectorRef q) const override;
  /// Freezes the control points outside sculpted_control_points(initial_surface(), region,
  /// margin) (dynamics/dnurbs/local_sculpting.h).
  int freeze_outside(const SculptedRegion& region, int margin) override;
  /// S_u, S_v of the NURBS surface at u, their Jacobians with respect to the control points
  /// (and free weights) and Jdot qd (free weights; zero for fixed ones), by nurbs/jacobian.h.
  void tangent_kinematics(ConstVectorRef q, ConstVectorRef qd, const Eigen::Vector2d& u,
                          TangentKinematics& tangents) const override;

 private:
  NurbsSurface surface_;
};

}  // namespace dnurbs
