#pragma once
// What every rational control-net model (the tensor-product D-NURBS curves and surfaces,
// dnurbs_model.h, and the triangular D-NURBS surfaces, dynamics/triangular) does with its
// generalized coordinates (Qin & Terzopoulos, "D-NURBS: a physics-based framework for geometric
// design", IEEE TVCG 2(1) 1996, section 3; Terzopoulos, "Deformable Models: Classic,
// Topology-Adaptive and Generalized Formulations", eqs. 1.21-1.24):
//
//   fixed weights: q = [P_0, P_1, ...] (3 per control point), J does not depend on q and
//     M = S_M (x) I_3, D = S_D (x) I_3, K = S_K (x) I_3 with scalar matrices assembled once;
//   free weights:  q = [P_0, w_0, P_1, w_1, ...] (4 per control point), M, D, K re-assembled at
//     every state into a 4 x 4 block pattern sized once, every weight bounded below by the
//     minimum weight, weight 0 fixed as the gauge, an optional constant weight inertia.
//
// Well-posed free weights. M(q) = integral mu J^T J is singular along every motion (dP, dw) with
// J (dP, dw) = 0: from x = A / W (A = sum_a N_a w_a P_a, W = sum_a N_a w_a),
// dx = (dA - x dW) / W, so the null motions are those with dA = x dW for every u. dW = W (a
// common scaling of the weights) is one, always (the gauge, removed by fixing weight 0). When x is
// a polynomial of degree d (a straight line or a flat patch with linear parametrization, d = 1),
// every polynomial dW of degree <= p - d (per direction) gives one too: p - 1 more for a straight
// cubic, 8 more for a flat bicubic. Along them nothing acts (no mass, no stiffness, no force:
// J^T f and g are orthogonal to them), and near them (gently curved shapes) M is nearly singular.
// Exact D-NURBS then drifts without bound along those directions: weights run into the minimum,
// whose projection moves the shape, and runs diverge (tests/hardcase/test_free_weights.cpp).
//
// The chosen treatment, scale-aware regularization of the weights (the default):
//   - a constant weight inertia m_w on every weight's diagonal of M (Tikhonov regularization of
//     the acceleration in the null directions: the motion there costs m_w |wdot|^2 / 2 of kinetic
//     energy, so a force-free null direction gets no acceleration, the least-norm answer);
//   - a weight stiffness k_w pulling every weight towards its initial value, potential
//     (1/2) k_w |w - w_0|^2 (it keeps the drift along the null directions bounded: they oscillate
//     about the initial weights instead of wandering off).
// Both are derived from the initial shape: m_w = 10 mean_a M_ww(a, a), k_w = 2 mean_a K_ww(a, a),
// the mean diagonal of the weight rows of M and K at the initial state (integral mu |E_a|^2 and
// integral sum_alpha k_alpha |E_a^alpha|^2 with E_a = dx/dw_a), so they follow the shape's size,
// density and material. Effect on the dynamics: both are constant terms of a Lagrangian (kinetic
// (1/2) m_w |wdot|^2, potential (1/2) k_w |w - w_0|^2), so g is unchanged and energy is conserved
// (dissipated with damping); weights respond more slowly (their inertia is about 10 times the
// natural weight diagonal of M) and resist a change with about twice the shape's own weight
// stiffness, so weights stay near their initial values (within 0.6 to 1 in
// tests/hardcase/test_free_weights.cpp, from 1) and a static shape under a load differs from exact
// D-NURBS in its weights' part; the control points carry the deformation. Smaller scales (0.1 and
// 0.1) still let flat sheets diverge within 20 steps; 10 and 2 keep every case of that test bounded
// over 10,000 steps. Fixed weights and control points are unaffected.
//
// Rest shape. By default the energy is E(q) = (1/2) integral sum_alpha k_alpha |x^alpha(q)|^2
// (Terzopoulos 2003, eq. 1.20), which is zero only for a shape shrunk to a point (tension) or a
// straight line / flat plane (rigidity). With a rest shape q_r (set_rest_shape) it is the energy
// of the change from that shape,
//   E(q) = (1/2) integral sum_alpha k_alpha |x^alpha(q) - x^alpha(q_r)|^2,
//   f_int = -dE/dq = -integral sum_alpha k_alpha J_alpha^T (x^alpha(q) - x^alpha(q_r)),
// so q_r is at rest (f_int(q_r) = 0): the derived model stores x^alpha(q_r) at its quadrature
// points (store_rest_derivatives); with fixed weights f_int = -K (q - q_r) exactly, K unchanged.
// A rest shape that yields (set_plastic_flow, dynamics/core/plastic_flow.h) moves q_r towards q
// after every committed step, so a push leaves a dent.
//
// The derived model supplies its basis and quadrature: the rational basis at a parameter
// (visit_rational_point), the scalar matrices (fixed weights), the block matrices at q (free
// weights) and the rest derivatives; the point kinematics, point forces and the rest shape's
// bookkeeping follow here.

#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/model.h"
#include "dnurbs/dynamics/core/plastic_flow.h"
#include "dnurbs/nurbs/jacobian.h"

namespace dnurbs {

/// The rational basis of a control-net model at one parameter u, a view into the model's own
/// evaluation (valid during the visit only). Listed B-spline a (0 <= a < count) belongs to
/// control point control_point[a]; the arrays hold quantity 0 (the point) of matrices with
/// kQuantityRows rows stored column by column (Eigen's default), as both basis evaluations give.
struct RationalPoint {
  static constexpr int kQuantityRows = 6;  // x, x_u, x_v, x_uu, x_uv, x_vv
  int count = 0;
  const int* control_point = nullptr;
  const double* basis = nullptr;          ///< N_a at basis[kQuantityRows a]
  const double* rational = nullptr;       ///< R_a = w_a N_a / W at rational[kQuantityRows a]
  const double* weight_column = nullptr;  ///< E_a = dx/dw_a at [3 a, 3 a + 3); null if unused
  double weight_sum = 0.0;                ///< W = sum_a w_a N_a
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< x(u)

  double value(int a) const { return basis[kQuantityRows * a]; }
  double rational_value(int a) const { return rational[kQuantityRows * a]; }
  Eigen::Map<const Eigen::Vector3d> weight_column_of(int a) const {
    return Eigen::Map<const Eigen::Vector3d>(weight_column + 3 * a);
  }
};

/// The coordinates, boundary conditions and constant-matrix caches of a rational control-net
/// model (see the file comment). Control point i owns the velocity-space coordinates
/// [i b, i b + 3) for its position and, with free weights, i b + 3 for its weight (b = 3 or 4).
class RationalControlNetModel : public Model {
 public:
  int coordinate_count() const override { return control_point_count_ * per_control_point_; }
  Eigen::VectorXd initial_coordinates() const override { return initial_coordinates_; }

  /// x(u) = sum_a R_a(u) P_a.
  Eigen::Vector3d position(ConstVectorRef q, const Eigen::Vector2d& u) const override;
  /// L(u) = dx/dq, 3 by velocity_count(): R_a(u) I_3 on control point a's position and, with
  /// free weights, E_a(u) on its weight, for every listed B-spline.
  SparseMatrix position_jacobian(ConstVectorRef q, const Eigen::Vector2d& u) const override;
  /// Free weights: free_weight_acceleration at u; fixed weights: zero (L is constant).
  Eigen::Vector3d jacobian_rate_times_velocity(ConstVectorRef q, ConstVectorRef qd,
                                               const Eigen::Vector2d& u) const override;
  /// L(u)^T f.
  void add_point_force(ConstVectorRef q, const Eigen::Vector2d& u, const Eigen::Vector3d& f,
                       VectorRef force) const override;

  /// E(q) = (1/2) integral sum_alpha k_alpha |x^alpha|^2 (Terzopoulos, Deformable Models,
  /// eq. 1.25). Fixed weights: from the constant K about the initial coordinates q0,
  /// E(q) = E(q0) + d^T K q0 + (1/2) d^T K d with d = q - q0 and E(q0) by quadrature, so that its
  /// rounding is eps |K| |q0| |d| rather than eps |K| |q|^2 (the quadratic form of a large smooth
  /// q cancels); free weights: by quadrature.
  double potential_energy(ConstVectorRef q) const final;

  bool matrices_are_constant() const override { return mode_ == WeightMode::kFixed; }
  /// Free weights: true (see Model::needs_newton_iterations and the file comment).
  bool needs_newton_iterations() const override { return mode_ == WeightMode::kFree; }
  /// Fixed weights: S (x) I_3 (built once); free weights: nullptr.
  const ModelMatrices* constant_matrices() const override;
  /// Fixed weights: a copy of constant_matrices(); free weights: the block matrices at q.
  void assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const override;
  int kronecker_block_size() const override { return mode_ == WeightMode::kFixed ? 3 : 0; }
  /// Fixed weights: S_M, S_D, S_K (control points by control points); free weights: nullptr.
  const ModelMatrices* scalar_matrices() const override;
  /// Free weights: w_i = max(w_i, minimum weight) and, where a weight was clamped,
  /// wdot_i = max(wdot_i, 0) (an inelastic contact with the bound). Fixed weights: nothing.
  void project_state(Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd) const override;
  /// i b; throws Error naming i if there is no such control point.
  int control_point_offset(int i) const override;
  /// Free weights: every weight coordinate is bounded below by the minimum weight.
  void coordinate_lower_bounds(VectorRef lower) const override;
  /// fix_control_point(i), with an Error naming i if there is no such control point.
  void fix_point(int i) override;

  WeightMode weight_mode() const { return mode_; }
  /// Number of distinct control points.
  int control_point_count() const { return control_point_count_; }
  double minimum_weight() const { return minimum_weight_; }
  /// Velocity-space index of weight i (free weights only; throws Error otherwise).
  int weight_offset(int i) const;
  /// Fixes the position of control point i (its three position coordinates; a free weight
  /// stays free).
  void fix_control_point(int i);
  /// Fixes free weight i (throws Error for fixed-weight models). With the default weight gauge
  /// weight 0 is already fixed; fixing a second weight fixes a weight ratio, a shape constraint.
  void fix_weight(int i);
  /// Control points (#control points by 3) and weights (#control points) at coordinates q
  /// (size coordinate_count(); throws Error otherwise). Fixed weights: the weights the model
  /// was built with.
  Eigen::MatrixX3d control_points(ConstVectorRef q) const;
  Eigen::VectorXd weights(ConstVectorRef q) const;
  /// Free weights: the weight inertia m_w and the weight stiffness k_w in use (see the file
  /// comment); 0 for fixed weights.
  double weight_inertia() const { return weight_inertia_; }
  double weight_stiffness() const { return weight_stiffness_; }

  // Rest shape and plastic flow (file comment) ------------------------------------------------
  /// Makes the shape at coordinates `q_rest` (coordinate_count() entries, finite; free weights
  /// >= the minimum weight) the rest shape; with free weights the weight anchor k_w then pulls
  /// towards its weights. Throws Error naming the entry otherwise.
  void set_rest_shape(ConstVectorRef q_rest);
  /// True once a rest shape is set (set_rest_shape, the settings' initial_shape_at_rest or
  /// plastic flow).
  bool has_rest_shape() const { return rest_coordinates_.size() > 0; }
  /// The rest shape's coordinates (coordinate_count(); empty without a rest shape).
  const Eigen::VectorXd& rest_coordinates() const { return rest_coordinates_; }
  /// Makes the rest shape yield by `flow` (checked; a rest shape is set from the initial
  /// coordinates when there is none), or stop yielding (nullopt).
  void set_plastic_flow(const std::optional<PlasticFlow>& flow);
  const std::optional<PlasticFlow>& plastic_flow() const { return plastic_flow_; }
  /// With plastic flow: the rule on every control point's position (free weights keep their
  /// rest values), the rest shape moved when a point yielded; returns the points that yielded.
  int flow_rest_shape(ConstVectorRef q, double dt) override;
  /// rest_coordinates() with plastic flow, empty without.
  Eigen::VectorXd flowing_rest_coordinates() const override;
  void restore_flowing_rest_coordinates(ConstVectorRef rest) override;
  /// Fixed weights with a rest shape: q_r; null otherwise.
  const Eigen::VectorXd* linear_rest_coordinates() const override {
    return has_rest_shape() && mode_ == WeightMode::kFixed ? &rest_coordinates_ : nullptr;
  }

 protected:
  /// Throws nothing: the derived model validates its weights and settings.
  RationalControlNetModel(WeightMode mode, int control_point_count, double minimum_weight);

  /// The initial coordinates from control points (#control points by 3) and weights
  /// (#control points), then fixed weights: the scalar matrices (assemble_scalar) and their
  /// S (x) I_3 expansion; free weights: the 4 x 4 block pattern of `scalar_pattern` (the
  /// control-point coupling pattern, #control points square), the weight inertia and stiffness
  /// (each throws Error unless finite and >= 0; unset inertia: both scale-aware, see the file
  /// comment; set inertia and unset stiffness: no stiffness) and, with `fix_weight_gauge`,
  /// weight 0 fixed.
  void build_coordinates(const Eigen::MatrixX3d& control_points, const Eigen::VectorXd& weights,
                         const SparseMatrix& scalar_pattern, std::optional<double> weight_inertia,
                         std::optional<double> weight_stiffness, bool fix_weight_gauge);
  /// Free weights: adds m_w and k_w to the weight diagonals of M and K (block pattern).
  void add_weight_regularization(ModelMatrices& matrices) const;
  /// Free weights: subtracts k_w (w - w_0) from the weight entries of `force` (q and force of
  /// coordinate_count()); weight_anchor_energy: (1/2) k_w |w - w_0|^2 at q (0 for fixed weights).
  /// w_0 is anchor_weights_: the initial weights unless a derived model moves it.
  void add_weight_anchor_force(ConstVectorRef q, VectorRef force) const;
  double weight_anchor_energy(ConstVectorRef q) const;
  /// tangent_kinematics of the derived surfaces, in two steps: start_tangent_columns sizes
  /// `tangents` for `active_count` control points (columns, J_u and J_v of 3 by b active_count,
  /// rates and biases zero); add_tangent_columns fills the slot of active control point `point`:
  /// its position columns N_u e_r, N_v e_r (r = x, y, z), with free weights its weight column
  /// (weight_u, weight_v: dS_u/dw, dS_v/dw), and their parts of the rates J_u qd, J_v qd (qd of
  /// velocity_count()).
  void start_tangent_columns(int active_count, TangentKinematics& tangents) const;
  void add_tangent_columns(int slot, int point, double basis_u, double basis_v,
                           const Eigen::Vector3d& weight_u, const Eigen::Vector3d& weight_v,
                           ConstVectorRef qd, TangentKinematics& tangents) const;
  /// Throws Error unless q has coordinate_count() entries (velocity_count() for qd).
  void check_coordinates(ConstVectorRef q) const;
  void check_velocity(ConstVectorRef qd) const;

  // The state every rational control-net model shares, set at construction and constant after.
  WeightMode mode_ = WeightMode::kFixed;
  int per_control_point_ = 3;  // b: 3 (fixed weights) or 4 (free weights)
  int control_point_count_ = 0;
  double minimum_weight_ = 1e-3;
  double weight_inertia_ = 0.0;    // free weights: added to every weight's diagonal entry of M
  double weight_stiffness_ = 0.0;  // free weights: k_w of the anchor to the initial weights
  Eigen::VectorXd fixed_weights_;  // the weights when they are not coordinates
  Eigen::VectorXd initial_coordinates_;
  Eigen::VectorXd anchor_weights_;  // free weights: w_0 of the weight anchor (initial or rest)
  // Fixed weights: scalar matrices and their S (x) I_3 expansion, built once by
  // build_coordinates (they depend on the knots, the fixed weights and the material only).
  ModelMatrices scalar_;
  ModelMatrices expanded_;
  // Fixed weights: E(q0) by quadrature and K q0, the expansion point of potential_energy.
  double reference_energy_ = 0.0;
  Eigen::VectorXd reference_gradient_;
  // Free weights: the 4 x 4 block pattern, sized once, and the value index of each weight's
  // diagonal entry in it.
  SparseMatrix block_pattern_;
  std::vector<int> weight_diagonal_;
  // Fixed weights with a rest shape: K q_r, added to f_int = -K q (file comment).
  Eigen::VectorXd rest_force_;

 private:
  // Calls visit once with the rational basis at u of the control net at q (its weight columns
  // filled when `weight_columns`); throws Error for q of the wrong size or u outside the domain.
  virtual void visit_rational_point(
      ConstVectorRef q, const Eigen::Vector2d& u, bool weight_columns,
      const std::function<void(const RationalPoint&)>& visit) const = 0;
  // The scalar matrices S_M, S_D, S_K of fixed weights at initial_coordinates_ (called once by
  // build_coordinates) and the block matrices M, D, K of free weights at q.
  virtual void assemble_scalar(ModelMatrices& scalar) const = 0;
  virtual void assemble_free(ConstVectorRef q, ModelMatrices& matrices) const = 0;
  // E(q) by quadrature of the rational Jacobians at q (any weight mode).
  virtual double quadrature_potential_energy(ConstVectorRef q) const = 0;
  // Stores x^alpha(q_rest) of every quantity with stiffness at every quadrature point of the
  // energy (set_rest_shape has checked q_rest), for the derived force and energy to subtract.
  virtual void store_rest_derivatives(ConstVectorRef q_rest) = 0;

  Eigen::VectorXd rest_coordinates_;
  std::optional<PlasticFlow> plastic_flow_;
};

/// Jdot qd = (2 / W) (sum_a N_a wdot_a Pdot_a - Wdot xdot), the velocity-product part of a
/// point's acceleration with free weights (qd = [Pdot_0, wdot_0, ...], size 4 #control points),
/// from A = x W with the homogeneous point A = sum_a N_a w_a P_a (Qin & Terzopoulos 1996,
/// section 3). `point` needs its weight columns.
Eigen::Vector3d free_weight_acceleration(const RationalPoint& point, ConstVectorRef qd);

}  // namespace dnurbs
