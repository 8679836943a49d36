#pragma once
// Generalized coordinates of swung surfaces and the Jacobians of a point and of its parametric
// derivatives with respect to them (Qin & Terzopoulos, Dynamic NURBS swung surfaces for
// physics-based shape design, CAD 27(2) 1995). With s = (alpha p_x t_x, alpha p_x t_y, p_z) the
// Jacobian is a product of the two curves' Jacobians, so it depends on q even for fixed weights;
// its second derivatives (for Jdot qd and the tangent stiffness) are given too.
//
// Everything is built from per-curve samples (the rational quantities of one planar curve at one
// parameter), so a quadrature loop evaluates each curve once per Gauss point of its own direction
// and forms the surface's Jacobians at the point pairs by products. No function allocates except
// the conveniences that take a SwungSurface.

#include <array>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "dnurbs/nurbs/jacobian.h"
#include "dnurbs/nurbs/knot_vector.h"
#include "dnurbs/nurbs/swung_surface.h"

namespace dnurbs {

/// Layout of the generalized coordinates q of a swung surface: the profile's m control points
/// first, then the trajectory's n; each contributes its two in-plane coordinates and, with free
/// weights, its weight:
///   q = [x_0, z_0, (w_0), ..., x_{m-1}, z_{m-1}, (w_{m-1}), X_0, Y_0, (W_0), ..., X_{n-1}, ...],
/// 2 (m + n) coordinates (fixed weights) or 3 (m + n) (free), against 3 m n (or 4 m n) for the
/// tensor-product twin. alpha is a shape constant, not a coordinate: scaling alpha by c moves
/// the surface exactly as scaling every profile x_i by c does, so as a coordinate it would only
/// add a direction of zero inertia.
struct SwungLayout {
  WeightMode mode = WeightMode::kFixed;
  int per_control_point = 2;  ///< 2 (fixed weights) or 3 (free weights)
  int profile_count = 0;      ///< m, distinct profile control points
  int trajectory_count = 0;   ///< n, distinct trajectory control points
  int coordinate_count() const { return per_control_point * (profile_count + trajectory_count); }
  /// Index of the x coordinate of profile control point i (z follows, then the weight).
  int profile_offset(int i) const { return per_control_point * i; }
  /// Index of the x coordinate of trajectory control point j (y follows, then the weight).
  int trajectory_offset(int j) const { return per_control_point * (profile_count + j); }
};

SwungLayout swung_layout(const SwungSurface& surface, WeightMode mode);
/// q of `surface` in the layout of `mode`.
Eigen::VectorXd swung_coordinates(const SwungSurface& surface, WeightMode mode);
/// The surface with the knots and alpha of `surface` and the control points (and, for free
/// weights, the weights) of q; fixed weights are those of `surface`. Throws Error if q has the
/// wrong size, a non-finite entry or a weight <= 0.
SwungSurface swung_surface_at(const SwungSurface& surface, WeightMode mode,
                              const Eigen::Ref<const Eigen::VectorXd>& q);

/// Where a planar curve's coordinates are: the two in-plane coordinates of control point i at
/// positions[i * position_stride + 0..1], its weight at weights[i * weight_stride]. For rates,
/// weights may be null (fixed weights: zero weight rates).
struct PlanarControlNet {
  const double* positions = nullptr;
  int position_stride = 2;
  const double* weights = nullptr;
  int weight_stride = 1;
};

/// The net of the profile (or trajectory) inside a coordinate or rate vector q laid out as
/// `layout`. Free weights are read from q; fixed weights from `fixed_weights` (stride 1), which
/// is null for rate vectors (fixed weights have zero rates).
PlanarControlNet swung_profile_net(const SwungLayout& layout, const double* q,
                                   const double* fixed_weights);
PlanarControlNet swung_trajectory_net(const SwungLayout& layout, const double* q,
                                      const double* fixed_weights);

/// One planar NURBS curve c(u) = sum_a N_a w_a P_a / W at one parameter, derivative orders
/// d = 0..2 (Piegl & Tiller, The NURBS Book, eq. 4.8 and the quotient rule of A4.2):
///   phi_a = N_a / W,  R_a = w_a phi_a = dc/dP_a,  E_a = phi_a (P_a - c) = dc/dw_a,
/// and their u-derivatives. Active control points a = 0..degree.
struct PlanarCurveSample {
  int degree = 0;
  std::array<int, kMaxDegree + 1> control_point{};                        ///< distinct index of a
  Eigen::Matrix<double, 3, kMaxDegree + 1> basis;                         ///< N_a^(d)
  Eigen::Matrix<double, 2, kMaxDegree + 1> control;                       ///< P_a (in-plane)
  Eigen::Matrix<double, 1, kMaxDegree + 1> weight;                        ///< w_a
  Eigen::Vector3d weight_sum = Eigen::Vector3d::Zero();                   ///< W^(d)
  Eigen::Matrix<double, 3, kMaxDegree + 1> phi;                           ///< phi_a^(d)
  Eigen::Matrix<double, 3, kMaxDegree + 1> rational;                      ///< R_a^(d)
  std::array<Eigen::Matrix<double, 2, kMaxDegree + 1>, 3> weight_column;  ///< [d].col(a) = E_a^(d)
  Eigen::Matrix<double, 2, 3> point = Eigen::Matrix<double, 2, 3>::Zero();  ///< col d = c^(d)
};

/// Sets degree, control_point and basis (N_a^(d), d = 0..2) of `sample` at u from `knots` (u
/// wraps for periodic knots; throws Error outside an open domain).
void planar_curve_basis(const KnotVector& knots, double u, PlanarCurveSample& sample);
/// Completes a sample whose degree, control_point and basis are set: every rational quantity
/// from the control points and weights of `net`.
void planar_curve_rational(const PlanarControlNet& net, PlanarCurveSample& sample);
/// Directional derivatives of c^(d), d = 0..2, along coordinate rates `rates` (same layout as
/// the curve's net): first.col(d) = J^(d) qd and second.col(d) = sum_kl d^2 c^(d)/dq_k dq_l qd_k
/// qd_l, the velocity-product part of the curve's acceleration (zero for fixed weights).
void planar_curve_rates(const PlanarCurveSample& sample, const PlanarControlNet& rates,
                        Eigen::Matrix<double, 2, 3>& first, Eigen::Matrix<double, 2, 3>& second);

/// Largest number of columns of a swung Jacobian: (p + 1) profile and (q + 1) trajectory control
/// points with up to 3 coordinates each.
inline constexpr int kMaxSwungColumns = 6 * (kMaxDegree + 1);

/// Jacobians of a swung surface point and its parametric derivatives, dense per point with an
/// index list: columns[Q] is the 3 by column_count matrix d s^Q / d q_coordinate[c] for the
/// quantities Q of SurfaceQuantity (S, S_u, S_v, S_uu, S_uv, S_vv) of total order <= order. Every
/// other coordinate has a zero column. Columns 0..profile_column_count-1 belong to the (p + 1)
/// active profile control points (x, z[, w] each), the rest to the (q + 1) active trajectory
/// control points (x, y[, w] each). With S^Q = (alpha f g_x, alpha f g_y, [l == 0] h) for
/// f = p_x^(k), h = p_z^(k), g = t^(l) (Q = (k, l)):
///   d S^Q / d x_a = alpha R_a^(k) (g_x, g_y, 0),   d S^Q / d z_a = (0, 0, [l == 0] R_a^(k)),
///   d S^Q / d X_b = (alpha f R_b^(l), 0, 0),       d S^Q / d Y_b = (0, alpha f R_b^(l), 0),
/// and for free weights d S^Q / d w_a = (alpha E_a.x g, [l == 0] E_a.z),
/// d S^Q / d W_b = (alpha f E_b, 0).
struct SwungJacobian {
  int order = 0;
  int column_count = 0;
  int profile_column_count = 0;
  std::array<int, kMaxSwungColumns> coordinate{};
  std::array<Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxSwungColumns>, 6> columns;
  std::array<Eigen::Vector3d, 6> point_derivatives;  ///< S^Q
};

/// S^Q = (alpha f g_x, alpha f g_y, [l == 0] h) of quantity Q = (k, l) (SurfaceQuantity, 0..5)
/// from the curves' points and derivatives (PlanarCurveSample::point of a profile sample at u,
/// columns (p_x, p_z)^(d), and of a trajectory sample at v): the point_derivatives of
/// swung_jacobian, by the same arithmetic, for a state whose samples are no longer at hand (a
/// rest shape kept as its curves' points at the Gauss points).
Eigen::Vector3d swung_point_derivative(const Eigen::Matrix<double, 2, 3>& profile_point,
                                       const Eigen::Matrix<double, 2, 3>& trajectory_point,
                                       double alpha, int quantity);

/// Combines a profile sample at u and a trajectory sample at v into the Jacobian of quantities
/// of total order <= order (0..2).
void swung_jacobian(const PlanarCurveSample& profile, const PlanarCurveSample& trajectory,
                    double alpha, const SwungLayout& layout, int order, SwungJacobian& jacobian);
/// The same at (u, v) of `surface`, with its own control points and weights as the state.
void swung_jacobian(const SwungSurface& surface, double u, double v, int order, WeightMode mode,
                    SwungJacobian& jacobian);

/// Jdot qd for every quantity Q of total order <= order: the velocity-product part
/// sum_kl d^2 S^Q / dq_k dq_l qd_k qd_l of d^2 S^Q / dt^2 = J^Q qdd + Jdot^Q qd, by the product
/// rule: alpha (f'' g + 2 f' g' + f g'') in x and y (dots are directional derivatives along qd)
/// and [l == 0] h'' in z. `rates` is the whole velocity vector (layout's size). Non-zero even
/// for fixed weights (the surface is bilinear in the two curves).
void swung_jacobian_rate(const PlanarCurveSample& profile, const PlanarCurveSample& trajectory,
                         double alpha, const SwungLayout& layout, const double* rates, int order,
                         std::array<Eigen::Vector3d, 6>& result);
void swung_jacobian_rate(const SwungSurface& surface, double u, double v, int order,
                         WeightMode mode, const Eigen::Ref<const Eigen::VectorXd>& rates,
                         std::array<Eigen::Vector3d, 6>& result);

/// Adds sum_c lambda_c d^2 S^Q_c / dq_i dq_j for the columns i, j of the Jacobian (local order,
/// `hessian` is at least column_count square): the cross terms alpha grad f (x) grad(lambda . g)
/// between the curves, and, for free weights, each curve's second derivatives in its weights.
/// Exactly symmetric.
void add_swung_hessian(const PlanarCurveSample& profile, const PlanarCurveSample& trajectory,
                       double alpha, const SwungLayout& layout, SurfaceQuantity quantity,
                       const Eigen::Vector3d& lambda, Eigen::MatrixXd& hessian);

/// The pieces of add_swung_hessian, for assemblies that sum them over quantities and Gauss points
/// before forming matrices:
///   cross block (profile columns x trajectory columns) = profile_gradient trajectory_gradient^T,
///   with profile_gradient = alpha grad_p p_x^(k) and trajectory_gradient = grad_t (lambda .
///   t^(l)), plus (free weights) add_planar_curve_hessian of the profile at order k with
///   profile_weight and of the trajectory at order l with trajectory_weight.
struct SwungHessianTerms {
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxSwungColumns, 1> profile_gradient;
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxSwungColumns, 1> trajectory_gradient;
  int profile_order = 0;                                        ///< k
  int trajectory_order = 0;                                     ///< l
  Eigen::Vector2d profile_weight = Eigen::Vector2d::Zero();     ///< mu on (p_x, p_z)^(k)
  Eigen::Vector2d trajectory_weight = Eigen::Vector2d::Zero();  ///< mu on t^(l)
};
void swung_hessian_terms(const PlanarCurveSample& profile, const PlanarCurveSample& trajectory,
                         double alpha, const SwungLayout& layout, SurfaceQuantity quantity,
                         const Eigen::Vector3d& lambda, SwungHessianTerms& terms);
/// Adds mu . d^2 c^(order) / dq_i dq_j of one curve with free weights (3 columns per active
/// control point: two in-plane coordinates and the weight) starting at local column `offset`;
/// exactly symmetric. For free weights only: with fixed weights the curve is linear in its
/// coordinates and has no such term (and only 2 columns per control point).
void add_planar_curve_hessian(const PlanarCurveSample& sample, int order, const Eigen::Vector2d& mu,
                              int offset, Eigen::MatrixXd& hessian);

/// The 3 by coordinate_count sparse matrix of one quantity.
Eigen::SparseMatrix<double> to_sparse_matrix(const SwungJacobian& jacobian,
                                             SurfaceQuantity quantity, int coordinate_count);

}  // namespace dnurbs
