#include "dnurbs/nurbs/triangular_nurbs_surface.h"

#include <cmath>

#include <Eigen/Geometry>

#include "dnurbs/core/error.h"

namespace dnurbs {

void triangular_rational_jacobian(const TriangularBasisValues& basis, int order,
                                  const TriangularControlNet& net, bool with_weight_columns,
                                  TriangularRationalJacobian& jacobian) {
  if (order < 0 || order > 2) {
    throw make_error("rational Jacobian order ", order, " is outside 0..2");
  }
  const Eigen::Index n = basis.count;
  // The listed control points (3 by n) and weights.
  Eigen::Matrix3Xd points(3, n);
  Eigen::RowVectorXd weights(n);
  for (Eigen::Index a = 0; a < n; ++a) {
    const std::ptrdiff_t node = basis.function[static_cast<size_t>(a)];
    weights[a] = net.weights[node * net.weight_stride];
    points.col(a) = Eigen::Map<const Eigen::Vector3d>(net.positions + node * net.position_stride);
  }
  // W and its derivatives, W^alpha = sum_a w_a N_a^alpha (rows: W, W_u, W_v, W_uu, W_uv, W_vv).
  const Eigen::Matrix<double, 6, 1> w = basis.value * weights.transpose();
  jacobian.order = order;
  jacobian.weight_sum = w[0];
  // phi_a = N_a / W by the quotient rule (differentiating W phi = N):
  //   phi_u = (N_u - W_u phi) / W,  phi_uu = (N_uu - 2 W_u phi_u - W_uu phi) / W,
  //   phi_uv = (N_uv - W_u phi_v - W_v phi_u - W_uv phi) / W, and likewise in v.
  auto& phi = jacobian.phi;
  phi.setZero(6, n);
  const auto& values = basis.value;
  phi.row(0) = values.row(0) / w[0];
  if (order >= 1) {
    phi.row(1) = (values.row(1) - w[1] * phi.row(0)) / w[0];
    phi.row(2) = (values.row(2) - w[2] * phi.row(0)) / w[0];
  }
  if (order >= 2) {
    phi.row(3) = (values.row(3) - 2.0 * w[1] * phi.row(1) - w[3] * phi.row(0)) / w[0];
    phi.row(4) = (values.row(4) - w[1] * phi.row(2) - w[2] * phi.row(1) - w[4] * phi.row(0)) / w[0];
    phi.row(5) = (values.row(5) - 2.0 * w[2] * phi.row(2) - w[5] * phi.row(0)) / w[0];
  }
  // R_a^alpha = w_a phi_a^alpha and x^alpha = sum_a R_a^alpha P_a.
  const int quantities = order == 0 ? 1 : (order == 1 ? 3 : 6);
  jacobian.rational = phi.array().rowwise() * weights.array();
  for (int alpha = 0; alpha < 6; ++alpha) {
    jacobian.point[static_cast<size_t>(alpha)] =
        alpha < quantities ? Eigen::Vector3d(points * jacobian.rational.row(alpha).transpose())
                           : Eigen::Vector3d::Zero();
  }
  if (!with_weight_columns) {
    return;
  }
  // d x^alpha / d w_a = D^alpha [phi_a (P_a - x)] by the Leibniz rule:
  //   E^u = phi_u (P - x) - phi x_u,  E^uu = phi_uu (P - x) - 2 phi_u x_u - phi x_uu,
  //   E^uv = phi_uv (P - x) - phi_u x_v - phi_v x_u - phi x_uv, and likewise in v.
  const Eigen::Matrix3Xd offset = points.colwise() - jacobian.point[0];
  const auto& x = jacobian.point;
  auto& e = jacobian.weight_column;
  for (int alpha = 0; alpha < 6; ++alpha) {
    e[static_cast<size_t>(alpha)] =
        alpha < quantities ? Eigen::Matrix3Xd(offset.array().rowwise() * phi.row(alpha).array())
                           : Eigen::Matrix3Xd::Zero(3, n);
  }
  if (order >= 1) {
    e[1] -= x[1] * phi.row(0);
    e[2] -= x[2] * phi.row(0);
  }
  if (order >= 2) {
    e[3] -= 2.0 * x[1] * phi.row(1) + x[3] * phi.row(0);
    e[4] -= x[2] * phi.row(1) + x[1] * phi.row(2) + x[4] * phi.row(0);
    e[5] -= 2.0 * x[2] * phi.row(2) + x[5] * phi.row(0);
  }
}

TriangularNurbsSurface::TriangularNurbsSurface(std::shared_ptr<const TriangularBSplineBasis> basis,
                                               Eigen::MatrixX3d control_points,
                                               Eigen::VectorXd weights)
    : basis_(std::move(basis)),
      control_points_(std::move(control_points)),
      weights_(std::move(weights)) {
  if (!basis_) {
    throw make_error("triangular NURBS surface without a basis");
  }
  const int count = basis_->function_count();
  if (control_points_.rows() != count) {
    throw make_error("triangular NURBS surface has ", control_points_.rows(),
                     " control points; its basis has ", count, " B-splines");
  }
  for (int a = 0; a < count; ++a) {
    if (!control_points_.row(a).allFinite()) {
      throw make_error("control point ", a, " of the triangular NURBS surface is not finite");
    }
  }
  if (weights_.size() == 0) {
    weights_ = Eigen::VectorXd::Ones(count);
  } else if (weights_.size() != count) {
    throw make_error("triangular NURBS surface has ", weights_.size(), " weights for ", count,
                     " control points");
  }
  for (int a = 0; a < count; ++a) {
    if (!(weights_[a] > 0.0) || !std::isfinite(weights_[a])) {
      throw make_error("weight ", a, " is ", weights_[a], " (weights must be positive and finite)");
    }
  }
  rational_ = (weights_.array() != weights_[0]).any();
  packed_points_ = control_points_;
}

TriangularControlNet TriangularNurbsSurface::control_net() const {
  TriangularControlNet net;
  net.positions = packed_points_.data();
  net.position_stride = 3;
  net.weights = weights_.data();
  return net;
}

std::array<Eigen::Vector3d, 6> TriangularNurbsSurface::derivatives_in_triangle(
    int t, const Eigen::Vector2d& u, int order) const {
  TriangularBasisValues values;
  basis_->evaluate_in_triangle(t, u, order, values);
  TriangularRationalJacobian jacobian;
  triangular_rational_jacobian(values, order, control_net(), false, jacobian);
  return jacobian.point;
}

std::array<Eigen::Vector3d, 6> TriangularNurbsSurface::derivatives(const Eigen::Vector2d& u,
                                                                   int order) const {
  const int t = basis_->triangulation().locate(u);
  if (t < 0) {
    throw make_error("point (", u.x(), ", ", u.y(), ") is outside the triangulated domain");
  }
  return derivatives_in_triangle(t, u, order);
}

Eigen::Vector3d TriangularNurbsSurface::point(const Eigen::Vector2d& u) const {
  return derivatives(u, 0)[0];
}

Eigen::Vector3d TriangularNurbsSurface::unit_normal(const Eigen::Vector2d& u) const {
  const auto d = derivatives(u, 1);
  const Eigen::Vector3d normal = d[1].cross(d[2]);
  const double length = normal.norm();
  if (!(length > 1e-300)) {
    throw make_error("triangular NURBS surface has no normal at (", u.x(), ", ", u.y(),
                     "): the tangents are parallel");
  }
  return normal / length;
}

TriangularNurbsSurface flat_triangular_surface(
    std::shared_ptr<const TriangularBSplineBasis> basis) {
  if (!basis) {
    throw make_error("flat triangular surface without a basis");
  }
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(basis->function_count(), 3);
  points.leftCols<2>() = basis->domain_points();
  return {std::move(basis), std::move(points)};
}

}  // namespace dnurbs
