#include "dnurbs/nurbs/knot_removal.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/QR>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/periodic_window.h"

namespace dnurbs {
namespace {

/// Knots and control rows after removal, with the number of removals done.
struct RemovedRows {
  std::vector<double> knots;
  Eigen::MatrixXd rows;
  int removed_count = 0;
};

// Checks a removal request; returns u (wrapped into the period for a periodic vector, the seam
// as t_p).
double check_removal(const KnotVector& knots, double u, int times, double tolerance) {
  if (!std::isfinite(tolerance) || tolerance < 0.0) {
    throw make_error("knot removal tolerance ", tolerance, " must be finite and >= 0");
  }
  if (!std::isfinite(u)) {
    throw make_error("knot ", u, " to remove is not finite");
  }
  if (knots.is_periodic()) {
    u = knots.wrap_to_period(u);
  } else if (!(u > knots.domain_start() && u < knots.domain_end())) {
    throw make_error("knot ", u, " to remove is not inside the domain (", knots.domain_start(),
                     ", ", knots.domain_end(), ")");
  }
  const int s = knots.multiplicity(u);
  if (s == 0) {
    throw make_error("knot ", u, " to remove is not a knot of the knot vector");
  }
  if (times < 1 || times > s) {
    throw make_error("knot ", u, " has multiplicity ", s, " and cannot be removed ", times,
                     " times");
  }
  const int n = knots.control_point_count();
  if (knots.is_periodic() && n - times < knots.degree() + 1) {
    throw make_error("removing knot ", u, " ", times, " times would leave ", n - times,
                     " control points, fewer than the ", knots.degree() + 1,
                     " a periodic basis of degree ", knots.degree(), " needs");
  }
  return u;
}

// P&T eq. 5.30: a homogeneous bound d w_min / (1 + |P|_max) keeps the curve within d.
double homogeneous_tolerance(double tolerance, const Eigen::MatrixX3d& points,
                             const Eigen::VectorXd& weights, bool rational) {
  if (!rational) {
    return tolerance;
  }
  return tolerance * weights.minCoeff() / (1.0 + points.rowwise().norm().maxCoeff());
}

// One removal of u (last index r, multiplicity s >= 1) from the knots t and control rows P, if
// every block of every row stays within `tolerance`. Removing u is undoing Boehm's insertion
// (Piegl & Tiller eq. 5.15 read backwards, as in A5.8): the coarse points Q satisfy
//   P_i = Q_i (i < r - p),   P_i = alpha_i Q_i + (1 - alpha_i) Q_{i-1} (r - p <= i <= r - s),
//   P_i = Q_{i-1} (i > r - s),   alpha_i = (u - t_i) / (t_{i+p+1} - t_i) in (0, 1),
// p - s + 1 equations for the p - s unknowns Q_{r-p}..Q_{r-s-1}. A5.8 solves them by recursion
// from both ends, dividing by alpha_i and 1 - alpha_i, which loses digits when knots nearly
// coincide; here the bidiagonal system is solved in the least-squares sense by Householder QR
// (backward stable), and the removal is accepted if every fine point P_i is reproduced within
// the tolerance: the curve then moves by at most the tolerance (the fine basis is a
// non-negative partition of unity, P&T eq. 5.29).
bool remove_once(std::vector<double>& t, Eigen::MatrixXd& points, int p, double u, double tolerance,
                 int block_size) {
  const int r = static_cast<int>(std::upper_bound(t.begin(), t.end(), u) - t.begin()) - 1;
  const int s = static_cast<int>(std::count(t.begin(), t.end(), u));
  const int unknowns = p - s;
  const auto knot = [&](int i) { return t[static_cast<size_t>(i)]; };
  const auto alpha = [&](int i) { return (u - knot(i)) / (knot(i + p + 1) - knot(i)); };
  // System M Q = B over the equations i = r - p .. r - s, known ends moved to the right.
  Eigen::MatrixXd matrix = Eigen::MatrixXd::Zero(unknowns + 1, std::max(unknowns, 1));
  Eigen::MatrixXd right = points.middleRows(r - p, unknowns + 1);
  for (int e = 0; e <= unknowns; ++e) {
    const int i = r - p + e;
    if (e < unknowns) {
      matrix(e, e) = alpha(i);
    } else {
      right.row(e) -= alpha(i) * points.row(r - s + 1);  // Q_{r-s} = P_{r-s+1}
    }
    if (e > 0) {
      matrix(e, e - 1) = 1.0 - alpha(i);
    } else {
      right.row(e) -= (1.0 - alpha(i)) * points.row(r - p - 1);  // Q_{r-p-1} = P_{r-p-1}
    }
  }
  Eigen::MatrixXd solved(unknowns, points.cols());
  if (unknowns > 0) {
    solved = matrix.householderQr().solve(right);
  }
  const Eigen::MatrixXd residual = unknowns > 0 ? Eigen::MatrixXd(matrix * solved - right) : right;
  const int block_count = static_cast<int>(points.cols()) / block_size;
  for (int e = 0; e <= unknowns; ++e) {
    for (int b = 0; b < block_count; ++b) {
      const Eigen::Index start = static_cast<Eigen::Index>(b) * block_size;
      if (!(residual.row(e).segment(start, block_size).norm() <= tolerance)) {
        return false;
      }
    }
  }
  for (int e = 0; block_size == 4 && e < unknowns; ++e) {
    for (int b = 0; b < block_count; ++b) {
      if (!(solved(e, b * 4 + 3) > 0.0)) {
        return false;
      }
    }
  }
  // Q: P_0..P_{r-p-1}, the solved points, P_{r-s+1}..P_n; the knots lose t_r.
  Eigen::MatrixXd coarse(points.rows() - 1, points.cols());
  coarse.topRows(r - p) = points.topRows(r - p);
  coarse.middleRows(r - p, unknowns) = solved;
  coarse.bottomRows(points.rows() - (r - s + 1)) = points.bottomRows(points.rows() - (r - s + 1));
  points = std::move(coarse);
  t.erase(t.begin() + r);
  return true;
}

// Removes u up to `times` times (each step within the tolerance), stopping at the first failure.
RemovedRows remove_knot_rows(const KnotVector& knots, Eigen::MatrixXd points, double u, int times,
                             double tolerance, int block_size) {
  std::vector<double> t = knots.knots();
  int removed = 0;
  while (removed < times && remove_once(t, points, knots.degree(), u, tolerance, block_size)) {
    ++removed;
  }
  return {std::move(t), std::move(points), removed};
}

// The period knots with one copy of u removed. A seam copy goes from the end of the list (or
// the start) so that the period keeps its start; the seam's only copy moves the period start to
// the next knot, t_{p+1} (the curve is the same function of the parameter; only the domain
// shifts).
std::vector<double> period_without(const KnotVector& knots, double u) {
  std::vector<double> period = knots.period_knots();
  const size_t n = period.size() - 1;
  const double start = period.front();
  const double end = period.back();
  if (u != start) {
    period.erase(std::find(period.begin(), period.end(), u));
  } else if (period[n - 1] == end) {
    period.erase(period.begin() + static_cast<std::ptrdiff_t>(n - 1));
  } else if (period[1] == start) {
    period.erase(period.begin() + 1);
  } else {
    std::vector<double> rotated(period.begin() + 1, period.end() - 1);
    rotated.push_back(period[1] + (end - start));
    period = std::move(rotated);
  }
  return period;
}

/// Knot vector and control rows after removal, with the number of removals done.
struct KnotsAndRemovedRows {
  KnotVector knots;
  Eigen::MatrixXd rows;
  int removed_count = 0;
};

// Periodic shapes: each removal step unwraps five periods [t_p - 2T, t_{p+n} + 2T] into an open
// curve, removes u once at every copy inside it (remove_once, each within the tolerance), and reads
// the control points of the periodic result off the middle (wrap_periodic).
KnotsAndRemovedRows remove_periodic_rows(KnotVector knots, Eigen::MatrixXd rows, double u,
                                         int times, double tolerance, int block_size) {
  const int p = knots.degree();
  int removed = 0;
  for (; removed < times; ++removed) {
    const int n = knots.control_point_count();
    KnotsAndRows window = unwrap_periodic(knots, rows, -2 * n, 5 * n + p);
    int index = p;  // u's first copy in the stored period t_p..t_{p+n-1}
    while (knots[index] != u) {
      ++index;
    }
    bool removable = true;
    for (int period = -2; period <= 2 && removable; ++period) {
      const double copy = knots.extended_knot(index + period * n);
      if (!(copy > window.knots.domain_start() && copy < window.knots.domain_end())) {
        continue;
      }
      RemovedRows step =
          remove_knot_rows(window.knots, window.rows, copy, 1, tolerance, block_size);
      removable = step.removed_count == 1;
      if (removable) {
        window = {KnotVector(p, std::move(step.knots)), std::move(step.rows)};
      }
    }
    if (!removable) {
      break;
    }
    KnotVector removed_knots = KnotVector::periodic(p, period_without(knots, u));
    rows = wrap_periodic(window, removed_knots);
    knots = std::move(removed_knots);
  }
  return {std::move(knots), std::move(rows), removed};
}

// Removal on the control rows of an open or periodic knot vector.
KnotsAndRemovedRows remove_knot_any(const KnotVector& knots, const ControlRows& rows, double u,
                                    int times, double bound) {
  if (knots.is_periodic()) {
    return remove_periodic_rows(knots, rows.rows, u, times, bound, rows.block_size);
  }
  RemovedRows result = remove_knot_rows(knots, rows.rows, u, times, bound, rows.block_size);
  return {KnotVector(knots.degree(), std::move(result.knots)), std::move(result.rows),
          result.removed_count};
}

}  // namespace

CurveKnotRemoval remove_knot(const NurbsCurve& curve, double u, int times, double tolerance) {
  u = check_removal(curve.knots(), u, times, tolerance);
  ControlRows rows = control_rows(curve);
  const double bound = homogeneous_tolerance(tolerance, curve.control_points(), curve.weights(),
                                             curve.is_rational());
  KnotsAndRemovedRows result = remove_knot_any(curve.knots(), rows, u, times, bound);
  if (result.removed_count == 0) {
    return {curve, 0, false};
  }
  rows.rows = std::move(result.rows);
  return {curve_from_control_rows(std::move(result.knots), rows), result.removed_count,
          result.removed_count == times};
}

SurfaceKnotRemoval remove_knot(const NurbsSurface& surface, SurfaceDirection direction, double u,
                               int times, double tolerance) {
  const KnotVector& knots =
      direction == SurfaceDirection::kU ? surface.knots_u() : surface.knots_v();
  u = check_removal(knots, u, times, tolerance);
  ControlRows rows = control_rows(surface, direction);
  const double bound = homogeneous_tolerance(tolerance, surface.control_points(), surface.weights(),
                                             surface.is_rational());
  KnotsAndRemovedRows result = remove_knot_any(knots, rows, u, times, bound);
  if (result.removed_count == 0) {
    return {surface, 0, false};
  }
  rows.rows = std::move(result.rows);
  return {surface_from_control_rows(surface, direction, std::move(result.knots), rows),
          result.removed_count, result.removed_count == times};
}

}  // namespace dnurbs
