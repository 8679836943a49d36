#include "dnurbs/nurbs/span_cached_surface_evaluator.h"

#include <algorithm>
#include <array>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/basis_functions.h"

namespace dnurbs {
namespace {

constexpr int kHomogeneous = 4;  // w x, w y, w z, w
using Homogeneous = std::array<double, kHomogeneous>;
using TaylorTable = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor,
                                  kMaxDegree + 1, kMaxDegree + 1>;

/// Row a holds the s^a coefficients of the p + 1 basis functions non-zero on `span`, in the local
/// parameter s = (u - mid) / half: N_j(u) = sum_a N_j^(a)(mid) half^a / a! s^a (a Taylor
/// polynomial, exact because N_j is a degree-p polynomial on the span).
TaylorTable basis_taylor_coefficients(const KnotVector& knots, int span) {
  const int degree = knots.degree();
  const double start = knots[span];
  const double half = 0.5 * (knots[span + 1] - start);
  BasisDerivatives derivatives;
  basis_functions_with_derivatives(knots, span, start + half, degree, derivatives);
  TaylorTable table(degree + 1, degree + 1);
  double scale = 1.0;  // half^a / a!
  for (int a = 0; a <= degree; ++a) {
    table.row(a) = scale * derivatives.row(a);
    scale *= half / (a + 1);
  }
  return table;
}

std::vector<double> span_starts(const KnotVector& knots) {
  std::vector<double> starts;
  for (const int span : knots.non_empty_spans()) {
    starts.push_back(knots[span]);
  }
  starts.push_back(knots.domain_end());
  return starts;
}

std::vector<double> inverse_half_widths(const std::vector<double>& span_starts) {
  std::vector<double> inverses;
  for (std::size_t k = 0; k + 1 < span_starts.size(); ++k) {
    inverses.push_back(2.0 / (span_starts[k + 1] - span_starts[k]));
  }
  return inverses;
}

/// Horner's rule for a polynomial with vector coefficients c_0..c_n (the first `Components` of
/// each, `stride` doubles apart) and its derivatives up to Order: value[d] = d^d/dx^d sum c_a x^a.
template <int Components, int Order>
void horner(const double* coefficients, int degree, std::ptrdiff_t stride, double x,
            std::array<Homogeneous, Order + 1>& value) {
  std::array<Homogeneous, Order + 1> accumulator{};
  const double* last = coefficients + degree * stride;
  for (int c = 0; c < Components; ++c) {
    accumulator[0][c] = last[c];
  }
  for (int a = degree - 1; a >= 0; --a) {
    const double* coefficient = coefficients + a * stride;
    for (int d = Order; d >= 1; --d) {
      for (int c = 0; c < Components; ++c) {
        accumulator[d][c] = accumulator[d][c] * x + accumulator[d - 1][c];
      }
    }
    for (int c = 0; c < Components; ++c) {
      accumulator[0][c] = accumulator[0][c] * x + coefficient[c];
    }
  }
  // Horner's accumulators hold p^(d) / d!.
  double factorial = 1.0;
  for (int d = 0; d <= Order; ++d) {
    factorial *= d > 1 ? d : 1;
    for (int c = 0; c < Components; ++c) {
      value[d][c] = factorial * accumulator[d][c];
    }
  }
}

/// Homogeneous derivatives A^(k,l) (local parameters) of the patch, k + l <= Order: first the
/// s-polynomial of each t power with its s-derivatives, then those rows as polynomials in t.
template <int Components, int Order>
void patch_derivatives(const double* patch, int degree_u, int degree_v, double s, double t,
                       std::array<std::array<Homogeneous, Order + 1>, Order + 1>& homogeneous) {
  // rows[k][b]: d^k/ds^k of the s-polynomial with t power b.
  std::array<std::array<Homogeneous, kMaxDegree + 1>, Order + 1> rows;
  const std::ptrdiff_t row_stride = static_cast<std::ptrdiff_t>(degree_u + 1) * Components;
  for (int b = 0; b <= degree_v; ++b) {
    std::array<Homogeneous, Order + 1> value;
    horner<Components, Order>(patch + b * row_stride, degree_u, Components, s, value);
    for (int k = 0; k <= Order; ++k) {
      rows[static_cast<std::size_t>(k)][static_cast<std::size_t>(b)] =
          value[static_cast<std::size_t>(k)];
    }
  }
  const auto along_v = [&]<int Remaining>(int k) {
    std::array<Homogeneous, Remaining + 1> value;
    horner<Components, Remaining>(rows[static_cast<std::size_t>(k)][0].data(), degree_v,
                                  kHomogeneous, t, value);
    for (int l = 0; l <= Remaining; ++l) {
      homogeneous[static_cast<std::size_t>(k)][static_cast<std::size_t>(l)] =
          value[static_cast<std::size_t>(l)];
    }
  };
  along_v.template operator()<Order>(0);
  if constexpr (Order >= 1) {
    along_v.template operator()<Order - 1>(1);
  }
  if constexpr (Order >= 2) {
    along_v.template operator()<Order - 2>(2);
  }
}

/// S^(k,l), k + l <= Order, from a patch with `Components` doubles per coefficient (3: the
/// points of a non-rational surface, w = 1; 4: homogeneous w P, w).
template <int Components, int Order>
void surface_derivatives(const double* patch, int degree_u, int degree_v, double s, double t,
                         double inverse_half_u, double inverse_half_v, SurfaceDerivatives& result) {
  std::array<std::array<Homogeneous, Order + 1>, Order + 1> homogeneous;
  patch_derivatives<Components, Order>(patch, degree_u, degree_v, s, t, homogeneous);
  // Chain rule d/du = inverse_half_u d/ds, d/dv = inverse_half_v d/dt.
  result.reset(Order);
  std::array<std::array<double, Order + 1>, Order + 1> weight{};
  double scale_u = 1.0;
  for (int k = 0; k <= Order; ++k) {
    double scale = scale_u;
    for (int l = 0; k + l <= Order; ++l) {
      const Homogeneous& value =
          homogeneous[static_cast<std::size_t>(k)][static_cast<std::size_t>(l)];
      result(k, l) = scale * Eigen::Vector3d(value[0], value[1], value[2]);
      if constexpr (Components == kHomogeneous) {
        weight[static_cast<std::size_t>(k)][static_cast<std::size_t>(l)] = scale * value[3];
      }
      scale *= inverse_half_v;
    }
    scale_u *= inverse_half_u;
  }
  if constexpr (Components == kHomogeneous) {
    // Quotient rule on homogeneous coordinates (Piegl & Tiller A4.4 for k + l <= 2):
    // S^(k,l) = (A^(k,l) - sum_(i,j) != 0 binom(k,i) binom(l,j) w^(i,j) S^(k-i,l-j)) / w.
    const auto w = [&](int k, int l) {
      return weight[static_cast<std::size_t>(k)][static_cast<std::size_t>(l)];
    };
    const double inverse_w = 1.0 / w(0, 0);
    result(0, 0) *= inverse_w;
    if constexpr (Order >= 1) {
      result(1, 0) = (result(1, 0) - w(1, 0) * result(0, 0)) * inverse_w;
      result(0, 1) = (result(0, 1) - w(0, 1) * result(0, 0)) * inverse_w;
    }
    if constexpr (Order >= 2) {
      result(2, 0) =
          (result(2, 0) - 2.0 * w(1, 0) * result(1, 0) - w(2, 0) * result(0, 0)) * inverse_w;
      result(1, 1) = (result(1, 1) - w(1, 0) * result(0, 1) - w(0, 1) * result(1, 0) -
                      w(1, 1) * result(0, 0)) *
                     inverse_w;
      result(0, 2) =
          (result(0, 2) - 2.0 * w(0, 1) * result(0, 1) - w(0, 2) * result(0, 0)) * inverse_w;
    }
  }
}

template <int Components>
void surface_derivatives(const double* patch, int degree_u, int degree_v, double s, double t,
                         double inverse_half_u, double inverse_half_v, int order,
                         SurfaceDerivatives& result) {
  switch (order) {
    case 0:
      surface_derivatives<Components, 0>(patch, degree_u, degree_v, s, t, inverse_half_u,
                                         inverse_half_v, result);
      return;
    case 1:
      surface_derivatives<Components, 1>(patch, degree_u, degree_v, s, t, inverse_half_u,
                                         inverse_half_v, result);
      return;
    default:
      surface_derivatives<Components, 2>(patch, degree_u, degree_v, s, t, inverse_half_u,
                                         inverse_half_v, result);
  }
}

}  // namespace

SpanCachedSurfaceEvaluator::SpanCachedSurfaceEvaluator(const NurbsSurface& surface)
    : knots_u_(surface.knots_u()),
      knots_v_(surface.knots_v()),
      degree_u_(surface.degree_u()),
      degree_v_(surface.degree_v()),
      rational_(surface.is_rational()),
      span_starts_u_(span_starts(knots_u_)),
      span_starts_v_(span_starts(knots_v_)),
      inverse_half_widths_u_(inverse_half_widths(span_starts_u_)),
      inverse_half_widths_v_(inverse_half_widths(span_starts_v_)) {
  const std::vector<int> spans_u = knots_u_.non_empty_spans();
  const std::vector<int> spans_v = knots_v_.non_empty_spans();
  span_count_v_ = static_cast<int>(spans_v.size());
  components_ = rational_ ? kHomogeneous : 3;
  patch_size_ = (degree_u_ + 1) * (degree_v_ + 1) * components_;
  coefficients_.assign(spans_u.size() * spans_v.size() * static_cast<std::size_t>(patch_size_),
                       0.0);
  std::vector<TaylorTable> taylor_v;
  taylor_v.reserve(spans_v.size());
  for (const int span : spans_v) {
    taylor_v.push_back(basis_taylor_coefficients(knots_v_, span));
  }
  // Non-rational surfaces (all weights equal) are patches of the points themselves with w = 1.
  const auto homogeneous_point = [&](int index) {
    const double w = rational_ ? surface.weights()[index] : 1.0;
    const Eigen::Vector3d p = surface.control_points().row(index).transpose();
    return Homogeneous{w * p.x(), w * p.y(), w * p.z(), w};
  };
  for (std::size_t su = 0; su < spans_u.size(); ++su) {
    const int span_u = spans_u[su];
    const TaylorTable taylor_u = basis_taylor_coefficients(knots_u_, span_u);
    for (std::size_t sv = 0; sv < spans_v.size(); ++sv) {
      const int span_v = spans_v[sv];
      double* target = coefficients_.data() + (su * spans_v.size() + sv) * patch_size_;
      // C_ab = sum_i T_u(a, i) sum_j T_v(b, j) Pw_ij, the inner sums formed once per i.
      for (int i = 0; i <= degree_u_; ++i) {
        const int row = knots_u_.control_point_index(span_u, i);
        std::array<Homogeneous, kMaxDegree + 1> v_sums{};
        for (int j = 0; j <= degree_v_; ++j) {
          const Homogeneous pw = homogeneous_point(
              surface.control_point_index(row, knots_v_.control_point_index(span_v, j)));
          for (int b = 0; b <= degree_v_; ++b) {
            for (int c = 0; c < kHomogeneous; ++c) {
              v_sums[static_cast<std::size_t>(b)][static_cast<std::size_t>(c)] +=
                  taylor_v[sv](b, j) * pw[static_cast<std::size_t>(c)];
            }
          }
        }
        for (int b = 0; b <= degree_v_; ++b) {
          for (int a = 0; a <= degree_u_; ++a) {
            double* coefficient = target + (b * (degree_u_ + 1) + a) * components_;
            for (int c = 0; c < components_; ++c) {
              coefficient[c] +=
                  taylor_u(a, i) * v_sums[static_cast<std::size_t>(b)][static_cast<std::size_t>(c)];
            }
          }
        }
      }
    }
  }
}

SpanCachedSurfaceEvaluator::SpanLocation SpanCachedSurfaceEvaluator::locate(
    const KnotVector& knots, const std::vector<double>& span_starts,
    const std::vector<double>& inverse_half_widths, double parameter) {
  // Inside the domain no mapping is needed; NaN, wrapping and out-of-domain values go through
  // to_domain (which throws for the bad ones).
  const double u = parameter >= span_starts.front() && parameter <= span_starts.back()
                       ? parameter
                       : knots.to_domain(parameter);
  // Largest span whose start is <= u (the domain end belongs to the last span), by a binary
  // search whose halving step compiles to a conditional move: random parameters would otherwise
  // mispredict about half of the branches.
  const double* start = span_starts.data();
  std::size_t count = span_starts.size() - 1;
  while (count > 1) {
    const std::size_t half = count / 2;
    start = start[half] <= u ? start + half : start;
    count -= half;
  }
  const auto span = static_cast<std::size_t>(start - span_starts.data());
  const double inverse_half = inverse_half_widths[span];
  return {static_cast<int>(span), (u - start[0]) * inverse_half - 1.0, inverse_half};
}

SpanCachedSurfaceEvaluator::SpanLocation SpanCachedSurfaceEvaluator::locate_u(double u) const {
  return locate(knots_u_, span_starts_u_, inverse_half_widths_u_, u);
}

SpanCachedSurfaceEvaluator::SpanLocation SpanCachedSurfaceEvaluator::locate_v(double v) const {
  return locate(knots_v_, span_starts_v_, inverse_half_widths_v_, v);
}

Eigen::Vector3d SpanCachedSurfaceEvaluator::point(double u, double v) const {
  SurfaceDerivatives result;
  derivatives(u, v, 0, result);
  return result(0, 0);
}

void SpanCachedSurfaceEvaluator::derivatives(double u, double v, int order,
                                             SurfaceDerivatives& result) const {
  if (order < 0 || order > kMaxOrder) {
    throw make_error("span-cached derivative order ", order, " is outside 0..", kMaxOrder);
  }
  const SpanLocation at_u = locate_u(u);
  const SpanLocation at_v = locate_v(v);
  const double* coefficients = patch(at_u.span, at_v.span);
  if (rational_) {
    surface_derivatives<kHomogeneous>(coefficients, degree_u_, degree_v_, at_u.local, at_v.local,
                                      at_u.inverse_half, at_v.inverse_half, order, result);
  } else {
    surface_derivatives<3>(coefficients, degree_u_, degree_v_, at_u.local, at_v.local,
                           at_u.inverse_half, at_v.inverse_half, order, result);
  }
}

}  // namespace dnurbs
