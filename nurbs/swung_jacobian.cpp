#include "dnurbs/nurbs/swung_jacobian.h"

#include <cmath>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/basis_functions.h"

namespace dnurbs {
namespace {

// Derivative orders (k in u, l in v) of the quantities S, S_u, S_v, S_uu, S_uv, S_vv.
constexpr std::array<int, 6> kOrderU = {0, 1, 0, 2, 1, 0};
constexpr std::array<int, 6> kOrderV = {0, 0, 1, 0, 1, 2};
// binom(d, j) for d, j <= 2.
constexpr std::array<std::array<double, 3>, 3> kBinomial = {{{1, 0, 0}, {1, 1, 0}, {1, 2, 1}}};

int quantities_of_order(int order) {
  if (order < 0 || order > 2) {
    throw make_error("swung Jacobian order ", order, " is outside 0..2");
  }
  return order == 0 ? 1 : (order == 1 ? 3 : 6);
}

// D^d (phi_a phi_b) for d = 0..2 by the Leibniz rule.
std::array<double, 3> phi_products(const PlanarCurveSample& s, int a, int b) {
  return {s.phi(0, a) * s.phi(0, b), s.phi(1, a) * s.phi(0, b) + s.phi(0, a) * s.phi(1, b),
          s.phi(2, a) * s.phi(0, b) + 2.0 * s.phi(1, a) * s.phi(1, b) + s.phi(0, a) * s.phi(2, b)};
}

// Adds mu . d^2 c^(d) / dq dq of one curve (free weights) into `hessian` at local column `offset`,
// with 3 columns (two in-plane coordinates, weight) per active control point:
//   d^2 c / dP_a dw_b = delta_ab phi_a - w_a phi_a phi_b,
//   d^2 c / dw_a dw_b = -phi_a phi_b (P_a + P_b - 2 c),
// differentiated d times in the curve's parameter (the control points do not depend on it).
void add_curve_hessian(const PlanarCurveSample& s, int d, const Eigen::Vector2d& mu, int offset,
                       Eigen::MatrixXd& hessian) {
  const int n = s.degree + 1;
  std::array<double, 3> m{};
  for (int k = 0; k <= d; ++k) {
    m[static_cast<size_t>(k)] = mu.dot(s.point.col(k));
  }
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      const std::array<double, 3> products = phi_products(s, a, b);
      const double product = products[static_cast<size_t>(d)];
      const int position_a = offset + 3 * a;
      const int weight_b = offset + 3 * b + 2;
      for (int c = 0; c < 2; ++c) {
        const double value = mu[c] * ((a == b ? s.phi(d, a) : 0.0) - s.weight[a] * product);
        hessian(position_a + c, weight_b) += value;
        hessian(weight_b, position_a + c) += value;
      }
      if (b < a) {
        continue;
      }
      // D^d (phi_a phi_b (mu . c)) by the Leibniz rule.
      double with_point = 0.0;
      for (int j = 0; j <= d; ++j) {
        with_point += kBinomial[static_cast<size_t>(d)][static_cast<size_t>(j)] *
                      products[static_cast<size_t>(j)] * m[static_cast<size_t>(d - j)];
      }
      const double value =
          -mu.dot(s.control.col(a) + s.control.col(b)) * product + 2.0 * with_point;
      const int weight_a = offset + 3 * a + 2;
      hessian(weight_a, weight_b) += value;
      if (a != b) {
        hessian(weight_b, weight_a) += value;
      }
    }
  }
}

PlanarControlNet curve_net(const SwungLayout& layout, const double* q, int offset,
                           const double* fixed_weights) {
  PlanarControlNet net;
  net.positions = q + offset;
  net.position_stride = layout.per_control_point;
  if (layout.mode == WeightMode::kFree) {
    net.weights = q + offset + 2;
    net.weight_stride = 3;
  } else {
    net.weights = fixed_weights;
    net.weight_stride = 1;
  }
  return net;
}

// Samples of both curves of `surface` at (u, v) with q = its own coordinates.
void surface_samples(const SwungSurface& surface, double u, double v, const SwungLayout& layout,
                     const Eigen::VectorXd& q, PlanarCurveSample& profile,
                     PlanarCurveSample& trajectory) {
  planar_curve_basis(surface.profile().knots(), u, profile);
  planar_curve_basis(surface.trajectory().knots(), v, trajectory);
  planar_curve_rational(
      curve_net(layout, q.data(), layout.profile_offset(0), surface.profile().weights().data()),
      profile);
  planar_curve_rational(curve_net(layout, q.data(), layout.trajectory_offset(0),
                                  surface.trajectory().weights().data()),
                        trajectory);
}

}  // namespace

// -----------------------------------------------------------------------------------------------
// Coordinates

PlanarControlNet swung_profile_net(const SwungLayout& layout, const double* q,
                                   const double* fixed_weights) {
  return curve_net(layout, q, layout.profile_offset(0), fixed_weights);
}

PlanarControlNet swung_trajectory_net(const SwungLayout& layout, const double* q,
                                      const double* fixed_weights) {
  return curve_net(layout, q, layout.trajectory_offset(0), fixed_weights);
}

SwungLayout swung_layout(const SwungSurface& surface, WeightMode mode) {
  SwungLayout layout;
  layout.mode = mode;
  layout.per_control_point = mode == WeightMode::kFree ? 3 : 2;
  layout.profile_count = surface.profile().control_point_count();
  layout.trajectory_count = surface.trajectory().control_point_count();
  return layout;
}

Eigen::VectorXd swung_coordinates(const SwungSurface& surface, WeightMode mode) {
  const SwungLayout layout = swung_layout(surface, mode);
  Eigen::VectorXd q(layout.coordinate_count());
  const bool free = mode == WeightMode::kFree;
  for (int i = 0; i < layout.profile_count; ++i) {
    const int o = layout.profile_offset(i);
    q[o] = surface.profile().control_points()(i, 0);
    q[o + 1] = surface.profile().control_points()(i, 2);
    if (free) {
      q[o + 2] = surface.profile().weights()[i];
    }
  }
  for (int j = 0; j < layout.trajectory_count; ++j) {
    const int o = layout.trajectory_offset(j);
    q[o] = surface.trajectory().control_points()(j, 0);
    q[o + 1] = surface.trajectory().control_points()(j, 1);
    if (free) {
      q[o + 2] = surface.trajectory().weights()[j];
    }
  }
  return q;
}

SwungSurface swung_surface_at(const SwungSurface& surface, WeightMode mode,
                              const Eigen::Ref<const Eigen::VectorXd>& q) {
  const SwungLayout layout = swung_layout(surface, mode);
  if (q.size() != layout.coordinate_count()) {
    throw make_error("swung surface coordinate vector has ", q.size(), " entries, expected ",
                     layout.coordinate_count());
  }
  for (Eigen::Index k = 0; k < q.size(); ++k) {
    if (!std::isfinite(q[k])) {
      throw make_error("swung surface coordinate ", k, " is ", q[k]);
    }
  }
  const bool free = mode == WeightMode::kFree;
  Eigen::MatrixX3d profile = Eigen::MatrixX3d::Zero(layout.profile_count, 3);
  Eigen::VectorXd profile_weights = surface.profile().weights();
  for (int i = 0; i < layout.profile_count; ++i) {
    const int o = layout.profile_offset(i);
    profile(i, 0) = q[o];
    profile(i, 2) = q[o + 1];
    if (free) {
      profile_weights[i] = q[o + 2];
    }
  }
  Eigen::MatrixX3d trajectory = Eigen::MatrixX3d::Zero(layout.trajectory_count, 3);
  Eigen::VectorXd trajectory_weights = surface.trajectory().weights();
  for (int j = 0; j < layout.trajectory_count; ++j) {
    const int o = layout.trajectory_offset(j);
    trajectory(j, 0) = q[o];
    trajectory(j, 1) = q[o + 1];
    if (free) {
      trajectory_weights[j] = q[o + 2];
    }
  }
  return SwungSurface(NurbsCurve(surface.profile().knots(), profile, profile_weights),
                      NurbsCurve(surface.trajectory().knots(), trajectory, trajectory_weights),
                      surface.alpha());
}

// -----------------------------------------------------------------------------------------------
// Planar curve samples

void planar_curve_basis(const KnotVector& knots, double u, PlanarCurveSample& sample) {
  const double x = knots.to_domain(u);
  const int span = knots.find_span(x);
  BasisDerivatives derivatives;
  basis_functions_with_derivatives(knots, span, x, 2, derivatives);
  sample.degree = knots.degree();
  sample.basis.setZero();
  for (int a = 0; a <= sample.degree; ++a) {
    sample.control_point[static_cast<size_t>(a)] = knots.control_point_index(span, a);
    for (int d = 0; d < 3; ++d) {
      sample.basis(d, a) = derivatives(d, a);
    }
  }
}

void planar_curve_rational(const PlanarControlNet& net, PlanarCurveSample& s) {
  const int n = s.degree + 1;
  // Weight function weight_total^(d) = sum_a w_a N_a^(d).
  s.weight_sum.setZero();
  for (int a = 0; a < n; ++a) {
    const std::ptrdiff_t i = s.control_point[static_cast<size_t>(a)];
    s.weight[a] = net.weights[i * net.weight_stride];
    s.control(0, a) = net.positions[i * net.position_stride];
    s.control(1, a) = net.positions[i * net.position_stride + 1];
    s.weight_sum += s.weight[a] * s.basis.col(a);
  }
  const double weight_total = s.weight_sum[0];
  // phi_a = N_a / weight_total by the quotient rule (Piegl & Tiller A4.2 on the basis functions).
  s.point.setZero();
  for (int a = 0; a < n; ++a) {
    s.phi(0, a) = s.basis(0, a) / weight_total;
    s.phi(1, a) = (s.basis(1, a) - s.weight_sum[1] * s.phi(0, a)) / weight_total;
    s.phi(2, a) =
        (s.basis(2, a) - 2.0 * s.weight_sum[1] * s.phi(1, a) - s.weight_sum[2] * s.phi(0, a)) /
        weight_total;
    for (int d = 0; d < 3; ++d) {
      s.rational(d, a) = s.weight[a] * s.phi(d, a);
      s.point.col(d) += s.rational(d, a) * s.control.col(a);
    }
  }
  // E_a^(d) = D^d [phi_a (P_a - c)].
  for (int a = 0; a < n; ++a) {
    const Eigen::Vector2d offset = s.control.col(a) - s.point.col(0);
    s.weight_column[0].col(a) = s.phi(0, a) * offset;
    s.weight_column[1].col(a) = s.phi(1, a) * offset - s.phi(0, a) * s.point.col(1);
    s.weight_column[2].col(a) =
        s.phi(2, a) * offset - 2.0 * s.phi(1, a) * s.point.col(1) - s.phi(0, a) * s.point.col(2);
  }
}

void planar_curve_rates(const PlanarCurveSample& s, const PlanarControlNet& rates,
                        Eigen::Matrix<double, 2, 3>& first, Eigen::Matrix<double, 2, 3>& second) {
  first.setZero();
  second.setZero();
  Eigen::Vector3d weight_rate = Eigen::Vector3d::Zero();  // Wdot^(d)
  Eigen::Matrix<double, 2, 3> homogeneous_second;         // Addot^(d) = 2 sum N wdot Pdot
  homogeneous_second.setZero();
  const bool weights_move = rates.weights != nullptr;
  for (int a = 0; a <= s.degree; ++a) {
    const std::ptrdiff_t i = s.control_point[static_cast<size_t>(a)];
    const Eigen::Vector2d point_rate(rates.positions[i * rates.position_stride],
                                     rates.positions[i * rates.position_stride + 1]);
    const double w_rate = weights_move ? rates.weights[i * rates.weight_stride] : 0.0;
    for (int d = 0; d < 3; ++d) {
      first.col(d) +=
          s.rational(d, a) * point_rate + s.weight_column[static_cast<size_t>(d)].col(a) * w_rate;
      weight_rate[d] += s.basis(d, a) * w_rate;
      homogeneous_second.col(d) += 2.0 * s.basis(d, a) * w_rate * point_rate;
    }
  }
  if (!weights_move) {
    return;  // c is linear in the control points: no velocity-product term
  }
  // A^(d) = sum_j binom(d, j) c^(j) W^(d-j), twice differentiated along the rates (W is linear in
  // the weights, so its second rate vanishes), solved for c''^(d).
  for (int d = 0; d < 3; ++d) {
    Eigen::Vector2d value = homogeneous_second.col(d);
    for (int j = 0; j <= d; ++j) {
      const double binomial = kBinomial[static_cast<size_t>(d)][static_cast<size_t>(j)];
      value -= 2.0 * binomial * weight_rate[d - j] * first.col(j);
      if (j < d) {
        value -= binomial * s.weight_sum[d - j] * second.col(j);
      }
    }
    second.col(d) = value / s.weight_sum[0];
  }
}

// -----------------------------------------------------------------------------------------------
// Swung Jacobians

Eigen::Vector3d swung_point_derivative(const Eigen::Matrix<double, 2, 3>& profile_point,
                                       const Eigen::Matrix<double, 2, 3>& trajectory_point,
                                       double alpha, int quantity) {
  const int k = kOrderU[static_cast<size_t>(quantity)];
  const int l = kOrderV[static_cast<size_t>(quantity)];
  const double f = profile_point(0, k);
  const double h = profile_point(1, k);
  const double in_z = l == 0 ? 1.0 : 0.0;  // only S^(k,0) has a z component
  return {alpha * f * trajectory_point(0, l), alpha * f * trajectory_point(1, l), in_z * h};
}

void swung_jacobian(const PlanarCurveSample& profile, const PlanarCurveSample& trajectory,
                    double alpha, const SwungLayout& layout, int order, SwungJacobian& jacobian) {
  const int quantities = quantities_of_order(order);
  const Eigen::Index per = layout.per_control_point;
  const bool free = layout.mode == WeightMode::kFree;
  const int np = profile.degree + 1;
  const int nt = trajectory.degree + 1;
  jacobian.order = order;
  jacobian.profile_column_count = static_cast<int>(per * np);
  jacobian.column_count = static_cast<int>(per * (np + nt));
  for (int a = 0; a < np; ++a) {
    for (int c = 0; c < per; ++c) {
      jacobian.coordinate[static_cast<size_t>(per * a + c)] =
          layout.profile_offset(profile.control_point[static_cast<size_t>(a)]) + c;
    }
  }
  for (int b = 0; b < nt; ++b) {
    for (int c = 0; c < per; ++c) {
      jacobian.coordinate[static_cast<size_t>(per * (np + b) + c)] =
          layout.trajectory_offset(trajectory.control_point[static_cast<size_t>(b)]) + c;
    }
  }
  for (int quantity = 0; quantity < quantities; ++quantity) {
    const int k = kOrderU[static_cast<size_t>(quantity)];
    const int l = kOrderV[static_cast<size_t>(quantity)];
    const double f = profile.point(0, k);
    const Eigen::Vector2d g = trajectory.point.col(l);
    const double in_z = l == 0 ? 1.0 : 0.0;  // only S^(k,0) has a z component
    auto& columns = jacobian.columns[static_cast<size_t>(quantity)];
    columns.setZero(3, jacobian.column_count);
    jacobian.point_derivatives[static_cast<size_t>(quantity)] =
        swung_point_derivative(profile.point, trajectory.point, alpha, quantity);
    for (int a = 0; a < np; ++a) {
      const double r = profile.rational(k, a);
      columns.block<2, 1>(0, per * a) = alpha * r * g;
      columns(2, per * a + 1) = in_z * r;
      if (free) {
        const Eigen::Vector2d e = profile.weight_column[static_cast<size_t>(k)].col(a);
        columns.block<2, 1>(0, per * a + 2) = alpha * e.x() * g;
        columns(2, per * a + 2) = in_z * e.y();
      }
    }
    for (int b = 0; b < nt; ++b) {
      const int column = per * (np + b);
      const double r = alpha * f * trajectory.rational(l, b);
      columns(0, column) = r;
      columns(1, column + 1) = r;
      if (free) {
        columns.block<2, 1>(0, column + 2) =
            alpha * f * trajectory.weight_column[static_cast<size_t>(l)].col(b);
      }
    }
  }
}

void swung_jacobian(const SwungSurface& surface, double u, double v, int order, WeightMode mode,
                    SwungJacobian& jacobian) {
  const SwungLayout layout = swung_layout(surface, mode);
  const Eigen::VectorXd q = swung_coordinates(surface, mode);
  PlanarCurveSample profile;
  PlanarCurveSample trajectory;
  surface_samples(surface, u, v, layout, q, profile, trajectory);
  swung_jacobian(profile, trajectory, surface.alpha(), layout, order, jacobian);
}

void swung_jacobian_rate(const PlanarCurveSample& profile, const PlanarCurveSample& trajectory,
                         double alpha, const SwungLayout& layout, const double* rates, int order,
                         std::array<Eigen::Vector3d, 6>& result) {
  const int quantities = quantities_of_order(order);
  Eigen::Matrix<double, 2, 3> profile_first;
  Eigen::Matrix<double, 2, 3> profile_second;
  Eigen::Matrix<double, 2, 3> trajectory_first;
  Eigen::Matrix<double, 2, 3> trajectory_second;
  planar_curve_rates(profile, curve_net(layout, rates, layout.profile_offset(0), nullptr),
                     profile_first, profile_second);
  planar_curve_rates(trajectory, curve_net(layout, rates, layout.trajectory_offset(0), nullptr),
                     trajectory_first, trajectory_second);
  for (int quantity = 0; quantity < quantities; ++quantity) {
    const int k = kOrderU[static_cast<size_t>(quantity)];
    const int l = kOrderV[static_cast<size_t>(quantity)];
    // (f g)'' = f'' g + 2 f' g' + f g'' along the rates, f = p_x^(k), g = t^(l).
    const Eigen::Vector2d planar = alpha * (profile_second(0, k) * trajectory.point.col(l) +
                                            2.0 * profile_first(0, k) * trajectory_first.col(l) +
                                            profile.point(0, k) * trajectory_second.col(l));
    result[static_cast<size_t>(quantity)] =
        Eigen::Vector3d(planar.x(), planar.y(), l == 0 ? profile_second(1, k) : 0.0);
  }
}

void swung_jacobian_rate(const SwungSurface& surface, double u, double v, int order,
                         WeightMode mode, const Eigen::Ref<const Eigen::VectorXd>& rates,
                         std::array<Eigen::Vector3d, 6>& result) {
  const SwungLayout layout = swung_layout(surface, mode);
  if (rates.size() != layout.coordinate_count()) {
    throw make_error("swung surface rate vector has ", rates.size(), " entries, expected ",
                     layout.coordinate_count());
  }
  const Eigen::VectorXd q = swung_coordinates(surface, mode);
  PlanarCurveSample profile;
  PlanarCurveSample trajectory;
  surface_samples(surface, u, v, layout, q, profile, trajectory);
  swung_jacobian_rate(profile, trajectory, surface.alpha(), layout, rates.data(), order, result);
}

void swung_hessian_terms(const PlanarCurveSample& profile, const PlanarCurveSample& trajectory,
                         double alpha, const SwungLayout& layout, SurfaceQuantity quantity,
                         const Eigen::Vector3d& lambda, SwungHessianTerms& terms) {
  const auto index = static_cast<size_t>(quantity);
  const int k = kOrderU[index];
  const int l = kOrderV[index];
  const Eigen::Index per = layout.per_control_point;
  const int np = profile.degree + 1;
  const int nt = trajectory.degree + 1;
  const bool free = layout.mode == WeightMode::kFree;
  const Eigen::Vector2d lambda_planar = lambda.head<2>();
  terms.profile_order = k;
  terms.trajectory_order = l;
  // Between the curves: S^Q_x,y = alpha f g_x,y, so lambda . d^2 S / dp dt =
  // alpha grad_p f (x) grad_t (lambda_x g_x + lambda_y g_y).
  terms.profile_gradient.setZero(per * np);
  terms.trajectory_gradient.setZero(per * nt);
  for (int a = 0; a < np; ++a) {
    terms.profile_gradient[per * a] = alpha * profile.rational(k, a);  // f = p_x: no z
    if (free) {
      terms.profile_gradient[per * a + 2] =
          alpha * profile.weight_column[static_cast<size_t>(k)](0, a);
    }
  }
  for (int b = 0; b < nt; ++b) {
    terms.trajectory_gradient.segment<2>(per * b) = lambda_planar * trajectory.rational(l, b);
    if (free) {
      terms.trajectory_gradient[per * b + 2] =
          lambda_planar.dot(trajectory.weight_column[static_cast<size_t>(l)].col(b));
    }
  }
  // Within each curve (free weights only): the profile with mu = (alpha lambda . g, [l == 0]
  // lambda_z) on (p_x, p_z)^(k), the trajectory with mu = alpha f lambda_planar on t^(l).
  terms.profile_weight = Eigen::Vector2d(alpha * lambda_planar.dot(trajectory.point.col(l)),
                                         l == 0 ? lambda.z() : 0.0);
  terms.trajectory_weight = alpha * profile.point(0, k) * lambda_planar;
}

void add_planar_curve_hessian(const PlanarCurveSample& sample, int order, const Eigen::Vector2d& mu,
                              int offset, Eigen::MatrixXd& hessian) {
  if (order < 0 || order > 2) {
    throw make_error("planar curve Hessian order ", order, " is outside 0..2");
  }
  add_curve_hessian(sample, order, mu, offset, hessian);
}

void add_swung_hessian(const PlanarCurveSample& profile, const PlanarCurveSample& trajectory,
                       double alpha, const SwungLayout& layout, SurfaceQuantity quantity,
                       const Eigen::Vector3d& lambda, Eigen::MatrixXd& hessian) {
  SwungHessianTerms terms;
  swung_hessian_terms(profile, trajectory, alpha, layout, quantity, lambda, terms);
  const auto rows = terms.profile_gradient.size();
  const auto columns = terms.trajectory_gradient.size();
  // The outer product once, added to both blocks: exactly symmetric.
  const Eigen::MatrixXd cross = terms.profile_gradient * terms.trajectory_gradient.transpose();
  hessian.block(0, rows, rows, columns) += cross;
  hessian.block(rows, 0, columns, rows) += cross.transpose();
  if (layout.mode != WeightMode::kFree) {
    return;  // each curve is linear in its own control points
  }
  add_curve_hessian(profile, terms.profile_order, terms.profile_weight, 0, hessian);
  add_curve_hessian(trajectory, terms.trajectory_order, terms.trajectory_weight,
                    static_cast<int>(rows), hessian);
}

Eigen::SparseMatrix<double> to_sparse_matrix(const SwungJacobian& jacobian,
                                             SurfaceQuantity quantity, int coordinate_count) {
  const auto index = static_cast<size_t>(quantity);
  if (static_cast<int>(index) >= quantities_of_order(jacobian.order)) {
    throw make_error("swung Jacobian of order ", jacobian.order, " has no quantity ",
                     static_cast<int>(index));
  }
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(3 * static_cast<size_t>(jacobian.column_count));
  const auto& columns = jacobian.columns[index];
  for (int c = 0; c < jacobian.column_count; ++c) {
    for (int r = 0; r < 3; ++r) {
      if (columns(r, c) != 0.0) {
        triplets.emplace_back(r, jacobian.coordinate[static_cast<size_t>(c)], columns(r, c));
      }
    }
  }
  Eigen::SparseMatrix<double> result(3, coordinate_count);
  result.setFromTriplets(triplets.begin(), triplets.end());
  return result;
}

}  // namespace dnurbs
