#pragma once
// Triangular D-NURBS surfaces (Qin & Terzopoulos, "Triangular NURBS and their dynamic
// generalizations", Computer Aided Geometric Design 14, 1997): a triangular NURBS surface over
// an arbitrary triangulated parametric domain whose control points and, optionally, weights are
// the generalized coordinates of Lagrangian dynamics,
//
//   M qdd + D qd + K q = f_q + g,
//   M = integral mu J^T J,  D = integral gamma J^T J,
//   K = integral a10 Ju^T Ju + a01 Jv^T Jv + b20 Juu^T Juu + 2 b11 Juv^T Juv + b02 Jvv^T Jvv,
//   f_q = integral J^T f,   g = -integral mu J^T Jdot qd   (free weights only),
//
// the thin plate under tension of the tensor-product D-NURBS (Terzopoulos, "Deformable models:
// classic, topology-adaptive and generalized formulations", eq. 1.20; Qin & Terzopoulos,
// "D-NURBS: a physics-based framework for geometric design", IEEE TVCG 2(1) 1996) with the
// integrals taken over the triangulated domain by Dunavant rules (triangular_quadrature.h).
//
// Fixed weights (the default): J does not depend on q and M = S_M (x) I_3 (likewise D, K),
// assembled once. Free weights: q = [P_0, w_0, P_1, w_1, ...] and M, D, K are re-assembled at
// every state from the cached B-spline values, into a pattern sized once; the weight gauge,
// the minimum weight and the weight inertia work as for the tensor-product model
// (dynamics/dnurbs_model.h).
//
// Plate theory: with a10 = a01 = 0 and b20 = b02 = b11 = D the energy of the normal
// displacement w is (D / 2) integral w_uu^2 + 2 w_uv^2 + w_vv^2, Kirchhoff's plate energy for
// Poisson's ratio 0, whose Euler-Lagrange equation is D Laplacian^2 w = q (the biharmonic
// plate). The Poisson term is a null Lagrangian for clamped edges and does not change the
// moment condition w_nn = 0 of a straight simply supported edge, so the clamped and simply
// supported plates of any Poisson ratio are reproduced.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dnurbs/dynamics/core/quadrature_assembly.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/dnurbs/rational_control_net_model.h"
#include "dnurbs/dynamics/triangular/triangular_quadrature.h"
#include "dnurbs/nurbs/jacobian.h"
#include "dnurbs/nurbs/triangular_nurbs_surface.h"

namespace dnurbs {

/// Settings of a triangular D-NURBS surface.
struct TriangularDNurbsSettings {
  /// Control points only (q = [P_0, P_1, ...]) or control points and weights
  /// (q = [P_0, w_0, P_1, w_1, ...]).
  WeightMode weight_mode = WeightMode::kFixed;
  /// Degree of the Dunavant rule (1..14); 0 picks 2n, which with exact cells makes M, D, K and
  /// forces of constant densities exact for non-rational surfaces (for rational ones the
  /// integrands are rational and the degree is an accuracy knob).
  int quadrature_degree = 0;
  /// 0 (the default): the rule on the polynomial cells of every domain triangle (exact, see
  /// triangular_quadrature.h); s >= 1: a composite rule on s^2 sub-triangles per domain triangle,
  /// which ignores the knot segments (relative error of K about 0.1 at s = 8 for degree 2).
  int quadrature_subdivisions = 0;
  /// Free weights: lower bound, gauge and inertia as DNurbsSettings.
  double minimum_weight = 1e-3;
  bool fix_weight_gauge = true;
  double weight_inertia = 0.0;
  /// Model::tessellate when the caller asks for no adaptive mesh (its max_error is 0):
  /// `tessellation_max_error` > 0 gives the adaptive mesh with that chord error and at most
  /// `tessellation_max_level` bisections (1..40); otherwise the uniform mesh with
  /// `tessellation_subdivisions` (1..1024) per domain triangle, or with 0 (the default) the
  /// fewest that make every mesh edge at most (domain width) / segments along u and v.
  int tessellation_subdivisions = 0;
  double tessellation_max_error = 0.0;
  int tessellation_max_level = 20;
  /// Measure the energy from the initial shape (set_rest_shape with the initial coordinates,
  /// rational_control_net_model.h), so that the shape as built is at rest.
  bool initial_shape_at_rest = false;
  /// A rest shape that yields (dynamics/core/plastic_flow.h), so a push leaves a dent. Implies a
  /// rest shape (the initial shape unless set_rest_shape moves it).
  std::optional<PlasticFlow> plastic_flow;
};

/// A triangular D-NURBS surface as a Model. Control point a belongs to B-spline a of the basis
/// (TriangularBSplineBasis numbering). The material (per unit parametric area) is that of the
/// tensor-product D-NURBS surface.
class TriangularDNurbsSurface : public RationalControlNetModel {
 public:
  /// Throws Error naming the value for bad material values, weights or settings.
  explicit TriangularDNurbsSurface(const TriangularNurbsSurface& surface,
                                   const DNurbsSurfaceMaterial& material = {},
                                   const TriangularDNurbsSettings& settings = {});

  std::unique_ptr<Model> clone() const override;
  int parametric_dimension() const override { return 2; }

  /// Fixed weights: -K (q - q_r) with the constant K (q_r = 0 without a rest shape); free
  /// weights: -integral sum_alpha k_alpha J_alpha^T (x^alpha - x^alpha_rest) by the Dunavant
  /// rule on every polynomial cell (rational_control_net_model.h, "Rest shape").
  void add_internal_force(ConstVectorRef q, VectorRef force) const override;
  /// g = -integral mu J^T Jdot qd (free weights; nothing for fixed weights).
  void add_inertial_force(ConstVectorRef q, ConstVectorRef qd, VectorRef force) const override;
  /// integral J^T f(u) over the triangulated domain, f per unit parametric area, by the
  /// model's quadrature (the sample's tangents are x_u and x_v).
  void add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                             VectorRef force) const override;

  /// The triangular NURBS surface at q.
  TriangularNurbsSurface surface(ConstVectorRef q) const;
  /// The bounding box of the triangulated domain (no periodic direction, no pole). A parameter
  /// in it lies in the domain only where the triangulation covers the box.
  ParameterDomain parameter_domain(ConstVectorRef q) const override;
  /// A domain that fills its bounding box (a rectangle, within 1e-12 of its area): the surface
  /// at q over parameter_domain(q) with the exact normals (x_u x x_v) / |x_u x x_v|. Any other
  /// domain (an L-shape, a hole) has no rectangular parameterization: throws Error.
  ParametricSurface parametric_surface(ConstVectorRef q) const override;
  /// The mesh of the surface at q (triangular_tessellation.h), with domain parameters as uv:
  /// settings.max_error > 0 gives the adaptive mesh (chord error, settings.max_level
  /// bisections), else the model's tessellation settings decide (TriangularDNurbsSettings).
  TriangleMesh tessellate(ConstVectorRef q, const ModelTessellationSettings& settings,
                          std::string name) const override;
  /// S_u = x_u and S_v = x_v at u with their Jacobians (R^u_a I_3, R^v_a I_3 and, with free
  /// weights, the weight columns E^u_a, E^v_a, for every B-spline listed at u), their rates and,
  /// with free weights, Jdot qd: the second derivatives of x_u, x_v along qd from the
  /// homogeneous forms A = x W (Piegl & Tiller, The NURBS Book, eq. 4.8 differentiated).
  void tangent_kinematics(ConstVectorRef q, ConstVectorRef qd, const Eigen::Vector2d& u,
                          TangentKinematics& tangents) const override;
  /// Fixes the control points of border_control_points (triangular_local_sculpting.h): every
  /// B-spline whose trace on the boundary is not zero, so that the border curve cannot move
  /// (free weights stay free). The exact clamped and simply supported conditions of
  /// triangular_boundary_conditions.h constrain combinations and are not coordinate fixes.
  void fix_border() override;
  /// Fixes every control point outside triangular_sculpted_control_points(region, margin) and
  /// returns how many were frozen.
  int freeze_outside(const SculptedRegion& region, int margin) override;

  const TriangularNurbsSurface& initial_surface() const { return surface_; }
  const TriangularQuadrature& quadrature() const { return *quadrature_; }
  /// Area of the parametric domain.
  double parametric_measure() const;

 private:
  // Material at point p: material_[p * kMaterialStride + 0] = mu, [+1] = gamma,
  // [+1 + alpha] = k_alpha (alpha = 1..5).
  static constexpr int kMaterialStride = 7;

  TriangularControlNet control_net(const ConstVectorRef& q) const;
  const double* material_at(int p) const {
    return &material_[static_cast<size_t>(p) * kMaterialStride];
  }
  int stiffness_order() const;
  // Calls visit(p, values, jacobian, local) at every quadrature point p of element e (or of all
  // elements) with the cached B-splines and the rational Jacobian of quantities up to `order`.
  template <typename Visit>
  void for_each_point_of(int e, const TriangularControlNet& net, int order, bool weight_columns,
                         Visit&& visit) const;
  template <typename Visit>
  void for_each_point(const TriangularControlNet& net, int order, bool weight_columns,
                      Visit&& visit) const;
  // The rational basis at u (the B-splines listed for the domain triangle containing u; throws
  // Error for u outside the triangulated domain).
  void visit_rational_point(ConstVectorRef q, const Eigen::Vector2d& u, bool weight_columns,
                            const std::function<void(const RationalPoint&)>& visit) const override;
  // The B-splines and the rational Jacobian at an arbitrary parameter.
  void jacobian_at(const Eigen::Vector2d& u, const TriangularControlNet& net, int order,
                   bool weight_columns, TriangularRationalJacobian& jacobian,
                   TriangularBasisValues& values) const;
  void assemble_scalar(ModelMatrices& scalar) const override;
  // E = (1/2) integral sum_alpha k_alpha |x^alpha - x^alpha_rest|^2 over the triangulated
  // domain.
  double quadrature_potential_energy(ConstVectorRef q) const override;
  void store_rest_derivatives(ConstVectorRef q_rest) override;
  // x^alpha - x^alpha_rest of quantity alpha (1..5) at quadrature point p (x^alpha without a
  // rest shape).
  Eigen::Vector3d rest_difference(int p, const TriangularRationalJacobian& jacobian,
                                  int alpha) const;
  void assemble_free(ConstVectorRef q, ModelMatrices& matrices) const override;

  TriangularNurbsSurface surface_;
  TriangularDNurbsSettings settings_;
  std::shared_ptr<const TriangularQuadrature> quadrature_;  // immutable, shared by clones
  bool has_damping_ = false;
  std::array<bool, 6> has_stiffness_{};
  std::vector<double> material_;
  AssemblyPattern pattern_;
  // The rest shape: x^alpha(q_r), alpha = 1..5, at every quadrature point (kRestStride doubles
  // per point, alpha 1 first), empty without one.
  static constexpr int kRestStride = 15;
  std::vector<double> rest_derivatives_;
};

}  // namespace dnurbs
