#include "dnurbs/nurbs/nurbs_surface.h"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/rational_validation.h"

namespace dnurbs {
namespace {

double binomial(int n, int k) {
  double value = 1.0;
  for (int i = 1; i <= k; ++i) {
    value = value * (n - k + i) / i;
  }
  return value;
}

}  // namespace

void SurfaceDerivatives::reset(int order) {
  if (order < 0 || order > kMaxOrder) {
    throw make_error("surface derivative order ", order, " is outside 0..", kMaxOrder);
  }
  order_ = order;
  for (int k = 0; k <= order; ++k) {
    for (int l = 0; k + l <= order; ++l) {
      (*this)(k, l).setZero();
    }
  }
}

NurbsSurface::NurbsSurface(KnotVector knots_u, KnotVector knots_v, Eigen::MatrixX3d control_points,
                           Eigen::VectorXd weights)
    : knots_u_(std::move(knots_u)), knots_v_(std::move(knots_v)) {
  const int count = knots_u_.control_point_count() * knots_v_.control_point_count();
  if (control_points.rows() != count) {
    throw make_error("surface needs ", knots_u_.control_point_count(), " x ",
                     knots_v_.control_point_count(), " = ", count, " control points, got ",
                     control_points.rows());
  }
  check_control_points(control_points, count);
  control_points_ = std::move(control_points);
  if (weights.size() == 0) {
    weights = Eigen::VectorXd::Ones(count);
  }
  set_weights(weights);
}

void NurbsSurface::set_control_points(const Eigen::MatrixX3d& control_points) {
  check_control_points(control_points,
                       knots_u_.control_point_count() * knots_v_.control_point_count());
  control_points_ = control_points;
}

void NurbsSurface::set_weights(const Eigen::VectorXd& weights) {
  check_weights(weights, knots_u_.control_point_count() * knots_v_.control_point_count());
  weights_ = weights;
  rational_ = (weights_.array() != weights_[0]).any();
}

Eigen::Vector3d NurbsSurface::point(double u, double v) const {
  const int span_u = knots_u_.find_span(u);
  const int span_v = knots_v_.find_span(v);
  BasisValues basis_u;
  BasisValues basis_v;
  basis_functions(knots_u_, span_u, knots_u_.to_domain(u), basis_u);
  basis_functions(knots_v_, span_v, knots_v_.to_domain(v), basis_v);
  Eigen::Vector3d numerator = Eigen::Vector3d::Zero();
  double denominator = 0.0;
  for (int a = 0; a <= degree_u(); ++a) {
    const int i = knots_u_.control_point_index(span_u, a);
    for (int b = 0; b <= degree_v(); ++b) {
      const int index = control_point_index(i, knots_v_.control_point_index(span_v, b));
      const double weighted = basis_u[a] * basis_v[b] * weights_[index];
      numerator += weighted * control_points_.row(index).transpose();
      denominator += weighted;
    }
  }
  return numerator / denominator;
}

void NurbsSurface::derivatives(double u, double v, int order, SurfaceDerivatives& result) const {
  const int span_u = knots_u_.find_span(u);
  const int span_v = knots_v_.find_span(v);
  BasisDerivatives basis_u;
  BasisDerivatives basis_v;
  basis_functions_with_derivatives(knots_u_, span_u, knots_u_.to_domain(u), order, basis_u);
  basis_functions_with_derivatives(knots_v_, span_v, knots_v_.to_domain(v), order, basis_v);

  // Homogeneous derivatives A^(k,l) = sum N_a^(k) N_b^(l) w P and W^(k,l) likewise (the fourth
  // coordinate). The v-sums are formed first per row a, so each costs O((p+1)(q+1)).
  SurfaceDerivatives homogeneous;
  homogeneous.reset(order);
  std::array<double, (kMaxDerivativeOrder + 1) * (kMaxDerivativeOrder + 1)> weight_sums{};
  const auto weight_index = [](int k, int l) { return k * (kMaxDerivativeOrder + 1) + l; };
  for (int a = 0; a <= degree_u(); ++a) {
    const int i = knots_u_.control_point_index(span_u, a);
    std::array<Eigen::Vector3d, kMaxDerivativeOrder + 1> row_points;
    std::array<double, kMaxDerivativeOrder + 1> row_weights{};
    for (int l = 0; l <= order; ++l) {
      row_points[static_cast<size_t>(l)].setZero();
    }
    for (int b = 0; b <= degree_v(); ++b) {
      const int index = control_point_index(i, knots_v_.control_point_index(span_v, b));
      const double w = weights_[index];
      const Eigen::Vector3d weighted_point = w * control_points_.row(index).transpose();
      for (int l = 0; l <= order; ++l) {
        row_points[static_cast<size_t>(l)] += basis_v(l, b) * weighted_point;
        row_weights[static_cast<size_t>(l)] += basis_v(l, b) * w;
      }
    }
    for (int k = 0; k <= order; ++k) {
      for (int l = 0; k + l <= order; ++l) {
        homogeneous(k, l) += basis_u(k, a) * row_points[static_cast<size_t>(l)];
        weight_sums[static_cast<size_t>(weight_index(k, l))] +=
            basis_u(k, a) * row_weights[static_cast<size_t>(l)];
      }
    }
  }
  const auto weight = [&](int k, int l) {
    return weight_sums[static_cast<size_t>(weight_index(k, l))];
  };

  // Quotient rule on homogeneous coordinates, Piegl & Tiller A4.4 (with equal weights the
  // weight derivatives vanish exactly and S^(k,l) = A^(k,l) / w).
  result.reset(order);
  if (!rational_) {
    for (int k = 0; k <= order; ++k) {
      for (int l = 0; k + l <= order; ++l) {
        result(k, l) = homogeneous(k, l) / weights_[0];
      }
    }
    return;
  }
  for (int k = 0; k <= order; ++k) {
    for (int l = 0; k + l <= order; ++l) {
      Eigen::Vector3d value = homogeneous(k, l);
      for (int j = 1; j <= l; ++j) {
        value -= binomial(l, j) * weight(0, j) * result(k, l - j);
      }
      for (int i = 1; i <= k; ++i) {
        value -= binomial(k, i) * weight(i, 0) * result(k - i, l);
        Eigen::Vector3d mixed = Eigen::Vector3d::Zero();
        for (int j = 1; j <= l; ++j) {
          mixed += binomial(l, j) * weight(i, j) * result(k - i, l - j);
        }
        value -= binomial(k, i) * mixed;
      }
      result(k, l) = value / weight(0, 0);
    }
  }
}

SurfaceDerivatives NurbsSurface::derivatives(double u, double v, int order) const {
  SurfaceDerivatives result;
  derivatives(u, v, order, result);
  return result;
}

Eigen::Vector3d NurbsSurface::unit_normal(double u, double v) const {
  const SurfaceDerivatives d = derivatives(u, v, 2);
  const Eigen::Vector3d& su = d(1, 0);
  const Eigen::Vector3d& sv = d(0, 1);
  const Eigen::Vector3d normal = su.cross(sv);
  const double scale = su.norm() * sv.norm();
  if (normal.norm() > 1e-12 * scale && scale > 0.0) {
    return normal.normalized();
  }
  // Degenerate point: Sv (or Su) vanishes along a collapsed edge u = u0 (or v = v0). Moving into
  // the domain, Sv ~ (u - u0) Suv (or Su ~ (v - v0) Suv), so the limit normal is
  // sign(u - u0) Su x Suv (or sign(v - v0) Suv x Sv); the sign is negative at the domain end.
  const double u_side = knots_u_.to_domain(u) >= knots_u_.domain_end() ? -1.0 : 1.0;
  const double v_side = knots_v_.to_domain(v) >= knots_v_.domain_end() ? -1.0 : 1.0;
  const Eigen::Vector3d limit = sv.norm() <= su.norm()
                                    ? Eigen::Vector3d(u_side * su.cross(d(1, 1)))
                                    : Eigen::Vector3d(v_side * d(1, 1).cross(sv));
  if (limit.norm() > 0.0 && std::isfinite(limit.norm())) {
    return limit.normalized();
  }
  throw make_error("surface normal is undefined at (u, v) = (", u, ", ", v, ")");
}

SurfaceCurvature NurbsSurface::curvature(double u, double v) const {
  const SurfaceDerivatives d = derivatives(u, v, 2);
  const Eigen::Vector3d& su = d(1, 0);
  const Eigen::Vector3d& sv = d(0, 1);
  const Eigen::Vector3d cross = su.cross(sv);
  if (!(cross.norm() > 1e-12 * su.norm() * sv.norm()) || !std::isfinite(cross.norm())) {
    throw make_error("curvature is undefined at the degenerate point (u, v) = (", u, ", ", v, ")");
  }
  const Eigen::Vector3d normal = cross.normalized();
  // First (I) and second (II) fundamental forms; principal curvatures solve II x = k I x.
  Eigen::Matrix2d first;
  first << su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv);
  Eigen::Matrix2d second;
  second << d(2, 0).dot(normal), d(1, 1).dot(normal), d(1, 1).dot(normal), d(0, 2).dot(normal);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> solver(second, first);
  SurfaceCurvature result;
  result.principal_min = solver.eigenvalues()[0];
  result.principal_max = solver.eigenvalues()[1];
  result.gaussian = second.determinant() / first.determinant();
  result.mean =
      0.5 *
      (first(0, 0) * second(1, 1) - 2.0 * first(0, 1) * second(0, 1) + first(1, 1) * second(0, 0)) /
      first.determinant();
  const Eigen::Vector2d min_coefficients = solver.eigenvectors().col(0);
  const Eigen::Vector2d max_coefficients = solver.eigenvectors().col(1);
  result.direction_min = (min_coefficients[0] * su + min_coefficients[1] * sv).normalized();
  result.direction_max = (max_coefficients[0] * su + max_coefficients[1] * sv).normalized();
  return result;
}

}  // namespace dnurbs
