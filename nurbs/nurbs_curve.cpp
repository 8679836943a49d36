#include "dnurbs/nurbs/nurbs_curve.h"

#include <cmath>

#include <Eigen/Geometry>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/rational_validation.h"

namespace dnurbs {

NurbsCurve::NurbsCurve(KnotVector knots, Eigen::MatrixX3d control_points, Eigen::VectorXd weights)
    : knots_(std::move(knots)) {
  const int count = knots_.control_point_count();
  if (control_points.rows() != count) {
    throw make_error("curve of degree ", knots_.degree(), " with ", knots_.size(), " knots needs ",
                     count, " control points, got ", control_points.rows());
  }
  check_control_points(control_points, count);
  control_points_ = std::move(control_points);
  if (weights.size() == 0) {
    weights = Eigen::VectorXd::Ones(count);
  }
  set_weights(weights);
}

void NurbsCurve::set_control_points(const Eigen::MatrixX3d& control_points) {
  check_control_points(control_points, knots_.control_point_count());
  control_points_ = control_points;
}

void NurbsCurve::set_weights(const Eigen::VectorXd& weights) {
  check_weights(weights, knots_.control_point_count());
  weights_ = weights;
  rational_ = (weights_.array() != weights_[0]).any();
}

Eigen::Vector3d NurbsCurve::point(double u) const {
  const int span = knots_.find_span(u);
  BasisValues basis;
  basis_functions(knots_, span, knots_.to_domain(u), basis);
  Eigen::Vector3d numerator = Eigen::Vector3d::Zero();
  double denominator = 0.0;
  for (int j = 0; j <= degree(); ++j) {
    const int i = knots_.control_point_index(span, j);
    const double weighted = basis[j] * weights_[i];
    numerator += weighted * control_points_.row(i).transpose();
    denominator += weighted;
  }
  return numerator / denominator;
}

void NurbsCurve::derivatives(double u, int order, CurveDerivatives& result) const {
  const int span = knots_.find_span(u);
  const double local = knots_.to_domain(u);
  BasisDerivatives basis;
  basis_functions_with_derivatives(knots_, span, local, order, basis);
  // Homogeneous derivatives A^(k) = sum N_i^(k) w_i P_i and w^(k) = sum N_i^(k) w_i.
  CurveDerivatives homogeneous;
  homogeneous.setZero(order + 1, 3);
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxDerivativeOrder + 1, 1> weight_derivatives;
  weight_derivatives.setZero(order + 1);
  for (int j = 0; j <= degree(); ++j) {
    const int i = knots_.control_point_index(span, j);
    for (int k = 0; k <= order; ++k) {
      const double weighted = basis(k, j) * weights_[i];
      homogeneous.row(k) += weighted * control_points_.row(i);
      weight_derivatives[k] += weighted;
    }
  }
  if (!rational_) {
    // Equal weights: C^(k) = A^(k) / w exactly, without the rounding of the quotient rule.
    result = homogeneous / weights_[0];
    return;
  }
  // Quotient rule, Piegl & Tiller A4.2: C^(k) = (A^(k) - sum_{i=1..k} binom(k,i) w^(i) C^(k-i)) /
  // w.
  result.resize(order + 1, 3);
  for (int k = 0; k <= order; ++k) {
    Eigen::RowVector3d value = homogeneous.row(k);
    double binomial = 1.0;
    for (int i = 1; i <= k; ++i) {
      binomial = binomial * (k - i + 1) / i;
      value -= binomial * weight_derivatives[i] * result.row(k - i);
    }
    result.row(k) = value / weight_derivatives[0];
  }
}

CurveDerivatives NurbsCurve::derivatives(double u, int order) const {
  CurveDerivatives result;
  derivatives(u, order, result);
  return result;
}

Eigen::Vector3d NurbsCurve::unit_tangent(double u) const {
  const CurveDerivatives d = derivatives(u, 1);
  const Eigen::Vector3d tangent = d.row(1).transpose();
  const double length = tangent.norm();
  if (!(length > 0.0)) {
    throw make_error("curve tangent vanishes at u = ", u);
  }
  return tangent / length;
}

double NurbsCurve::curvature(double u) const {
  const CurveDerivatives d = derivatives(u, 2);
  const Eigen::Vector3d first = d.row(1).transpose();
  const Eigen::Vector3d second = d.row(2).transpose();
  const double speed = first.norm();
  if (!(speed > 0.0)) {
    throw make_error("curvature is undefined where the tangent vanishes, at u = ", u);
  }
  return first.cross(second).norm() / (speed * speed * speed);
}

Eigen::Vector3d NurbsCurve::principal_normal(double u) const {
  const CurveDerivatives d = derivatives(u, 2);
  const Eigen::Vector3d first = d.row(1).transpose();
  const Eigen::Vector3d second = d.row(2).transpose();
  // Component of C'' orthogonal to C', pointing to the centre of curvature.
  const Eigen::Vector3d normal = second - first * (first.dot(second) / first.squaredNorm());
  const double length = normal.norm();
  if (!(length > 1e-14 * second.norm()) || !std::isfinite(length)) {
    throw make_error("principal normal is undefined (zero curvature or tangent) at u = ", u);
  }
  return normal / length;
}

}  // namespace dnurbs
