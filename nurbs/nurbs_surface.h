#pragma once
// Tensor-product NURBS surfaces in 3-D (Terzopoulos 2003, eq. 1.27 with fixed time): points,
// partial derivatives, normals and curvatures, rational or not, open or periodic in either
// direction.

#include <array>

#include <Eigen/Core>

#include "dnurbs/nurbs/basis_functions.h"
#include "dnurbs/nurbs/knot_vector.h"

namespace dnurbs {

/// Partial derivatives S^(k,l) = d^(k+l) S / du^k dv^l for k + l <= order, fixed capacity.
class SurfaceDerivatives {
 public:
  int order() const { return order_; }
  const Eigen::Vector3d& operator()(int k, int l) const { return values_[index(k, l)]; }
  Eigen::Vector3d& operator()(int k, int l) { return values_[index(k, l)]; }
  void reset(int order);

 private:
  static constexpr int kMaxOrder = kMaxDerivativeOrder;
  static int index(int k, int l) { return k * (kMaxOrder + 1) + l; }
  int order_ = 0;
  std::array<Eigen::Vector3d, (kMaxOrder + 1) * (kMaxOrder + 1)> values_;
};

/// Curvatures of a surface at a point, with respect to the unit normal (Su x Sv)/|Su x Sv|.
struct SurfaceCurvature {
  double gaussian = 0.0;                                    ///< K = k1 k2
  double mean = 0.0;                                        ///< H = (k1 + k2) / 2
  double principal_max = 0.0;                               ///< k1 >= k2
  double principal_min = 0.0;                               ///< k2
  Eigen::Vector3d direction_max = Eigen::Vector3d::Zero();  ///< unit principal direction of k1
  Eigen::Vector3d direction_min = Eigen::Vector3d::Zero();  ///< unit principal direction of k2
};

/// A tensor-product NURBS surface S(u, v) with (m + 1) x (n + 1) control points.
///
/// Control points and weights are stored flat with the u index outer: control point (i, j) is
/// row i * (n + 1) + j, matching the coordinate order of the D-NURBS models.
class NurbsSurface {
 public:
  /// `control_points` has knots_u.control_point_count() * knots_v.control_point_count() rows;
  /// `weights` the same count (all > 0) or empty for a non-rational surface.
  NurbsSurface(KnotVector knots_u, KnotVector knots_v, Eigen::MatrixX3d control_points,
               Eigen::VectorXd weights = {});

  int degree_u() const { return knots_u_.degree(); }
  int degree_v() const { return knots_v_.degree(); }
  const KnotVector& knots_u() const { return knots_u_; }
  const KnotVector& knots_v() const { return knots_v_; }
  /// Distinct control points along u (m + 1) and along v (n + 1).
  int control_point_count_u() const { return knots_u_.control_point_count(); }
  int control_point_count_v() const { return knots_v_.control_point_count(); }
  int control_point_count() const { return static_cast<int>(control_points_.rows()); }
  /// Flat index of control point (i, j).
  int control_point_index(int i, int j) const { return i * control_point_count_v() + j; }
  const Eigen::MatrixX3d& control_points() const { return control_points_; }
  const Eigen::VectorXd& weights() const { return weights_; }
  bool is_rational() const { return rational_; }

  void set_control_points(const Eigen::MatrixX3d& control_points);
  void set_weights(const Eigen::VectorXd& weights);

  Eigen::Vector3d point(double u, double v) const;
  /// S^(k,l) for k + l <= order (rational by the quotient rule, Piegl & Tiller A4.4).
  void derivatives(double u, double v, int order, SurfaceDerivatives& result) const;
  SurfaceDerivatives derivatives(double u, double v, int order) const;
  /// Unit normal (Su x Sv)/|Su x Sv|. Where Su or Sv vanishes (a pole of a surface of
  /// revolution) the limit normal from the mixed derivative is returned; throws Error if none.
  Eigen::Vector3d unit_normal(double u, double v) const;
  /// Gaussian, mean and principal curvatures from the two fundamental forms.
  SurfaceCurvature curvature(double u, double v) const;

 private:
  KnotVector knots_u_;
  KnotVector knots_v_;
  Eigen::MatrixX3d control_points_;
  Eigen::VectorXd weights_;
  bool rational_ = false;
};

}  // namespace dnurbs
