#include "dnurbs/dynamics/core/homogeneous_point.h"

namespace dnurbs {

namespace {

// Number of terms with alpha < quantities (quantities 1, 3 or 6).
int term_count(int quantities) {
  return kLeibnizFirst[static_cast<size_t>(quantities)];
}
// A term whose alpha has a v derivative beyond the point's order_v is skipped (its beta and
// alpha - beta may not, but then alpha itself has no basis).
bool skipped(const LeibnizTerm& term, int order_v) {
  return kQuantityOrderV[static_cast<size_t>(term.alpha)] > order_v;
}

}  // namespace

void homogeneous_point(const HomogeneousSums& sums, int order, int order_v,
                       HomogeneousPoint& point) {
  const int quantities = quantity_count(order);
  const int terms = term_count(quantities);
  point.quantities = quantities;
  point.order_v = order_v;
  // W V = 1: V^0 = 1 / W, V^alpha = -V^0 sum_{beta != 0} C W^beta V^(alpha - beta)
  const double inverse = 1.0 / sums[0][3];
  point.inverse_weight.fill(0.0);
  point.inverse_weight[0] = inverse;
  for (int t = 1; t < terms; ++t) {
    const LeibnizTerm& term = kLeibnizTerms[static_cast<size_t>(t)];
    if (term.beta != 0 && !skipped(term, order_v)) {
      point.inverse_weight[static_cast<size_t>(term.alpha)] -=
          inverse * term.coefficient * sums[static_cast<size_t>(term.beta)][3] *
          point.inverse_weight[static_cast<size_t>(term.rest)];
    }
  }
  // x = A V: x^alpha = sum_beta C A^beta V^(alpha - beta)
  for (int alpha = 0; alpha < quantities; ++alpha) {
    point.point[static_cast<size_t>(alpha)].setZero();
  }
  for (int t = 0; t < terms; ++t) {
    const LeibnizTerm& term = kLeibnizTerms[static_cast<size_t>(t)];
    if (skipped(term, order_v)) {
      continue;
    }
    point.point[static_cast<size_t>(term.alpha)] +=
        (term.coefficient * point.inverse_weight[static_cast<size_t>(term.rest)]) *
        sums[static_cast<size_t>(term.beta)].head<3>();
  }
}

Eigen::Vector3d rational_rate(const HomogeneousPoint& point, const Eigen::Vector4d& rate_sum) {
  return point.inverse_weight[0] * (rate_sum.head<3>() - rate_sum[3] * point.point[0]);
}

void homogeneous_force_density(const HomogeneousPoint& point,
                               const std::array<Eigen::Vector3d, kQuantityCount>& h,
                               HomogeneousSums& density) {
  const int quantities = point.quantities;
  const int terms = term_count(quantities);
  std::array<double, kQuantityCount> s{};
  for (int beta = 0; beta < quantities; ++beta) {
    density[static_cast<size_t>(beta)].setZero();
  }
  for (int t = 0; t < terms; ++t) {
    const LeibnizTerm& term = kLeibnizTerms[static_cast<size_t>(t)];
    if (skipped(term, point.order_v)) {
      continue;
    }
    const Eigen::Vector3d& h_alpha = h[static_cast<size_t>(term.alpha)];
    density[static_cast<size_t>(term.beta)].head<3>() +=
        (term.coefficient * point.inverse_weight[static_cast<size_t>(term.rest)]) * h_alpha;
    s[static_cast<size_t>(term.beta)] +=
        term.coefficient * point.point[static_cast<size_t>(term.rest)].dot(h_alpha);
  }
  // -T_gamma = -sum_{beta >= gamma} C V^(beta - gamma) s_beta
  for (int t = 0; t < terms; ++t) {
    const LeibnizTerm& term = kLeibnizTerms[static_cast<size_t>(t)];
    if (skipped(term, point.order_v)) {
      continue;
    }
    density[static_cast<size_t>(term.beta)][3] -=
        term.coefficient * point.inverse_weight[static_cast<size_t>(term.rest)] *
        s[static_cast<size_t>(term.alpha)];
  }
}

}  // namespace dnurbs
