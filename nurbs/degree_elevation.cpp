#include "dnurbs/nurbs/degree_elevation.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/periodic_window.h"

namespace dnurbs {
namespace {

/// A knot vector with the control rows it goes with.
struct ElevatedRows {
  KnotVector knots;
  Eigen::MatrixXd rows;
};

void check_elevation(const KnotVector& knots, int degree_increase) {
  if (degree_increase < 0) {
    throw make_error("degree increase ", degree_increase, " must be >= 0");
  }
  if (knots.degree() + degree_increase > kMaxDegree) {
    throw make_error("elevating degree ", knots.degree(), " by ", degree_increase, " gives degree ",
                     knots.degree() + degree_increase, " above the maximum ", kMaxDegree);
  }
  if (knots.is_periodic()) {
    return;
  }
  const int p = knots.degree();
  const int m = knots.size() - 1;
  if (knots[0] != knots[p] || knots[m - p] != knots[m]) {
    throw make_error("degree elevation needs a clamped knot vector; its end knots are ", knots[0],
                     " .. ", knots[p], " and ", knots[m - p], " .. ", knots[m]);
  }
}

// Boehm's knot insertion, once (Piegl & Tiller eq. 5.15): the new points are convex
// combinations of old neighbors, alpha_i = (u - t_i) / (t_{i+p} - t_i) in [0, 1].
void insert_once(std::vector<double>& knots, Eigen::MatrixXd& points, int p, double u) {
  const int k =
      static_cast<int>(std::upper_bound(knots.begin(), knots.end(), u) - knots.begin()) - 1;
  const int s = static_cast<int>(std::count(knots.begin(), knots.end(), u));
  const auto knot = [&](int i) { return knots[static_cast<size_t>(i)]; };
  Eigen::MatrixXd inserted(points.rows() + 1, points.cols());
  inserted.topRows(k - p + 1) = points.topRows(k - p + 1);
  for (int i = k - p + 1; i <= k - s; ++i) {
    const double alpha = (u - knot(i)) / (knot(i + p) - knot(i));
    inserted.row(i) = alpha * points.row(i) + (1.0 - alpha) * points.row(i - 1);
  }
  inserted.bottomRows(points.rows() - (k - s)) = points.bottomRows(points.rows() - (k - s));
  knots.insert(knots.begin() + k + 1, u);
  points = std::move(inserted);
}

// The blossom of the degree-p spline (knots t, control rows P) at the sorted knots S (p values
// that contain every knot strictly between S's ends at least as often as t does): the knots of S
// that t lacks are inserted (Boehm, convex) into a local copy until S is a run of consecutive
// knots t*_{a+1..a+p}; then b(S) = P*_a (Ramshaw, Blossoms are polar forms, CAGD 6, 1989).
Eigen::RowVectorXd blossom_at_knots(const std::vector<double>& t, const Eigen::MatrixXd& points,
                                    int p, const std::vector<double>& sorted) {
  const int m = static_cast<int>(t.size()) - 1;
  const double low = sorted.front();
  const double high = sorted.back();
  const auto first_of = [](const std::vector<double>& knots, double value) {
    return static_cast<int>(std::lower_bound(knots.begin(), knots.end(), value) - knots.begin());
  };
  const auto count_of = [](const std::vector<double>& knots, double value) {
    const auto range = std::equal_range(knots.begin(), knots.end(), value);
    return static_cast<int>(range.second - range.first);
  };
  // Local copy: knots t_L..t_R and the control points whose knots lie in it.
  const int left = std::max(0, first_of(t, low) - p - 1);
  const int right = std::min(m, first_of(t, high) + count_of(t, high) + p);
  std::vector<double> knots(t.begin() + left, t.begin() + right + 1);
  Eigen::MatrixXd local = points.middleRows(left, right - p - left);
  for (size_t i = 0; i < sorted.size(); ++i) {
    if (i > 0 && sorted[i] == sorted[i - 1]) {
      continue;
    }
    const int needed = count_of(sorted, sorted[i]);
    for (int missing = needed - count_of(knots, sorted[i]); missing > 0; --missing) {
      insert_once(knots, local, p, sorted[i]);
    }
  }
  // The run: the last copies of `low` that S holds, the knots between, the first copies of
  // `high`. S of p equal knots takes the first p copies (the last p at the clamped start).
  const int first = first_of(knots, low);
  const int a = low == high ? std::max(first - 1, 0)
                            : first + count_of(knots, low) - count_of(sorted, low) - 1;
  return local.row(a);
}

// Degree p -> p + 1 on a clamped knot vector (every distinct knot gains a copy). The coefficient
// of the new basis function j is the degree-raised blossom at its interior knots
// x = t'_{j+1..j+p+1}: the mean of the old blossom over the p + 1 ways of leaving one of them out
// (Ramshaw 1989; Prautzsch, Degree elevation of B-spline curves, CAGD 1, 1984). Every blossom is
// made of Boehm insertions, so each new point is a convex combination of old ones: the result
// is accurate to round-off whatever the knot spacing (unlike A5.9's knot removal step, whose
// divisions lose digits when knots nearly coincide).
ElevatedRows elevate_once(const KnotVector& knots, const Eigen::MatrixXd& points) {
  const int p = knots.degree();
  const std::vector<double>& t = knots.knots();
  std::vector<double> raised;
  raised.reserve(2 * t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    if (i == 0 || t[i] != t[i - 1]) {
      raised.push_back(t[i]);
    }
    raised.push_back(t[i]);
  }
  const int count = static_cast<int>(raised.size()) - p - 2;
  Eigen::MatrixXd elevated = Eigen::MatrixXd::Zero(count, points.cols());
  std::vector<double> subset(static_cast<size_t>(p));
  for (int j = 0; j < count; ++j) {
    const auto interior = raised.begin() + j + 1;
    Eigen::RowVectorXd blossom;
    for (int left_out = 0; left_out <= p; ++left_out) {
      // Leaving out equal knots gives the same blossom.
      if (left_out == 0 || interior[left_out] != interior[left_out - 1]) {
        std::copy(interior, interior + left_out, subset.begin());
        std::copy(interior + left_out + 1, interior + p + 1, subset.begin() + left_out);
        blossom = blossom_at_knots(t, points, p, subset);
      }
      elevated.row(j) += blossom;
    }
  }
  elevated /= p + 1;
  return {KnotVector(p + 1, std::move(raised)), std::move(elevated)};
}

// Raises a clamped B-spline by t degrees, one at a time.
ElevatedRows elevate_open_rows(const KnotVector& knots, const Eigen::MatrixXd& points, int t) {
  ElevatedRows result{knots, points};
  for (int step = 0; step < t; ++step) {
    result = elevate_once(result.knots, result.rows);
  }
  return result;
}

// Periodic curves: the period's knots with every distinct knot raised by t (the seam by t copies
// at the start of the list, so that its multiplicity across the wrap grows by t).
KnotVector elevated_periodic_knots(const KnotVector& knots, int t) {
  const std::vector<double> period = knots.period_knots();
  std::vector<double> elevated;
  elevated.reserve(period.size() * static_cast<size_t>(t + 1));
  for (size_t i = 0; i + 1 < period.size(); ++i) {
    const bool seam_copy_at_end = period[i] == period.back();
    if ((i == 0 || period[i] != period[i - 1]) && !seam_copy_at_end) {
      elevated.insert(elevated.end(), static_cast<size_t>(t), period[i]);
    }
    elevated.push_back(period[i]);
  }
  elevated.push_back(period.back());
  return KnotVector::periodic(knots.degree() + t, elevated);
}

// Periodic curves: three periods [t_p - T, t_{p+n} + T] of the bi-infinite spline as an open
// curve, clamped at both ends and elevated (elevate_open_rows); the middle of the result is the
// elevated periodic spline, whose control points are read off by matching knots (wrap_periodic).
ElevatedRows elevate_periodic_rows(const KnotVector& knots, const Eigen::MatrixXd& points, int t) {
  const int n = knots.control_point_count();
  const KnotsAndRows window =
      clamp_window(unwrap_periodic(knots, points, -n, 3 * n + knots.degree()));
  ElevatedRows elevated = elevate_open_rows(window.knots, window.rows, t);
  KnotVector target = elevated_periodic_knots(knots, t);
  Eigen::MatrixXd rows =
      wrap_periodic({std::move(elevated.knots), std::move(elevated.rows)}, target);
  return {std::move(target), std::move(rows)};
}

ElevatedRows elevate_rows(const KnotVector& knots, const Eigen::MatrixXd& points, int t) {
  return knots.is_periodic() ? elevate_periodic_rows(knots, points, t)
                             : elevate_open_rows(knots, points, t);
}

}  // namespace

NurbsCurve elevate_degree(const NurbsCurve& curve, int degree_increase) {
  check_elevation(curve.knots(), degree_increase);
  if (degree_increase == 0) {
    return curve;
  }
  ControlRows rows = control_rows(curve);
  ElevatedRows result = elevate_rows(curve.knots(), rows.rows, degree_increase);
  rows.rows = std::move(result.rows);
  return curve_from_control_rows(std::move(result.knots), rows);
}

NurbsSurface elevate_degree(const NurbsSurface& surface, SurfaceDirection direction,
                            int degree_increase) {
  const KnotVector& knots =
      direction == SurfaceDirection::kU ? surface.knots_u() : surface.knots_v();
  check_elevation(knots, degree_increase);
  if (degree_increase == 0) {
    return surface;
  }
  ControlRows rows = control_rows(surface, direction);
  ElevatedRows result = elevate_rows(knots, rows.rows, degree_increase);
  rows.rows = std::move(result.rows);
  return surface_from_control_rows(surface, direction, std::move(result.knots), rows);
}

}  // namespace dnurbs
