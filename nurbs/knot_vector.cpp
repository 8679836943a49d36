#include "dnurbs/nurbs/knot_vector.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// Element i (an int index) of a std::array or std::vector.
template <typename Container>
auto& at(Container& container, int i) {
  return container[static_cast<size_t>(i)];
}

void check_degree(int degree) {
  if (degree < 1 || degree > kMaxDegree) {
    throw make_error("degree ", degree, " is outside 1..", kMaxDegree);
  }
}

}  // namespace

KnotVector::KnotVector(int degree, std::vector<double> knots)
    : degree_(degree), knots_(std::move(knots)) {
  check_degree(degree_);
  control_point_count_ = static_cast<int>(knots_.size()) - degree_ - 1;
  validate();
}

KnotVector::KnotVector(PeriodicTag, int degree, const std::vector<double>& period_knots)
    : degree_(degree), periodic_(true) {
  check_degree(degree_);
  const int n = static_cast<int>(period_knots.size()) - 1;
  if (n < degree + 1) {
    throw make_error("a periodic basis of degree ", degree, " needs at least ", degree + 2,
                     " period knots (", degree + 1, " control points), got ", n + 1);
  }
  for (size_t i = 0; i < period_knots.size(); ++i) {
    if (!std::isfinite(period_knots[i])) {
      throw make_error("period knot ", i, " is not finite (", period_knots[i], ")");
    }
  }
  const double start = period_knots.front();
  const double end = period_knots.back();
  if (!(end - start > 0.0)) {
    throw make_error("periodic knots must span a positive period, got [", start, ", ", end, "]");
  }
  // Snap knots within the seam tolerance onto the period start or end: a list whose wrapped
  // copies were computed as t_{i+n} - T carries round-off there that is not a real knot.
  const double tolerance =
      kPeriodicSeamTolerance * std::max({std::abs(start), std::abs(end), end - start});
  std::vector<double> period = period_knots;
  for (int i = 1; i < n; ++i) {
    double& knot = period[static_cast<size_t>(i)];
    if (std::abs(knot - start) <= tolerance) {
      knot = start;
    } else if (std::abs(knot - end) <= tolerance) {
      knot = end;
    }
    if (knot < at(period, i - 1)) {
      throw make_error("period knots decrease at index ", i, ": ", at(period, i - 1), " > ", knot);
    }
  }
  if (at(period, n - 1) > end) {
    throw make_error("period knots decrease at index ", n, ": ", at(period, n - 1), " > ", end);
  }
  control_point_count_ = n;
  knots_.resize(static_cast<size_t>(n) + 2 * static_cast<size_t>(degree) + 1);
  for (int i = 0; i <= n; ++i) {
    at(knots_, degree + i) = period[static_cast<size_t>(i)];
  }
  // Extend one period by p knots on each side with the same spacing, t_{i+n} = t_i + T, the seam
  // copies exactly t_p - T and t_{p+n} (shifted_period_knot).
  for (int i = 0; i < degree; ++i) {
    knots_[static_cast<size_t>(i)] = shifted_period_knot(at(period, i + n - degree), -1);
    at(knots_, degree + n + 1 + i) = shifted_period_knot(at(period, i + 1), 1);
  }
  validate();
}

double KnotVector::shifted_period_knot(double x, int periods) const {
  const double start = knots_[static_cast<size_t>(degree_)];
  const double end = at(knots_, degree_ + control_point_count_);
  const double period = end - start;
  // The copies of the seam: period k starts at t_p + k T (exactly t_{p+n} for k = 1).
  const auto seam = [&](int k) { return k == 0 ? start : k == 1 ? end : start + k * period; };
  if (x == start) {
    return seam(periods);
  }
  if (x == end) {
    return seam(periods + 1);
  }
  return x + periods * period;
}

double KnotVector::extended_knot(int i) const {
  if (!periodic_) {
    if (i < 0 || i >= size()) {
      throw make_error("knot index ", i, " is outside 0..", size() - 1);
    }
    return knots_[static_cast<size_t>(i)];
  }
  const int n = control_point_count_;
  const int offset = i - degree_;
  const int periods = offset >= 0 ? offset / n : -((-offset + n - 1) / n);
  const int m = offset - periods * n;
  return shifted_period_knot(at(knots_, degree_ + m), periods);
}

void KnotVector::validate() const {
  const int p = degree_;
  const int count = size();
  if (count < 2 * (p + 1)) {
    throw make_error("a knot vector of degree ", p, " needs at least ", 2 * (p + 1), " knots, got ",
                     count);
  }
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(knots_[static_cast<size_t>(i)])) {
      throw make_error("knot ", i, " is not finite (", knots_[static_cast<size_t>(i)], ")");
    }
    if (i > 0 && knots_[static_cast<size_t>(i)] < at(knots_, i - 1)) {
      throw make_error("knot vector decreases at index ", i, ": ", at(knots_, i - 1), " > ",
                       knots_[static_cast<size_t>(i)]);
    }
  }
  if (!(domain_end() > domain_start())) {
    throw make_error("knot vector has an empty domain [", domain_start(), ", ", domain_end(), "]");
  }
  // Multiplicities: at most p inside the domain, at most p + 1 at the ends.
  for (int i = 0; i < count;) {
    int j = i;
    while (j + 1 < count && at(knots_, j + 1) == knots_[static_cast<size_t>(i)]) {
      ++j;
    }
    const int multiplicity = j - i + 1;
    const double value = knots_[static_cast<size_t>(i)];
    const bool interior = value > domain_start() && value < domain_end();
    const int allowed = interior || periodic_ ? p : p + 1;
    if (multiplicity > allowed) {
      throw make_error("knot ", value, " has multiplicity ", multiplicity, " (at index ", i,
                       "), more than ", allowed, " allowed for degree ", p);
    }
    i = j + 1;
  }
}

KnotVector KnotVector::clamped_uniform(int degree, int control_point_count, double start,
                                       double end) {
  check_degree(degree);
  if (control_point_count < degree + 1) {
    throw make_error("degree ", degree, " needs at least ", degree + 1, " control points, got ",
                     control_point_count);
  }
  if (!std::isfinite(start) || !std::isfinite(end) || !(end > start)) {
    throw make_error("clamped knot vector needs finite start < end, got [", start, ", ", end, "]");
  }
  const int spans = control_point_count - degree;
  std::vector<double> breakpoints(static_cast<size_t>(spans + 1));
  for (int i = 0; i <= spans; ++i) {
    breakpoints[static_cast<size_t>(i)] = i == spans ? end : start + (end - start) * i / spans;
  }
  return clamped_from_breakpoints(degree, breakpoints);
}

KnotVector KnotVector::clamped_from_breakpoints(int degree,
                                                const std::vector<double>& breakpoints) {
  check_degree(degree);
  if (breakpoints.size() < 2) {
    throw make_error("clamped knot vector needs at least 2 breakpoints, got ", breakpoints.size());
  }
  std::vector<double> knots;
  knots.reserve(breakpoints.size() + 2 * static_cast<size_t>(degree));
  knots.insert(knots.end(), static_cast<size_t>(degree), breakpoints.front());
  knots.insert(knots.end(), breakpoints.begin(), breakpoints.end());
  knots.insert(knots.end(), static_cast<size_t>(degree), breakpoints.back());
  return KnotVector(degree, std::move(knots));
}

KnotVector KnotVector::uniform(int degree, int control_point_count) {
  check_degree(degree);
  if (control_point_count < degree + 1) {
    throw make_error("degree ", degree, " needs at least ", degree + 1, " control points, got ",
                     control_point_count);
  }
  std::vector<double> knots(static_cast<size_t>(control_point_count + degree + 1));
  for (size_t i = 0; i < knots.size(); ++i) {
    knots[i] = static_cast<double>(i);
  }
  return KnotVector(degree, std::move(knots));
}

KnotVector KnotVector::periodic(int degree, const std::vector<double>& period_knots) {
  return KnotVector(PeriodicTag{}, degree, period_knots);
}

KnotVector KnotVector::periodic_uniform(int degree, int control_point_count, double start,
                                        double end) {
  if (control_point_count < 1 || !std::isfinite(start) || !std::isfinite(end)) {
    throw make_error(
        "periodic knot vector needs a positive control point count and finite ends,"
        " got ",
        control_point_count, " over [", start, ", ", end, "]");
  }
  std::vector<double> period_knots(static_cast<size_t>(control_point_count + 1));
  for (int i = 0; i <= control_point_count; ++i) {
    period_knots[static_cast<size_t>(i)] =
        i == control_point_count ? end : start + (end - start) * i / control_point_count;
  }
  return periodic(degree, period_knots);
}

std::vector<double> KnotVector::period_knots() const {
  if (!periodic_) {
    return knots_;
  }
  return {knots_.begin() + degree_, knots_.begin() + degree_ + control_point_count_ + 1};
}

double KnotVector::to_domain(double u) const {
  if (!std::isfinite(u)) {
    throw make_error("parameter ", u, " is not finite");
  }
  const double start = domain_start();
  const double end = domain_end();
  if (u >= start && u <= end) {
    return u;
  }
  const double length = end - start;
  if (periodic_) {
    double wrapped = start + std::fmod(u - start, length);
    if (wrapped < start) {
      wrapped += length;
    }
    return wrapped >= end ? start : wrapped;
  }
  // Allow round-off just outside the domain (a relative 1e-12), reject anything further.
  const double slack = 1e-12 * std::max({1.0, std::abs(start), std::abs(end)});
  if (u < start - slack || u > end + slack) {
    throw make_error("parameter ", u, " is outside the domain [", start, ", ", end, "]");
  }
  return std::clamp(u, start, end);
}

double KnotVector::wrap_to_period(double u) const {
  const double wrapped = to_domain(u);
  if (!periodic_) {
    return wrapped;
  }
  const double start = domain_start();
  const double end = domain_end();
  const double tolerance =
      kPeriodicSeamTolerance * std::max({std::abs(start), std::abs(end), end - start});
  return wrapped - start <= tolerance || end - wrapped <= tolerance ? start : wrapped;
}

int KnotVector::find_span(double u) const {
  u = to_domain(u);
  const int last = basis_count() - 1;
  if (u >= domain_end()) {
    int k = last;
    while (knots_[static_cast<size_t>(k)] >= at(knots_, k + 1)) {
      --k;
    }
    return k;
  }
  // Largest k in [p, last] with t_k <= u; then t_k <= u < t_{k+1}.
  const auto first = knots_.begin() + degree_;
  const auto past = knots_.begin() + last + 1;
  const auto upper = std::upper_bound(first, past, u);
  return static_cast<int>(upper - knots_.begin()) - 1;
}

int KnotVector::multiplicity(double u) const {
  const auto range = std::equal_range(knots_.begin(), knots_.end(), u);
  return static_cast<int>(range.second - range.first);
}

std::vector<int> KnotVector::non_empty_spans() const {
  std::vector<int> spans;
  for (int k = degree_; k < basis_count(); ++k) {
    if (knots_[static_cast<size_t>(k)] < at(knots_, k + 1)) {
      spans.push_back(k);
    }
  }
  return spans;
}

}  // namespace dnurbs
