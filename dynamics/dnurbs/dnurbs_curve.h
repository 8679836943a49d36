#pragma once
// D-NURBS curves (Terzopoulos 2003, eqs. 1.21-1.26): a NURBS curve whose control points and,
// optionally, weights are the generalized coordinates of a Lagrangian system with the snake energy
// (tension w1, rigidity w2) as its elastic potential.

#include <memory>

#include "dnurbs/dynamics/dnurbs/dnurbs_model.h"
#include "dnurbs/nurbs/nurbs_curve.h"

namespace dnurbs {

/// Material of a D-NURBS curve, per unit parametric length (constants or functions of u.x()).
struct DNurbsCurveMaterial {
  MaterialFunction mass_density = 1.0;     ///< mu (>= 0)
  MaterialFunction damping_density = 0.0;  ///< gamma (>= 0)
  MaterialFunction tension = 0.0;          ///< w1 (>= 0), weight of |x_u|^2
  MaterialFunction rigidity = 0.0;         ///< w2 (>= 0), weight of |x_uu|^2
};

/// A D-NURBS curve as a Model. Coordinates: q = [P_0, P_1, ...] (3 n, fixed weights) or
/// q = [P_0, w_0, P_1, w_1, ...] (4 n, free weights). Matrices are 3n by 3n or 4n by 4n:
///   M = integral mu J^T J du,   D = integral gamma J^T J du             (Terzopoulos 2003,
///   eq. 1.25) K = integral w1 J_u^T J_u + w2 J_uu^T J_uu du                        (Terzopoulos
///   2003, eq. 1.26)
/// Material parameters are u = (u, 0).
class DNurbsCurve : public DNurbsModel {
 public:
  /// Throws Error naming the value for a negative or non-finite material value at a quadrature
  /// point, a weight <= 0 (or below the minimum weight when free) or a bad setting.
  explicit DNurbsCurve(const NurbsCurve& curve, const DNurbsCurveMaterial& material = {},
                       const DNurbsSettings& settings = {});

  std::unique_ptr<Model> clone() const override { return std::make_unique<DNurbsCurve>(*this); }

  /// The NURBS curve at coordinates q.
  NurbsCurve curve(ConstVectorRef q) const;
  /// The curve the model was built from.
  const NurbsCurve& initial_curve() const { return curve_; }

  /// The knot domain [t_p, t_{m-p}], periodic_u for a periodic knot vector.
  ParameterDomain parameter_domain(ConstVectorRef q) const override;
  /// The NURBS curve at q.
  std::optional<Shape> exact_shape(ConstVectorRef q) const override;
  /// Freezes the control points outside sculpted_control_points(initial_curve(), region,
  /// margin) (dynamics/dnurbs/local_sculpting.h).
  int freeze_outside(const SculptedRegion& region, int margin) override;

 private:
  NurbsCurve curve_;
};

}  // namespace dnurbs
