#include "nurbs/triangular_nurbs_surface.h"

#include <cmath>

#include <Eigen/Geometry>

#include "core/error.h"

namespace dnurbs {

namespace {

// Leibniz terms of the quotient rule for quantity alpha (x, x_u, x_v, x_uu, x_uv, x_vv):
// D^alpha (W phi) = sum over splits alpha = beta + rest of coefficient D^beta W D^rest phi.
// Listed are the splits with beta != 0 (the beta = 0 term is W D^alpha phi).
struct LeibnizTerm {
  int beta;
  int rest;
  double coefficient;
};
struct LeibnizTerms {
  int count;
  std::array<LeibnizTerm, 3> terms;
};
constexpr std::array<LeibnizTerms, 6> kLeibniz = {{
    {0, {}},
    {1, {{{1, 0, 1.0}}}},
    {1, {{{2, 0, 1.0}}}},
    {2, {{{1, 1, 2.0}, {3, 0, 1.0}}}},
    {3, {{{1, 2, 1.0}, {2, 1, 1.0}, {4, 0, 1.0}}}},
    {2, {{{2, 2, 2.0}, {5, 0, 1.0}}}},
}};

int quantity_count(int order) {
  return order == 0 ? 1 : (order == 1 ? 3 : 6);
}

}  // namespace

void triangular_rational_jacobian(const TriangularBasisValues& basis, int order,
                                  const TriangularControlNet& net, bool with_weight_columns,
                                  TriangularRationalJacobian& jacobian) {
  const int n = basis.count;
  const int quantities = quantity_count(order);
  jacobian.order = order;
  jacobian.rational.setZero(6, n);
  jacobian.phi.setZero(6, n);

  // Weight function W^alpha = sum_a w_a N_a^alpha.
  std::array<double, 6> weight_sum{};
  for (int a = 0; a < n; ++a) {
    const std::ptrdiff_t node = basis.function[static_cast<size_t>(a)];
    const double w = net.weights[node * net.weight_stride];
    for (int alpha = 0; alpha < quantities; ++alpha) {
      weight_sum[static_cast<size_t>(alpha)] += w * basis.value(alpha, a);
    }
  }
  const double inverse_weight = 1.0 / weight_sum[0];
  jacobian.weight_sum = weight_sum[0];

  // phi_a = N_a / W by the quotient rule: W phi^alpha = N^alpha - sum_{beta != 0} c W^beta
  // phi^rest.
  for (int alpha = 0; alpha < quantities; ++alpha) {
    const LeibnizTerms& leibniz = kLeibniz[static_cast<size_t>(alpha)];
    for (int a = 0; a < n; ++a) {
      double value = basis.value(alpha, a);
      for (int t = 0; t < leibniz.count; ++t) {
        const LeibnizTerm& term = leibniz.terms[static_cast<size_t>(t)];
        value -= term.coefficient * weight_sum[static_cast<size_t>(term.beta)] *
                 jacobian.phi(term.rest, a);
      }
      jacobian.phi(alpha, a) = value * inverse_weight;
    }
  }

  // R_a^alpha = w_a phi_a^alpha and x^alpha = sum_a R_a^alpha P_a.
  for (auto& point : jacobian.point) {
    point.setZero();
  }
  for (int a = 0; a < n; ++a) {
    const std::ptrdiff_t node = basis.function[static_cast<size_t>(a)];
    const double w = net.weights[node * net.weight_stride];
    const Eigen::Map<const Eigen::Vector3d> position(net.positions + node * net.position_stride);
    for (int alpha = 0; alpha < quantities; ++alpha) {
      const double r = w * jacobian.phi(alpha, a);
      jacobian.rational(alpha, a) = r;
      jacobian.point[static_cast<size_t>(alpha)] += r * position;
    }
  }
  if (!with_weight_columns) {
    return;
  }

  // E_a^alpha = D^alpha [phi_a (P_a - x)] = phi_a^alpha P_a - sum_{beta <= alpha} c phi^beta
  // x^rest.
  for (int alpha = 0; alpha < 6; ++alpha) {
    jacobian.weight_column[static_cast<size_t>(alpha)].setZero(3, n);
  }
  for (int alpha = 0; alpha < quantities; ++alpha) {
    auto& column = jacobian.weight_column[static_cast<size_t>(alpha)];
    const LeibnizTerms& leibniz = kLeibniz[static_cast<size_t>(alpha)];
    for (int a = 0; a < n; ++a) {
      const std::ptrdiff_t node = basis.function[static_cast<size_t>(a)];
      const Eigen::Map<const Eigen::Vector3d> position(net.positions + node * net.position_stride);
      Eigen::Vector3d value = jacobian.phi(alpha, a) * position -
                              jacobian.phi(0, a) * jacobian.point[static_cast<size_t>(alpha)];
      for (int t = 0; t < leibniz.count; ++t) {
        const LeibnizTerm& term = leibniz.terms[static_cast<size_t>(t)];
        value -= term.coefficient * jacobian.phi(term.beta, a) *
                 jacobian.point[static_cast<size_t>(term.rest)];
      }
      column.col(a) = value;
    }
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
