#pragma once
// The D-NURBS model shared by curves and surfaces (Terzopoulos 2003, eqs. 1.21-1.27): generalized
// coordinates are the control points and, when freed, the weights; M, D and K are Gauss
// quadrature sums over the non-empty knot spans (span products for surfaces) of J^T J terms.
//
// Fixed weights (the default): J does not depend on q, M = S_M (x) I_3 (likewise D, K), and the
// scalar matrices are assembled once at construction. Free weights: the B-spline basis values
// at the quadrature points are cached once (they do not depend on q) and M, D, K are
// re-assembled from that cache at every state into a pattern sized once.

#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/material_function.h"
#include "dnurbs/dynamics/core/plastic_flow.h"
#include "dnurbs/dynamics/core/quadrature_assembly.h"
#include "dnurbs/dynamics/dnurbs/rational_control_net_model.h"
#include "dnurbs/nurbs/jacobian.h"
#include "dnurbs/nurbs/knot_vector.h"

namespace dnurbs {

/// Settings of a D-NURBS model.
struct DNurbsSettings {
  /// Control points only (kFixed, q = [P_0, P_1, ...]) or control points and weights (kFree,
  /// q = [P_0, w_0, P_1, w_1, ...]).
  WeightMode weight_mode = WeightMode::kFixed;
  /// Gauss points per non-empty span and direction; 0 picks p + 1 (per direction), which makes
  /// M and D (integrand degree 2p) exact for non-rational shapes with constant densities, and
  /// K too (integrand degree 2p - 2 and 2p - 4, p points would already do). For rational
  /// shapes (non-uniform weights) the integrands are rational and this is an accuracy knob.
  int quadrature_points = 0;
  /// Free weights never go below this value (> 0): after every step the integrator projects
  /// w_i = max(w_i, minimum_weight) and, where a weight was clamped, removes the part of its
  /// velocity that points further down (wdot_i = max(wdot_i, 0)): an inelastic contact with the
  /// bound, which keeps every point of the shape finite.
  double minimum_weight = 1e-3;
  /// Free weights only: scaling every weight by one factor leaves the shape unchanged, so M(q)
  /// and K(q) are singular along q_gauge = [0, w_0, 0, w_1, ...] (J q_gauge = 0). With this
  /// setting (the default) weight 0 is a fixed coordinate, which removes exactly that direction
  /// without restricting the shape. Switch it off only when fixing some weight yourself.
  bool fix_weight_gauge = true;
  /// Free weights only: the weight regularization (rational_control_net_model.h, "Well-posed
  /// free weights"). Unset (the default): scale-aware, derived from the initial shape,
  ///   weight inertia   m_w = 10 mean_a M_ww(a, a) at the initial state,
  ///   weight stiffness k_w =  2 mean_a K_ww(a, a) at the initial state,
  /// k_w pulling every weight towards its initial value (energy (1/2) k_w |w - w_0|^2). Set
  /// (>= 0): that constant inertia and, unless weight_stiffness is set too, no weight stiffness
  /// (0, 0 is exact D-NURBS, whose M(q) is singular beyond the gauge for straight and flat
  /// shapes, so that free-weight runs there diverge).
  std::optional<double> weight_inertia;
  /// Free weights only: an explicit weight stiffness k_w (>= 0); unset: as above.
  std::optional<double> weight_stiffness;
  /// Measure the stretching and bending energy from the initial shape (DNurbsModel::
  /// set_rest_shape with the initial coordinates), so that the shape as built is at rest; false
  /// (the default): from zero, the energy of Terzopoulos 2003, eq. 1.20, under which tension
  /// shrinks every curved shape.
  bool initial_shape_at_rest = false;
  /// A rest shape that yields (dynamics/core/plastic_flow.h): after every step each control
  /// point's rest position flows towards its position beyond the yield distance, so a push leaves
  /// a dent. Implies a rest shape (the initial shape unless set_rest_shape moves it).
  std::optional<PlasticFlow> plastic_flow;
};

/// A D-NURBS curve or surface as a Model. Use DNurbsCurve or DNurbsSurface to build one.
///
/// Material: `mass_density` mu and `damping_density` gamma per unit parametric measure, and the
/// stiffness coefficients k_alpha of the quantities alpha = 1..5 (x_u, x_v, x_uu, x_uv, x_vv):
///   K = integral sum_alpha k_alpha J_alpha^T J_alpha     (Terzopoulos 2003, eqs. 1.26 and 1.20).
///
/// Rest shape and plastic flow: rational_control_net_model.h; the rest derivatives x^alpha(q_r)
/// are stored at the Gauss points.
class DNurbsModel : public RationalControlNetModel {
 public:
  int parametric_dimension() const override { return surface_ ? 2 : 1; }

  void add_internal_force(ConstVectorRef q, VectorRef force) const override;
  /// g = -integral mu J^T Jdot qd with Jdot qd = (2 / W) (sum_a N_a wdot_a Pdot_a - Wdot xdot)
  /// (free weights; zero for fixed weights).
  void add_inertial_force(ConstVectorRef q, ConstVectorRef qd, VectorRef force) const override;
  void add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                             VectorRef force) const override;
  /// Free weights: M, D, K, f_int and g (when `inertial`) in one pass over the Gauss points,
  /// the rational Jacobian evaluated once per point (free_pass); fixed weights: Model's default.
  void assemble_step(ConstVectorRef q, ConstVectorRef qd, bool inertial, ModelMatrices& matrices,
                     VectorRef force) const override;
  /// Free weights: f_int + g - D qd - M a matrix-free in one pass (per Gauss point
  /// -J_0^T w (mu J_0 a + gamma J_0 qd), and the weight inertia's -m_w a_w); fixed weights:
  /// Model's default.
  void add_step_residual(ConstVectorRef q, ConstVectorRef qd, ConstVectorRef a, bool inertial,
                         VectorRef force) const override;

  /// The parametric measure of the domain (length of a curve's, area of a surface's).
  double parametric_measure() const;

 protected:
  /// `knots_v` is null for curves. `stiffness` holds k_alpha for alpha = 0..5 (k_0 unused).
  DNurbsModel(const KnotVector& knots_u, const KnotVector* knots_v,
              const Eigen::MatrixX3d& control_points, const Eigen::VectorXd& weights,
              const MaterialFunction& mass_density, const MaterialFunction& damping_density,
              const std::array<MaterialFunction, kQuantityCount>& stiffness,
              const std::array<const char*, kQuantityCount>& stiffness_names,
              const DNurbsSettings& settings);

 private:
  // Construction steps: checks, the material values at every quadrature point, the element
  // connectivity and pattern, the initial coordinates and the constant (fixed-weight) matrices
  // or the free-weight block pattern.
  void validate(const Eigen::VectorXd& weights, const DNurbsSettings& settings) const;
  void build_material_table(const MaterialFunction& mass_density,
                            const MaterialFunction& damping_density,
                            const std::array<MaterialFunction, kQuantityCount>& stiffness,
                            const std::array<const char*, kQuantityCount>& stiffness_names);
  void build_pattern();
  // The quadrature loop of every integral (Terzopoulos 2003, eq. 1.25): at each quadrature point of
  // each element, the basis and the rational Jacobian of derivative order `order` (with the weight
  // columns when `weight_columns`) at the control net, then
  //   point(element, point, weight (quadrature weight times span lengths), material values,
  //         basis, jacobian),
  // and element_done(element) after the element's last point.
  template <typename PointVisitor, typename ElementVisitor>
  void for_each_quadrature_point(const ControlNet& net, int order, bool weight_columns,
                                 PointVisitor&& point, ElementVisitor&& element_done) const;
  // Zeroes a free-weight matrix in the block pattern (or empties it when unused).
  void reset_block_matrix(SparseMatrix& matrix, bool used) const;
  // Basis at an arbitrary parameter / at quadrature point `point` of element `element`.
  void basis_at(const Eigen::Vector2d& u, PointBasis& basis) const;
  void basis_at_quadrature(int element, int point, PointBasis& basis) const;
  void visit_rational_point(ConstVectorRef q, const Eigen::Vector2d& u, bool weight_columns,
                            const std::function<void(const RationalPoint&)>& visit) const override;
  ControlNet control_net(ConstVectorRef q) const;
  int points_per_element() const { return table_u_.points_per_span * table_v_.points_per_span; }
  int element_count() const { return table_u_.span_count * table_v_.span_count; }
  // Quadrature weight (times span lengths) and parameter of a point.
  double quadrature_weight(int element, int point) const;
  Eigen::Vector2d quadrature_parameter(int element, int point) const;
  // Assembly of the scalar (fixed weights) or block (free weights) matrices at q.
  void assemble_scalar(ModelMatrices& scalar) const override;
  // E = (1/2) integral sum_alpha k_alpha |x^alpha - x^alpha_rest|^2 at the Gauss points.
  double quadrature_potential_energy(ConstVectorRef q) const override;
  void store_rest_derivatives(ConstVectorRef q_rest) override;
  void assemble_free(ConstVectorRef q, ModelMatrices& matrices) const override;
  // Free weights, one pass over the Gauss points: M, D, K at q into `matrices` (block pattern,
  // weight regularization added) and, when `force` is non-null (coordinate_count() entries), the
  // internal force f_int(q) and, when `qd` is non-null too, the inertial force g(q, qd) added to
  // it. The element matrices live in per-thread buffers: no allocation once they have grown.
  void free_pass(ConstVectorRef q, const double* qd, ModelMatrices& matrices, double* force) const;
  // The element matrices of free_pass: the distinct entries of the 4 x 4 blocks of the upper
  // control point pairs (see the .cpp).
  struct FreeElementMatrices {
    const double* mass;
    const double* damping;
    const double* stiffness;
  };
  // Adds element `element`'s matrices (and their mirrored lower pairs) into the block pattern.
  void scatter_free_element(int element, const FreeElementMatrices& local,
                            ModelMatrices& matrices) const;
  // Per Gauss point (quadrature weight `weight`, material values m, rest derivatives `rest` of
  // rest_at): force -= J_alpha^T (w k_alpha (x^alpha - x^alpha_rest)) for the quantities with
  // stiffness, and force -= w mu J_0^T (Jdot qd) (free weights, force and qd of
  // coordinate_count()).
  void subtract_elastic_force(double weight, const double* m, const double* rest,
                              const PointBasis& basis, const RationalJacobian& jacobian,
                              double* force) const;
  static void subtract_inertial_force(double weight, const double* m, const PointBasis& basis,
                                      const RationalJacobian& jacobian, const double* qd,
                                      double* force);
  // Highest derivative order the stiffness needs (1 or 2; 0 without stiffness).
  int stiffness_order() const;
  // The rest derivatives x^alpha(q_r), alpha = 1..5, at quadrature point `point` of element
  // `element` (3 doubles each, alpha 1 first), or null without a rest shape.
  const double* rest_at(int element, int point) const;
  // x^alpha - x^alpha_rest at one point (x^alpha without a rest shape), x^alpha given.
  static Eigen::Vector3d rest_difference(const Eigen::Vector3d& x, int alpha, const double* rest);

  // Material values at quadrature point i (element * points_per_element + point):
  // material_[i * 8 + 0] = mu, [+1] = gamma, [+2 + alpha] = k_alpha.
  static constexpr int kMaterialStride = 8;

  bool surface_ = false;
  int count_v_ = 1;  // control points along v (1 for curves)
  bool has_damping_ = false;
  std::array<bool, kQuantityCount> has_stiffness_{};
  KnotVector knots_u_;
  std::vector<KnotVector> knots_v_;  // empty for curves, one entry for surfaces
  DirectionQuadrature table_u_;
  DirectionQuadrature table_v_;
  std::vector<double> material_;
  AssemblyPattern pattern_;
  // The rest shape (rational_control_net_model.h): x^alpha(q_r) at every quadrature point
  // (kRestStride doubles per point), empty without one.
  static constexpr int kRestStride = 3 * (kQuantityCount - 1);
  std::vector<double> rest_derivatives_;
};

template <typename PointVisitor, typename ElementVisitor>
void DNurbsModel::for_each_quadrature_point(const ControlNet& net, int order, bool weight_columns,
                                            PointVisitor&& point,
                                            ElementVisitor&& element_done) const {
  PointBasis basis;
  RationalJacobian jacobian;
  const int per_element = points_per_element();
  for (int e = 0; e < element_count(); ++e) {
    for (int g = 0; g < per_element; ++g) {
      basis_at_quadrature(e, g, basis);
      rational_jacobian(basis, order, net, weight_columns, jacobian);
      const double* material =
          &material_[static_cast<size_t>((e * per_element + g) * kMaterialStride)];
      point(e, g, quadrature_weight(e, g), material, static_cast<const PointBasis&>(basis),
            static_cast<const RationalJacobian&>(jacobian));
    }
    element_done(e);
  }
}

}  // namespace dnurbs
