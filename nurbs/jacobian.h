#pragma once
// The generalized-coordinate Jacobian of D-NURBS (Terzopoulos 2003, eq. 1.23 and its surface
// analogue, below eq 1.27): J = dx/dq of a point and of its parametric derivatives with respect to
// the control points and, when weights are free, the weights. Only the (p + 1) or (p + 1)(q + 1)
// active control points appear; evaluation uses fixed-capacity storage and never allocates.

#include <array>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "dnurbs/nurbs/basis_functions.h"
#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs {

/// Which quantities are generalized coordinates: control points only (weights fixed, the
/// default: q = [P_0, P_1, ...]) or control points and weights (q = [P_0, w_0, P_1, w_1, ...]).
enum class WeightMode { kFixed, kFree };

/// Coordinates per control point: 3 with fixed weights, 4 with free weights.
inline int coordinates_per_control_point(WeightMode mode) {
  return mode == WeightMode::kFree ? 4 : 3;
}

/// Parametric quantities whose Jacobians are available.
enum class CurveQuantity { kPoint = 0, kU = 1, kUU = 2 };
enum class SurfaceQuantity { kPoint = 0, kU = 1, kV = 2, kUU = 3, kUV = 4, kVV = 5 };

/// Jacobian of a curve point and its u-derivatives at one parameter.
///
/// For active control point a (0..active_count-1) with distinct index control_point[a]:
///   d C^(d) / d P_a = basis(d, a) * I_3   (basis(d, a) is the d-th derivative of the rational
///                                          basis function R_a; the whole fixed-weight Jacobian)
///   d C^(d) / d w_a = weight_column(d, a)  (a 3-vector, filled only for WeightMode::kFree)
/// for d = 0..order.
struct CurveJacobian {
  int order = 0;
  int active_count = 0;
  std::array<int, kMaxDegree + 1> control_point{};
  Eigen::Matrix<double, 3, kMaxDegree + 1> basis;
  std::array<Eigen::Matrix<double, 3, kMaxDegree + 1>, 3> weight_column;  ///< [d].col(a)
  CurveDerivatives point_derivatives;  ///< C^(d)(u), d = 0..order, as a by-product
};

/// Jacobian of a surface point and its partial derivatives up to second order at one (u, v),
/// indexed by SurfaceQuantity: basis(quantity, a) multiplies I_3, weight_column[quantity].col(a)
/// is d/dw_a. Active control points a = 0..active_count-1 are ordered with the u index outer.
struct SurfaceJacobian {
  static constexpr int kMaxActive = (kMaxDegree + 1) * (kMaxDegree + 1);
  int order = 0;  ///< 0: point only; 1: adds u, v; 2: adds uu, uv, vv
  int active_count = 0;
  std::array<int, kMaxActive> control_point{};
  Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxActive> basis;
  std::array<Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxActive>, 6> weight_column;
  std::array<Eigen::Vector3d, 6> point_derivatives;  ///< S, Su, Sv, Suu, Suv, Svv
};

/// Fills `jacobian` at u for parametric derivatives 0..order (order <= 2).
void curve_jacobian(const NurbsCurve& curve, double u, int order, WeightMode mode,
                    CurveJacobian& jacobian);
/// Fills `jacobian` at (u, v) for partial derivatives of total order <= order (order <= 2).
void surface_jacobian(const NurbsSurface& surface, double u, double v, int order, WeightMode mode,
                      SurfaceJacobian& jacobian);

/// Jdot qd for every quantity d = 0..order (curves) or every SurfaceQuantity of total order <=
/// order (surfaces): the second directional derivative sum_kl d^2 x^(d) / dq_k dq_l qd_k qd_l of
/// the point or parametric derivative in the coordinate direction qd, given as the rates of all
/// control points (`point_rates`, control_point_count by 3) and of all weights (`weight_rates`,
/// control_point_count; zero for fixed weights). It is the velocity-product part of
/// d^2 x^(d) / dt^2 = J qdd + Jdot qd, which constraints need (Terzopoulos 2003, eq. 1.40's sigma).
/// Zero when weight_rates is zero. Results: curve rows d, surface entries by SurfaceQuantity.
void curve_jacobian_rate(const NurbsCurve& curve, double u, int order,
                         const Eigen::MatrixX3d& point_rates, const Eigen::VectorXd& weight_rates,
                         CurveDerivatives& result);
void surface_jacobian_rate(const NurbsSurface& surface, double u, double v, int order,
                           const Eigen::MatrixX3d& point_rates, const Eigen::VectorXd& weight_rates,
                           std::array<Eigen::Vector3d, 6>& result);

/// The 3 by #coordinates sparse matrix of one quantity, coordinates laid out as in WeightMode.
Eigen::SparseMatrix<double> to_sparse_matrix(const CurveJacobian& jacobian, CurveQuantity quantity,
                                             WeightMode mode, int control_point_count);
Eigen::SparseMatrix<double> to_sparse_matrix(const SurfaceJacobian& jacobian,
                                             SurfaceQuantity quantity, WeightMode mode,
                                             int control_point_count);

}  // namespace dnurbs
