#include "dnurbs/nurbs/jacobian.h"

#include <vector>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// Multi-indices alpha = (k, l) of the quantities, in order of total degree; curves use l = 0.
struct MultiIndex {
  int k;
  int l;
};
constexpr std::array<MultiIndex, 6> kSurfaceIndices = {
    {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}}};
constexpr std::array<MultiIndex, 3> kCurveIndices = {{{0, 0}, {1, 0}, {2, 0}}};

int quantity_count(int order, bool surface) {
  if (order < 0 || order > 2) {
    throw make_error("Jacobian derivative order ", order, " is outside 0..2");
  }
  return surface ? (order + 1) * (order + 2) / 2 : order + 1;
}

double binomial(int n, int k) {
  return (k == 0 || k == n) ? 1.0 : static_cast<double>(n);
}

// Product binomial C(alpha, beta) for the orders <= 2 used here.
double multi_binomial(MultiIndex alpha, MultiIndex beta) {
  return binomial(alpha.k, beta.k) * binomial(alpha.l, beta.l);
}

// Position of multi-index (k, l) in the quantity list.
template <size_t N>
int position(const std::array<MultiIndex, N>& indices, int k, int l) {
  for (size_t q = 0; q < N; ++q) {
    if (indices[q].k == k && indices[q].l == l) {
      return static_cast<int>(q);
    }
  }
  return -1;
}

// Shared core for curves and surfaces. Inputs per active control point a and quantity alpha:
// B(alpha, a) the non-rational tensor basis derivative, w(a) the weight, P(a) the point.
// Outputs: rational basis derivatives R(alpha, a) (Terzopoulos 2003, eq. 1.23: dx^(alpha)/dP_a = R
// I_3), the derivatives x^(alpha), and when free, dx^(alpha)/dw_a from differentiating A^(alpha) =
// sum_{beta<=alpha} C(alpha,beta) W^(beta) x^(alpha-beta) with respect to w_a:
//   W dx^(alpha) = B^(alpha) P - sum_{beta<=alpha} C B^(beta) x^(alpha-beta)
//                  - sum_{0<beta<=alpha} C W^(beta) dx^(alpha-beta).
template <size_t N, typename BasisMatrix, typename WeightColumns, typename Points>
void rational_jacobian(const std::array<MultiIndex, N>& indices, int quantities, int active,
                       const BasisMatrix& nonrational, const double* weights,
                       const Eigen::MatrixX3d& control_points, const int* control_point,
                       bool is_rational, WeightMode mode, BasisMatrix& rational,
                       WeightColumns& weight_column, Points& point_derivatives) {
  std::array<double, N> weight_derivative{};
  for (int q = 0; q < quantities; ++q) {
    double sum = 0.0;
    for (int a = 0; a < active; ++a) {
      sum += nonrational(q, a) * weights[a];
    }
    // Equal weights: W is constant, so its derivatives are exactly zero (not sums of rounding).
    weight_derivative[static_cast<size_t>(q)] = (q == 0 || is_rational) ? sum : 0.0;
  }
  const double w0 = weight_derivative[0];
  for (int q = 0; q < quantities; ++q) {
    const MultiIndex alpha = indices[static_cast<size_t>(q)];
    for (int a = 0; a < active; ++a) {
      double value = nonrational(q, a) * weights[a];
      for (int p = 1; p <= q; ++p) {
        const MultiIndex beta = indices[static_cast<size_t>(p)];
        if (beta.k <= alpha.k && beta.l <= alpha.l) {
          const int rest = position(indices, alpha.k - beta.k, alpha.l - beta.l);
          value -= multi_binomial(alpha, beta) * weight_derivative[static_cast<size_t>(p)] *
                   rational(rest, a);
        }
      }
      rational(q, a) = value / w0;
    }
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int a = 0; a < active; ++a) {
      x += rational(q, a) * control_points.row(control_point[a]).transpose();
    }
    point_derivatives[static_cast<size_t>(q)] = x;
  }
  if (mode != WeightMode::kFree) {
    return;
  }
  for (int q = 0; q < quantities; ++q) {
    const MultiIndex alpha = indices[static_cast<size_t>(q)];
    for (int a = 0; a < active; ++a) {
      Eigen::Vector3d value = nonrational(q, a) * control_points.row(control_point[a]).transpose();
      for (int p = 0; p <= q; ++p) {
        const MultiIndex beta = indices[static_cast<size_t>(p)];
        if (beta.k > alpha.k || beta.l > alpha.l) {
          continue;
        }
        const int rest = position(indices, alpha.k - beta.k, alpha.l - beta.l);
        const double c = multi_binomial(alpha, beta);
        value -= c * nonrational(p, a) * point_derivatives[static_cast<size_t>(rest)];
        if (p > 0) {
          value -= c * weight_derivative[static_cast<size_t>(p)] *
                   weight_column[static_cast<size_t>(rest)].col(a);
        }
      }
      weight_column[static_cast<size_t>(q)].col(a) = value / w0;
    }
  }
}

}  // namespace

void curve_jacobian(const NurbsCurve& curve, double u, int order, WeightMode mode,
                    CurveJacobian& jacobian) {
  const int quantities = quantity_count(order, false);
  const KnotVector& knots = curve.knots();
  const int span = knots.find_span(u);
  BasisDerivatives basis;
  basis_functions_with_derivatives(knots, span, knots.to_domain(u), order, basis);
  const int active = curve.degree() + 1;
  jacobian.order = order;
  jacobian.active_count = active;
  std::array<double, kMaxDegree + 1> weights{};
  Eigen::Matrix<double, 3, kMaxDegree + 1> nonrational;
  for (int a = 0; a < active; ++a) {
    const int index = knots.control_point_index(span, a);
    jacobian.control_point[static_cast<size_t>(a)] = index;
    weights[static_cast<size_t>(a)] = curve.weights()[index];
    for (int q = 0; q < quantities; ++q) {
      nonrational(q, a) = basis(q, a);
    }
  }
  std::array<Eigen::Vector3d, 3> points;
  rational_jacobian(kCurveIndices, quantities, active, nonrational, weights.data(),
                    curve.control_points(), jacobian.control_point.data(), curve.is_rational(),
                    mode, jacobian.basis, jacobian.weight_column, points);
  jacobian.point_derivatives.resize(quantities, 3);
  for (int q = 0; q < quantities; ++q) {
    jacobian.point_derivatives.row(q) = points[static_cast<size_t>(q)].transpose();
  }
}

void surface_jacobian(const NurbsSurface& surface, double u, double v, int order, WeightMode mode,
                      SurfaceJacobian& jacobian) {
  const int quantities = quantity_count(order, true);
  const KnotVector& knots_u = surface.knots_u();
  const KnotVector& knots_v = surface.knots_v();
  const int span_u = knots_u.find_span(u);
  const int span_v = knots_v.find_span(v);
  BasisDerivatives basis_u;
  BasisDerivatives basis_v;
  basis_functions_with_derivatives(knots_u, span_u, knots_u.to_domain(u), order, basis_u);
  basis_functions_with_derivatives(knots_v, span_v, knots_v.to_domain(v), order, basis_v);
  const int p = surface.degree_u();
  const int q_degree = surface.degree_v();
  const int active = (p + 1) * (q_degree + 1);
  jacobian.order = order;
  jacobian.active_count = active;
  jacobian.basis.resize(6, active);
  for (auto& column : jacobian.weight_column) {
    column.resize(3, active);
  }
  std::array<double, SurfaceJacobian::kMaxActive> weights{};
  Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, SurfaceJacobian::kMaxActive> nonrational(6,
                                                                                          active);
  for (int a = 0; a <= p; ++a) {
    const int i = knots_u.control_point_index(span_u, a);
    for (int b = 0; b <= q_degree; ++b) {
      const int local = a * (q_degree + 1) + b;
      const int index = surface.control_point_index(i, knots_v.control_point_index(span_v, b));
      jacobian.control_point[static_cast<size_t>(local)] = index;
      weights[static_cast<size_t>(local)] = surface.weights()[index];
      for (int quantity = 0; quantity < quantities; ++quantity) {
        const MultiIndex alpha = kSurfaceIndices[static_cast<size_t>(quantity)];
        nonrational(quantity, local) = basis_u(alpha.k, a) * basis_v(alpha.l, b);
      }
    }
  }
  rational_jacobian(kSurfaceIndices, quantities, active, nonrational, weights.data(),
                    surface.control_points(), jacobian.control_point.data(), surface.is_rational(),
                    mode, jacobian.basis, jacobian.weight_column, jacobian.point_derivatives);
}

namespace {

template <typename Jacobian>
Eigen::SparseMatrix<double> sparse_from(const Jacobian& jacobian, int quantity, WeightMode mode,
                                        int control_point_count) {
  const int stride = coordinates_per_control_point(mode);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(jacobian.active_count) * 6);
  for (int a = 0; a < jacobian.active_count; ++a) {
    const int first = stride * jacobian.control_point[static_cast<size_t>(a)];
    for (int c = 0; c < 3; ++c) {
      entries.emplace_back(c, first + c, jacobian.basis(quantity, a));
      if (mode == WeightMode::kFree) {
        entries.emplace_back(c, first + 3,
                             jacobian.weight_column[static_cast<size_t>(quantity)](c, a));
      }
    }
  }
  Eigen::SparseMatrix<double> matrix(3, stride * control_point_count);
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

}  // namespace

Eigen::SparseMatrix<double> to_sparse_matrix(const CurveJacobian& jacobian, CurveQuantity quantity,
                                             WeightMode mode, int control_point_count) {
  const int index = static_cast<int>(quantity);
  if (index > jacobian.order) {
    throw make_error("curve Jacobian holds derivatives up to order ", jacobian.order,
                     ", asked for order ", index);
  }
  return sparse_from(jacobian, index, mode, control_point_count);
}

Eigen::SparseMatrix<double> to_sparse_matrix(const SurfaceJacobian& jacobian,
                                             SurfaceQuantity quantity, WeightMode mode,
                                             int control_point_count) {
  const int index = static_cast<int>(quantity);
  if (index >= (jacobian.order + 1) * (jacobian.order + 2) / 2) {
    throw make_error("surface Jacobian holds derivatives up to order ", jacobian.order,
                     ", asked for quantity ", index);
  }
  return sparse_from(jacobian, index, mode, control_point_count);
}

}  // namespace dnurbs

namespace dnurbs {
namespace {

// Second directional derivatives of x^(alpha) = A^(alpha) / W along (dP, dw). With
// A^(alpha) = sum_{beta<=alpha} C(alpha,beta) W^(beta) x^(alpha-beta) (Leibniz), A bilinear in
// (w, P) and W linear in w, differentiating once and twice gives
//   W Dx   = DA  - sum_{beta} C DW^(beta) x^(alpha-beta)      - sum_{beta>0} C W^(beta) Dx^(..)
//   W D2x  = D2A - sum_{beta} 2 C DW^(beta) Dx^(alpha-beta)   - sum_{beta>0} C W^(beta) D2x^(..)
// with DA = sum B (dw P + w dP), D2A = 2 sum B dw dP, DW = sum B dw.
using ActiveScalars = std::array<double, SurfaceJacobian::kMaxActive>;
using ActivePoints = std::array<Eigen::Vector3d, SurfaceJacobian::kMaxActive>;

template <size_t N, typename BasisMatrix>
void rational_second_directional(const std::array<MultiIndex, N>& indices, int quantities,
                                 int active, const BasisMatrix& nonrational, const ActiveScalars& w,
                                 const ActivePoints& P, const ActiveScalars& dw,
                                 const ActivePoints& dP, std::array<Eigen::Vector3d, N>& second) {
  std::array<double, N> W{};
  std::array<double, N> DW{};
  std::array<Eigen::Vector3d, N> A;
  std::array<Eigen::Vector3d, N> DA;
  std::array<Eigen::Vector3d, N> D2A;
  std::array<Eigen::Vector3d, N> x;
  std::array<Eigen::Vector3d, N> Dx;
  for (int q = 0; q < quantities; ++q) {
    const auto s = static_cast<size_t>(q);
    A[s].setZero();
    DA[s].setZero();
    D2A[s].setZero();
    for (int a = 0; a < active; ++a) {
      const auto t = static_cast<size_t>(a);
      const double B = nonrational(q, a);
      W[s] += B * w[t];
      DW[s] += B * dw[t];
      A[s] += B * w[t] * P[t];
      DA[s] += B * (dw[t] * P[t] + w[t] * dP[t]);
      D2A[s] += 2.0 * B * dw[t] * dP[t];
    }
  }
  for (int q = 0; q < quantities; ++q) {
    const MultiIndex alpha = indices[static_cast<size_t>(q)];
    Eigen::Vector3d value = A[static_cast<size_t>(q)];
    Eigen::Vector3d first = DA[static_cast<size_t>(q)];
    Eigen::Vector3d twice = D2A[static_cast<size_t>(q)];
    for (int p = 1; p <= q; ++p) {
      const MultiIndex beta = indices[static_cast<size_t>(p)];
      if (beta.k > alpha.k || beta.l > alpha.l) {
        continue;
      }
      const auto rest = static_cast<size_t>(position(indices, alpha.k - beta.k, alpha.l - beta.l));
      const double c = multi_binomial(alpha, beta);
      const auto b = static_cast<size_t>(p);
      value -= c * W[b] * x[rest];
      first -= c * (W[b] * Dx[rest] + DW[b] * x[rest]);
      twice -= c * (W[b] * second[rest] + 2.0 * DW[b] * Dx[rest]);
    }
    // The beta = 0 terms of Dx and D2x involve x^(alpha) and Dx^(alpha) themselves.
    const auto s = static_cast<size_t>(q);
    x[s] = value / W[0];
    Dx[s] = (first - DW[0] * x[s]) / W[0];
    second[s] = (twice - 2.0 * DW[0] * Dx[s]) / W[0];
  }
}

}  // namespace

void curve_jacobian_rate(const NurbsCurve& curve, double u, int order,
                         const Eigen::MatrixX3d& point_rates, const Eigen::VectorXd& weight_rates,
                         CurveDerivatives& result) {
  const int quantities = quantity_count(order, false);
  if (point_rates.rows() != curve.control_point_count() ||
      weight_rates.size() != curve.control_point_count()) {
    throw make_error("curve_jacobian_rate needs ", curve.control_point_count(),
                     " point and weight rates, got ", point_rates.rows(), " and ",
                     weight_rates.size());
  }
  const KnotVector& knots = curve.knots();
  const int span = knots.find_span(u);
  BasisDerivatives basis;
  basis_functions_with_derivatives(knots, span, knots.to_domain(u), order, basis);
  const int active = curve.degree() + 1;
  ActiveScalars w{};
  ActiveScalars dw{};
  ActivePoints P;
  ActivePoints dP;
  for (int a = 0; a < active; ++a) {
    const int index = knots.control_point_index(span, a);
    const auto t = static_cast<size_t>(a);
    w[t] = curve.weights()[index];
    dw[t] = weight_rates[index];
    P[t] = curve.control_points().row(index).transpose();
    dP[t] = point_rates.row(index).transpose();
  }
  std::array<Eigen::Vector3d, 3> second;
  rational_second_directional(kCurveIndices, quantities, active, basis, w, P, dw, dP, second);
  result.resize(quantities, 3);
  for (int q = 0; q < quantities; ++q) {
    result.row(q) = second[static_cast<size_t>(q)].transpose();
  }
}

void surface_jacobian_rate(const NurbsSurface& surface, double u, double v, int order,
                           const Eigen::MatrixX3d& point_rates, const Eigen::VectorXd& weight_rates,
                           std::array<Eigen::Vector3d, 6>& result) {
  const int quantities = quantity_count(order, true);
  if (point_rates.rows() != surface.control_point_count() ||
      weight_rates.size() != surface.control_point_count()) {
    throw make_error("surface_jacobian_rate needs ", surface.control_point_count(),
                     " point and weight rates, got ", point_rates.rows(), " and ",
                     weight_rates.size());
  }
  const KnotVector& knots_u = surface.knots_u();
  const KnotVector& knots_v = surface.knots_v();
  const int span_u = knots_u.find_span(u);
  const int span_v = knots_v.find_span(v);
  BasisDerivatives basis_u;
  BasisDerivatives basis_v;
  basis_functions_with_derivatives(knots_u, span_u, knots_u.to_domain(u), order, basis_u);
  basis_functions_with_derivatives(knots_v, span_v, knots_v.to_domain(v), order, basis_v);
  const int q_degree = surface.degree_v();
  const int active = (surface.degree_u() + 1) * (q_degree + 1);
  ActiveScalars w{};
  ActiveScalars dw{};
  ActivePoints P;
  ActivePoints dP;
  Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, SurfaceJacobian::kMaxActive> nonrational(6,
                                                                                          active);
  for (int a = 0; a <= surface.degree_u(); ++a) {
    const int i = knots_u.control_point_index(span_u, a);
    for (int b = 0; b <= q_degree; ++b) {
      const int local = a * (q_degree + 1) + b;
      const int index = surface.control_point_index(i, knots_v.control_point_index(span_v, b));
      const auto t = static_cast<size_t>(local);
      w[t] = surface.weights()[index];
      dw[t] = weight_rates[index];
      P[t] = surface.control_points().row(index).transpose();
      dP[t] = point_rates.row(index).transpose();
      for (int quantity = 0; quantity < quantities; ++quantity) {
        const MultiIndex alpha = kSurfaceIndices[static_cast<size_t>(quantity)];
        nonrational(quantity, local) = basis_u(alpha.k, a) * basis_v(alpha.l, b);
      }
    }
  }
  rational_second_directional(kSurfaceIndices, quantities, active, nonrational, w, P, dw, dP,
                              result);
}

}  // namespace dnurbs
