#pragma once
// Swung D-NURBS surfaces (Qin & Terzopoulos, Dynamic NURBS swung surfaces for physics-based shape
// design, CAD 27(2) 1995; Terzopoulos, Deformable Models: Classic, Topology-Adaptive and
// Generalized Formulations, section 4.1): the generalized coordinates are the control points
// and, optionally, the weights of the profile and trajectory curves of a SwungSurface, so a
// surface of m x n control points has 2 (m + n) or 3 (m + n) coordinates instead of 3 m n.
//
// The Jacobian J = dS/dq is a product of the two curves' Jacobians and depends on q even with
// fixed weights, so M(q), D(q) and the stiffness depend on the state, and the generalized
// inertial force g = -integral mu J^T Jdot qd is never zero. They are Gauss sums re-assembled at
// every state from curve bases cached once (SwungQuadrature, SwungElementAssembly), or, with
// fixed weights and constant material, closed-form quadratic forms of the curves' 1-D Gram
// matrices (SwungSeparableForms).
//
// Rest shape and plastic flow, as the rational control-net models have them
// (rational_control_net_model.h) in the swung surface's own coordinates. By default the energy
// is measured from zero (Terzopoulos, eq. 1.20); with a rest shape q_r (set_rest_shape, a
// profile and a trajectory with their weights) it is the energy of the change from that shape,
//   E(q) = 1/2 integral sum_Q k_Q |S^Q(q) - S^Q(q_r)|^2,
//   f_int = -dE/dq = -integral sum_Q k_Q J_Q(q)^T (S^Q(q) - S^Q(q_r)),
// so q_r is at rest (f_int(q_r) = 0 exactly: the same arithmetic gives S^Q(q) and S^Q(q_r)), and
// the step's tangent stiffness K(q) keeps its Gauss-Newton part while its exact second-derivative
// part weighs S^Q - S^Q(q_r). S is linear in each curve's coordinates (fixed weights) but
// bilinear in the two, so f_int = -K(q_r) (q - q_r) and E = 1/2 (q - q_r)^T K(q_r) (q - q_r) hold
// to second and third order in q - q_r, and exactly (fixed weights) when only one curve has left
// its rest; E depends on the surfaces alone, so the scaling gauge moves nothing. The model keeps
// q_r as each curve's points and derivatives at its Gauss points (SwungRestPoints; N_u + N_v
// entries), or, on the separable path, as q_r inside the closed forms. A rest shape that yields
// (set_plastic_flow, dynamics/core/plastic_flow.h) moves q_r towards q after every committed step:
// each curve control point's rest position, its two in-plane coordinates (x, z of the profile,
// X, Y of the trajectory: the trajectory's are scaled by alpha p_x on the surface, so on the unit
// circle a yield distance there is relative to the radius), flows where it is farther than the
// yield distance from its position; free weights keep their rest values. So a push leaves a dent.

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/model.h"
#include "dnurbs/dynamics/core/plastic_flow.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/swung/swung_quadrature.h"
#include "dnurbs/dynamics/swung/swung_separable_forms.h"
#include "dnurbs/nurbs/swung_jacobian.h"
#include "dnurbs/nurbs/swung_surface.h"

namespace dnurbs {

/// Settings of a swung D-NURBS surface.
struct DNurbsSwungSettings {
  /// Control points only (kFixed: 2 coordinates per control point) or control points and
  /// weights of both curves (kFree: 3 per control point).
  WeightMode weight_mode = WeightMode::kFixed;
  /// Gauss points per non-empty span and direction; 0 picks p + 1 along u (profile degree p)
  /// and q + 1 along v (trajectory degree q), which integrates M, D, K, E and g exactly for
  /// non-rational curves with fixed weights and constant material (every integrand is then a
  /// polynomial of degree <= 2p in u and <= 2q in v). With free weights 0 picks at least
  /// ceil(3 m / (2 S)) per span for a curve of m control points over S non-empty spans, so that
  /// its 2 S n position samples outnumber its 3 m coordinates: with fewer, M is singular along
  /// motions of one curve's points and weights that vanish at every Gauss point (the sphere's
  /// 5-point half-circle profile with 3 points on each of its 2 spans has two such directions).
  /// Rational curves (the circle) make the rule an accuracy knob.
  int quadrature_points = 0;
  /// Free weights never go below this value (> 0): the state is projected as in DNurbsModel
  /// (w = max(w, minimum), and the velocity of a clamped weight stops pointing further down).
  double minimum_weight = 1e-3;
  /// Fixes the gauges, the directions along which the surface does not move so M is singular:
  /// the scaling (p_x, t) -> (c p_x, t / c) always, by fixing the profile x coordinate of
  /// largest magnitude (gauge_coordinate(); among equal ones the nearest to the middle of the
  /// profile, a sphere's equator point; dynamics/swung/swung_gauge.h); and with free weights the
  /// common scaling of each curve's weights, by fixing weight 0 of the profile and of the
  /// trajectory. None of these restricts the shape (locally: any nearby shape is reached with
  /// them fixed). The scaling is fixed on the profile, not the trajectory, so that a step that
  /// leaves some residual along the gauge (a linearly implicit step with the exact tangent
  /// stiffness, which the gauge direction does not annihilate where E is stretched) scales the
  /// trajectory uniformly and a surface of revolution stays one; pinning one trajectory
  /// coordinate instead turned that residual into an out-of-round trajectory (3e-7 after 10
  /// steps of the egg test). The model's own fix functions release the scaling gauge
  /// coordinate when what they fix already breaks the scaling (a trajectory point off the
  /// origin, a profile point off the axis: then the gauge coordinate would be a real
  /// constraint); Model::fix_coordinate does not.
  bool fix_gauge = true;
  /// The assembled stiffness (the K_T of the step matrix M + c_v D + c_q K_T) is the Gauss-Newton
  /// part integral sum_Q k_Q J_Q^T J_Q of d^2E/dq^2 (false, the default: positive
  /// semi-definite, as the free-weight tensor-product model's), or the exact tangent
  /// d^2E/dq^2 = integral sum_Q k_Q (J_Q^T J_Q + sum_c S^Q_c d^2 S^Q_c / dq^2) (true: quadratic
  /// Newton convergence near equilibrium and small steps). The exact tangent is indefinite where
  /// the surface is stretched (the D-NURBS energy pulls every S^Q towards 0): on a sphere with a
  /// refined trajectory (36 control points) under the thin plate at dt = 0.01 it made the Newmark
  /// step diverge (energy 4 -> 4e10 in one step, with or without Newton iterations), while the
  /// Gauss-Newton stiffness stayed stable. The internal force -dE/dq is exact either way, so a
  /// step solved to convergence has the same answer with both.
  bool geometric_stiffness = false;
  /// Measure the energy from the initial shape (set_rest_shape with the initial coordinates), so
  /// that the surface as built is at rest; false (the default): from zero (Terzopoulos, eq.
  /// 1.20), under which tension shrinks every swung surface towards its axis.
  bool initial_shape_at_rest = false;
  /// A rest shape that yields (file comment): after every step each curve control point's rest
  /// position flows towards its position beyond the yield distance, so a push leaves a dent.
  /// Implies a rest shape (the initial shape unless set_rest_shape moves it).
  std::optional<PlasticFlow> plastic_flow;
  /// Free weights only: a constant inertia added to the diagonal of M for every weight
  /// coordinate (default 0: exact D-NURBS), as DNurbsSettings::weight_inertia. Weights are light
  /// coordinates (their M entries are ~1e-5 of the positions' for the prototypes), so forces
  /// accelerate them fast; a small positive value slows them. Constant, so g and energy
  /// conservation are unaffected.
  double weight_inertia = 0.0;
  /// With fixed weights and constant material every integrand is a product of a function of u
  /// and one of v, and M, D, K, E, f_int and g are closed-form quadratic forms of the curves'
  /// 1-D Gram matrices (SwungSeparableForms): O((m + n)^2) work per state instead of the
  /// Gauss-point work over the span products, the same sums up to round-off. False: always the
  /// general quadrature.
  bool separable_assembly = true;
};

/// A swung D-NURBS surface as a Model.
///
/// Coordinates (SwungLayout): q = [x_0, z_0, (w_0), ..., | X_0, Y_0, (W_0), ...], the profile's
/// control points then the trajectory's. Velocities and forces share that layout; matrices are
/// #coordinates by #coordinates, with the profile-trajectory block dense (every profile
/// coordinate couples with every trajectory one) and the curve blocks banded.
///
/// Material per unit parametric area (DNurbsSurfaceMaterial) and the D-NURBS energy of the
/// tensor-product model (Terzopoulos, eq. 1.20, measured from the zero state, or from a rest
/// shape: file comment):
///   M(q) = integral mu J^T J du dv,   D(q) = integral gamma J^T J du dv,
///   E(q) = 1/2 integral sum_Q k_Q |S^Q(q)|^2 du dv,
///   f_int = -dE/dq = -integral sum_Q k_Q J_Q^T S^Q,
/// Q = S_u, S_v, S_uu, S_uv, S_vv with k_Q = a10, a01, b20, 2 b11, b02. Since S^Q is not linear
/// in q, E is not (1/2) q^T K q: the model gives E, f_int and the tangent stiffness itself.
///
/// Stepping: M, D and K depend on q, so the integrators re-assemble and re-factor them at every
/// solve. With refined curves and bending stiffness the trajectory's tangential modes are stiff
/// (omega dt ~ 100 on a sphere refined to 35 x 68 control points with b02 = 0.005 at dt = 0.01),
/// and the linearly implicit Newmark step (no Newton iterations) diverged there, while implicit
/// Euler and Newmark with one Newton iteration stayed stable: use newton_iterations >= 1 for
/// refined shapes. A surface that collapses onto its axis (all p_x -> 0, e.g. under the D-NURBS
/// tension alone) makes M singular along the trajectory coordinates, and the step fails with
/// the integrator's non-finite-state error.
///
/// A swung surface has no 3-D control points among its coordinates: control_point_offset()
/// throws (forces and constraints on control points address the curve coordinates through
/// profile_offset() / trajectory_offset() and fixed coordinates instead). Its points, for
/// fix_point, are the profile's control points 0..m-1 and the trajectory's m..m+n-1.
///
/// Shape: the exact shape is the tensor-product twin (SwungSurface::to_nurbs_surface), the
/// parametric surface the swung surface itself with exact normals turned outward
/// (dynamics/swung/swung_parametric_surface.h); tessellation is the contract's default through
/// it. Local sculpting (freeze_outside) is not supported: every profile control point moves a
/// whole band of the surface around the axis and every trajectory point a whole strip from
/// pole to pole, so freezing the points away from a region does not keep the motion near it.
/// Neither is the semi-implicit step's scalar (node by node) path: semi_implicit_block_size()
/// is 0 and the stepper takes assemble_matrices(q), whose tangent stiffness linearizes f_int.
class DNurbsSwungSurface : public Model {
 public:
  /// Throws Error naming the value for a bad material value at a quadrature point, a weight
  /// below the minimum (free weights), a bad setting, or a profile whose control points are all
  /// on the z axis (no gauge coordinate).
  explicit DNurbsSwungSurface(const SwungSurface& surface,
                              const DNurbsSurfaceMaterial& material = {},
                              const DNurbsSwungSettings& settings = {});

  std::unique_ptr<Model> clone() const override {
    return std::make_unique<DNurbsSwungSurface>(*this);
  }

  int coordinate_count() const override { return layout_.coordinate_count(); }
  Eigen::VectorXd initial_coordinates() const override { return initial_coordinates_; }
  int parametric_dimension() const override { return 2; }

  Eigen::Vector3d position(ConstVectorRef q, const Eigen::Vector2d& u) const override;
  SparseMatrix position_jacobian(ConstVectorRef q, const Eigen::Vector2d& u) const override;
  /// Jdot qd = alpha (p_x'' t + 2 p_x' t' + p_x t'') in x, y and p_z'' in z (primes: rates along
  /// qd), non-zero even for fixed weights.
  Eigen::Vector3d jacobian_rate_times_velocity(ConstVectorRef q, ConstVectorRef qd,
                                               const Eigen::Vector2d& u) const override;

  bool matrices_are_constant() const override { return false; }
  void assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const override;
  void add_internal_force(ConstVectorRef q, VectorRef force) const override;
  double potential_energy(ConstVectorRef q) const override;
  /// g = -integral mu J^T (Jdot qd) du dv.
  void add_inertial_force(ConstVectorRef q, ConstVectorRef qd, VectorRef force) const override;
  void add_point_force(ConstVectorRef q, const Eigen::Vector2d& u, const Eigen::Vector3d& f,
                       VectorRef force) const override;
  void add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                             VectorRef force) const override;
  void project_state(Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd) const override;
  /// Free weights: lower[w] = minimum_weight() for every weight coordinate (fixed weights: none).
  void coordinate_lower_bounds(VectorRef lower) const override;

  // Shape (Model contract) -------------------------------------------------------------------
  /// swung_parameter_domain of the surface at q: poles where an open profile meets the axis,
  /// periodic where a curve is periodic or closed.
  ParameterDomain parameter_domain(ConstVectorRef q) const override;
  /// The outward side of the initial surface (swung_normal_orientation), fixed at construction.
  NormalOrientation normal_orientation() const override { return orientation_; }
  /// The swung surface at q with its exact normals, turned to normal_orientation().
  ParametricSurface parametric_surface(ConstVectorRef q) const override;
  /// The tensor-product twin of the surface at q (SwungSurface::to_nurbs_surface): shape files,
  /// export and curve-on-surface constraints see the exact shape.
  std::optional<Shape> exact_shape(ConstVectorRef q) const override;
  /// S_u, S_v at u with their Jacobians (profile and trajectory columns), J_u qd, J_v qd and
  /// Jdot_u qd, Jdot_v qd (swung_tangent_kinematics): surface normal constraints.
  void tangent_kinematics(ConstVectorRef q, ConstVectorRef qd, const Eigen::Vector2d& u,
                          TangentKinematics& tangents) const override;

  // Boundary conditions (Model contract) -----------------------------------------------------
  /// Fixes point i: profile control point i (0 <= i < m) or trajectory control point i - m
  /// (swung_point_coordinates); throws Error naming i otherwise.
  void fix_point(int i) override;
  /// Fixes the coordinates that hold the border edges (swung_border_coordinates over
  /// parameter_domain of the initial shape); throws Error for a closed surface (no border).
  void fix_border() override;

  // Swung coordinates ------------------------------------------------------------------------
  const SwungLayout& layout() const { return layout_; }
  WeightMode weight_mode() const { return layout_.mode; }
  double minimum_weight() const { return minimum_weight_; }
  /// Index of the x coordinate of profile control point i (z follows, then the weight) and of
  /// trajectory control point j (y follows, then the weight); throw Error for a bad index.
  int profile_offset(int i) const;
  int trajectory_offset(int j) const;
  /// The coordinate fixed for the scaling gauge (-1 if fix_gauge is off or the gauge was
  /// released because a fix already breaks the scaling).
  int gauge_coordinate() const { return gauge_coordinate_; }
  /// Fixes the in-plane coordinates of profile control point i / trajectory control point j
  /// (a free weight stays free), or every coordinate of the profile / trajectory. Each releases
  /// the scaling gauge coordinate when what it fixes breaks the scaling (DNurbsSwungSettings::
  /// fix_gauge).
  void fix_profile_point(int i);
  void fix_trajectory_point(int j);
  void fix_profile();
  void fix_trajectory();
  /// Keeps the poles closed: fixes x (at 0) of each end control point of an open profile that
  /// lies on the z axis (the poles of a sphere, the apex of a cone or hat). Without it a force
  /// with a radial component there moves x away from 0 and opens the pole into a hole.
  void fix_poles();

  /// The surface at coordinates q, and the one the model was built from.
  SwungSurface surface(const ConstVectorRef& q) const;
  const SwungSurface& initial_surface() const { return surface_; }
  /// Jacobians of S and its parametric derivatives up to `order` (0..2) at (u, v) and state q,
  /// and Jdot qd of each: what surface point, normal and tangent constraints need.
  void jacobian(const ConstVectorRef& q, const Eigen::Vector2d& u, int order,
                SwungJacobian& jacobian) const;
  void jacobian_rate(const ConstVectorRef& q, const ConstVectorRef& qd, const Eigen::Vector2d& u,
                     int order, std::array<Eigen::Vector3d, 6>& rates) const;
  /// Area of the parametric domain.
  double parametric_measure() const;
  /// True if the closed-form separable path is used (DNurbsSwungSettings::separable_assembly).
  bool uses_separable_assembly() const { return separable_; }

  // Rest shape and plastic flow (file comment) ------------------------------------------------
  /// Makes the surface at coordinates `q_rest` (coordinate_count() entries, finite; free weights
  /// >= the minimum weight) the rest shape. Throws Error naming the entry otherwise.
  void set_rest_shape(ConstVectorRef q_rest);
  /// True once a rest shape is set (set_rest_shape, initial_shape_at_rest or plastic flow).
  bool has_rest_shape() const { return rest_coordinates_.size() > 0; }
  /// The rest shape's coordinates (coordinate_count(); empty without a rest shape).
  const Eigen::VectorXd& rest_coordinates() const { return rest_coordinates_; }
  /// Makes the rest shape yield by `flow` (checked; a rest shape is set from the initial
  /// coordinates when there is none), or stop yielding (nullopt; the rest stays where it is).
  void set_plastic_flow(const std::optional<PlasticFlow>& flow);
  const std::optional<PlasticFlow>& plastic_flow() const { return plastic_flow_; }
  /// With plastic flow: the rule on the in-plane coordinates of every curve control point (free
  /// weights keep their rest values), the rest shape moved when a point yielded; returns the
  /// points that yielded.
  int flow_rest_shape(ConstVectorRef q, double dt) override;
  /// rest_coordinates() with plastic flow, empty without.
  Eigen::VectorXd flowing_rest_coordinates() const override;
  void restore_flowing_rest_coordinates(ConstVectorRef rest) override;

 private:
  void check_size(const ConstVectorRef& q, const char* what) const;
  // Fixes `coordinates`, releasing the scaling gauge coordinate first if they break the scaling.
  void fix_coordinates(const std::vector<int>& coordinates);
  // Rebuilds the model without the scaling gauge coordinate (the base class has no way to unfix
  // a coordinate), keeping every other fixed coordinate, and the gauge one if a fix asked for it,
  // and the rest shape and plastic flow as they are.
  void release_gauge();
  // Rational samples of both curves at a parameter / at every Gauss point, at state q.
  void samples_at(const ConstVectorRef& q, const Eigen::Vector2d& u, PlanarCurveSample& profile,
                  PlanarCurveSample& trajectory) const;
  void quadrature_samples(const ConstVectorRef& q, std::vector<PlanarCurveSample>& profile,
                          std::vector<PlanarCurveSample>& trajectory) const;
  // S^Q - S^Q(q_r) at Gauss point pair (i, j) from the Jacobian there (S^Q without a rest shape).
  Eigen::Vector3d change_from_rest(const SwungJacobian& jacobian, int i, int j, int quantity) const;

  SwungSurface surface_;
  // As given (release_gauge rebuilds the model from them).
  DNurbsSurfaceMaterial material_;
  DNurbsSwungSettings settings_;
  SwungLayout layout_;
  SwungQuadrature quadrature_;
  double minimum_weight_ = 1e-3;
  bool geometric_stiffness_ = true;
  double weight_inertia_ = 0.0;
  bool separable_ = false;               // fixed weights, constant material and the setting on
  SwungSeparableForms separable_forms_;  // built once when separable_
  int gauge_coordinate_ = -1;
  bool gauge_requested_ = false;  // a fix listed the gauge coordinate itself
  NormalOrientation orientation_ = NormalOrientation::kSuCrossSv;
  Eigen::VectorXd profile_weights_;     // the weights when they are not coordinates
  Eigen::VectorXd trajectory_weights_;  // (and the initial ones when they are)
  Eigen::VectorXd initial_coordinates_;
  // The rest shape (file comment): its coordinates (empty: none) and its curves at the Gauss
  // points, set by set_rest_shape; the separable forms keep their own copy of q_r.
  Eigen::VectorXd rest_coordinates_;
  SwungRestPoints rest_points_;
  std::optional<PlasticFlow> plastic_flow_;
  // The symmetric pattern of M, D, K (both triangles, values zero), sized once: both curves'
  // span couplings and the dense profile-trajectory block.
  SparseMatrix pattern_;
};

}  // namespace dnurbs
