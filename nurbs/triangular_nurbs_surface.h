#pragma once
// Triangular NURBS surfaces (Qin & Terzopoulos, "Triangular NURBS and their dynamic
// generalizations", Computer Aided Geometric Design 14, 1997, eq. 2): the rational form of
// triangular B-splines,
//
//   x(u) = sum_a w_a P_a N_a(u) / sum_a w_a N_a(u),
//
// with one control point P_a and weight w_a > 0 per B-spline N_a = N_beta^I, and its Jacobian
// with respect to the control points and weights (the quantities of the triangular D-NURBS
// model): d x^alpha / d P_a = R_a^alpha I_3 with R_a = w_a N_a / W, W = sum_a w_a N_a, and
// d x^alpha / d w_a = D^alpha [phi_a (P_a - x)] with phi_a = N_a / W, for the parametric
// derivatives alpha = x, x_u, x_v, x_uu, x_uv, x_vv.

#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/nurbs/triangular_bspline_basis.h"

namespace dnurbs {

/// Where control point positions and weights are stored: position of B-spline a at
/// positions[a * position_stride + c], weight at weights[a * weight_stride].
struct TriangularControlNet {
  const double* positions = nullptr;
  int position_stride = 3;
  const double* weights = nullptr;
  int weight_stride = 1;
};

/// The rational basis and Jacobian at one point, for the B-splines listed by the basis values
/// it was computed from (column a is B-spline basis.function[a]). Quantities alpha = 0..5 are
/// x, x_u, x_v, x_uu, x_uv, x_vv; only those of total order <= `order` are filled.
struct TriangularRationalJacobian {
  int order = 0;
  double weight_sum = 0.0;                            ///< W = sum_a w_a N_a
  Eigen::Matrix<double, 6, Eigen::Dynamic> rational;  ///< R(alpha, a) = D^alpha (w_a N_a / W)
  Eigen::Matrix<double, 6, Eigen::Dynamic> phi;       ///< phi(alpha, a) = D^alpha (N_a / W)
  std::array<Eigen::Matrix<double, 3, Eigen::Dynamic>, 6> weight_column;  ///< [alpha].col(a)
  std::array<Eigen::Vector3d, 6> point;                                   ///< x^alpha
};

/// Quotient rule for the rational Jacobian from the non-rational B-spline values (order 0..2;
/// weight columns only if `with_weight_columns`). Reuses the storage of `jacobian`.
void triangular_rational_jacobian(const TriangularBasisValues& basis, int order,
                                  const TriangularControlNet& net, bool with_weight_columns,
                                  TriangularRationalJacobian& jacobian);

/// A triangular NURBS surface: a triangular B-spline basis (shared, immutable) with control
/// points (function_count by 3) and weights (function_count, all > 0; empty: all 1).
class TriangularNurbsSurface {
 public:
  /// Throws Error for a null basis, sizes that do not match, non-finite control points or
  /// weights that are not positive and finite.
  TriangularNurbsSurface(std::shared_ptr<const TriangularBSplineBasis> basis,
                         Eigen::MatrixX3d control_points, Eigen::VectorXd weights = {});

  const TriangularBSplineBasis& basis() const { return *basis_; }
  const std::shared_ptr<const TriangularBSplineBasis>& shared_basis() const { return basis_; }
  int control_point_count() const { return static_cast<int>(control_points_.rows()); }
  const Eigen::MatrixX3d& control_points() const { return control_points_; }
  const Eigen::VectorXd& weights() const { return weights_; }
  bool is_rational() const { return rational_; }
  /// The control points and weights as a control net (valid while the surface lives).
  TriangularControlNet control_net() const;

  /// x(u) (u located in the domain; throws Error outside it).
  Eigen::Vector3d point(const Eigen::Vector2d& u) const;
  /// x, x_u, x_v, x_uu, x_uv, x_vv at u (entries beyond `order` zero).
  std::array<Eigen::Vector3d, 6> derivatives(const Eigen::Vector2d& u, int order) const;
  /// The same as the limit from inside domain triangle t (one-sided on edges and vertices).
  std::array<Eigen::Vector3d, 6> derivatives_in_triangle(int t, const Eigen::Vector2d& u,
                                                         int order) const;
  /// (x_u x x_v) / |x_u x x_v|; throws Error where the tangents are parallel.
  Eigen::Vector3d unit_normal(const Eigen::Vector2d& u) const;

 private:
  std::shared_ptr<const TriangularBSplineBasis> basis_;
  Eigen::MatrixX3d control_points_;
  Eigen::VectorXd weights_;
  bool rational_ = false;
  // The control points row by row (x, y, z of point 0, then point 1, ...) for control_net().
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> packed_points_;
};

/// The flat surface x(u, v) = (u, v, 0) over the basis's domain: control points at the domain
/// points (TriangularBSplineBasis::domain_points), weights 1.
TriangularNurbsSurface flat_triangular_surface(std::shared_ptr<const TriangularBSplineBasis> basis);

}  // namespace dnurbs
