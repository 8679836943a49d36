#pragma once
// NURBS curves in 3-D (Terzopoulos 2003, eq. 1.21 with fixed time): points, derivatives, tangents
// and curvature, rational or not, open or periodic.

#include <Eigen/Core>

#include "dnurbs/nurbs/basis_functions.h"
#include "dnurbs/nurbs/knot_vector.h"

namespace dnurbs {

/// Rows k = 0..order hold C^(k)(u): (order + 1) by 3, fixed capacity (no allocation).
using CurveDerivatives =
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor, kMaxDerivativeOrder + 1, 3>;

/// A NURBS curve C(u) = sum_i N_i(u) w_i P_i / sum_i N_i(u) w_i.
///
/// Control points are the distinct ones (n of them; a periodic curve wraps them), weights are
/// positive. A curve is a value: copy it freely.
class NurbsCurve {
 public:
  /// `control_points` n by 3 with n = knots.control_point_count(); `weights` of size n (all > 0)
  /// or empty for a non-rational curve. Throws Error naming the bad value otherwise.
  NurbsCurve(KnotVector knots, Eigen::MatrixX3d control_points, Eigen::VectorXd weights = {});

  int degree() const { return knots_.degree(); }
  const KnotVector& knots() const { return knots_; }
  bool is_periodic() const { return knots_.is_periodic(); }
  /// n by 3, the distinct control points.
  const Eigen::MatrixX3d& control_points() const { return control_points_; }
  /// n weights (all 1 for a non-rational curve).
  const Eigen::VectorXd& weights() const { return weights_; }
  /// True if some weight differs from the others (a curve with all weights equal is polynomial).
  bool is_rational() const { return rational_; }
  int control_point_count() const { return static_cast<int>(control_points_.rows()); }

  /// Replaces the control points (same count, finite) or weights (same count, > 0, finite).
  void set_control_points(const Eigen::MatrixX3d& control_points);
  void set_weights(const Eigen::VectorXd& weights);

  Eigen::Vector3d point(double u) const;
  /// C^(k)(u) for k = 0..order (rational derivatives by the quotient rule, Piegl & Tiller A4.2).
  void derivatives(double u, int order, CurveDerivatives& result) const;
  CurveDerivatives derivatives(double u, int order) const;
  /// Unit tangent C'/|C'|; throws Error where C' vanishes.
  Eigen::Vector3d unit_tangent(double u) const;
  /// Curvature |C' x C''| / |C'|^3; throws Error where C' vanishes.
  double curvature(double u) const;
  /// Unit principal normal (towards the centre of curvature); throws Error where the curvature
  /// vanishes.
  Eigen::Vector3d principal_normal(double u) const;

 private:
  KnotVector knots_;
  Eigen::MatrixX3d control_points_;
  Eigen::VectorXd weights_;
  bool rational_ = false;
};

}  // namespace dnurbs
