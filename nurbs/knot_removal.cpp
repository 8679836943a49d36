#include "nurbs/knot_removal.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/error.h"
#include "nurbs/periodic_window.h"

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

// Piegl & Tiller A5.8 on control rows: removes u (last index r, multiplicity s) up to `times`
// times. Every block of a row is checked against `tolerance` on its own, and a rational block
// must keep a positive weight.
RemovedRows remove_knot_rows(const KnotVector& knots, Eigen::MatrixXd points, double u, int times,
                             double tolerance, int block_size) {
  const int p = knots.degree();
  std::vector<double> t = knots.knots();
  const int m = knots.size() - 1;                     // last knot index
  const int n = static_cast<int>(points.rows()) - 1;  // last control point index
  const int s = knots.multiplicity(u);
  const int r = static_cast<int>(std::upper_bound(t.begin(), t.end(), u) - t.begin()) - 1;
  const int order = p + 1;
  const int block_count = static_cast<int>(points.cols()) / block_size;
  const auto knot = [&](int i) { return t[static_cast<size_t>(i)]; };
  const auto close = [&](const Eigen::RowVectorXd& a, const Eigen::RowVectorXd& b) {
    for (int k = 0; k < block_count; ++k) {
      const Eigen::Index start = static_cast<Eigen::Index>(k) * block_size;
      if ((a.segment(start, block_size) - b.segment(start, block_size)).norm() > tolerance) {
        return false;
      }
    }
    return true;
  };
  const auto positive_weights = [&](const Eigen::RowVectorXd& a) {
    for (int k = 0; block_size == 4 && k < block_count; ++k) {
      if (!(a[k * 4 + 3] > 0.0)) {
        return false;
      }
    }
    return true;
  };

  const int first_out = (2 * r - s - p) / 2;  // first control point out
  int last = r - s;
  int first = r - p;
  Eigen::MatrixXd temp(2 * p + 2, points.cols());
  int removed = 0;
  for (; removed < times; ++removed) {
    const int tr = removed;
    const int off = first - 1;  // difference in index between temp and points
    temp.row(0) = points.row(off);
    temp.row(last + 1 - off) = points.row(last + 1);
    int i = first;
    int j = last;
    int ii = 1;
    int jj = last - off;
    // New control points of one removal step, from both ends towards the middle.
    while (j - i > tr) {
      const double alpha_i = (u - knot(i)) / (knot(i + order + tr) - knot(i));
      const double alpha_j = (u - knot(j - tr)) / (knot(j + order) - knot(j - tr));
      temp.row(ii) = (points.row(i) - (1.0 - alpha_i) * temp.row(ii - 1)) / alpha_i;
      temp.row(jj) = (points.row(j) - alpha_j * temp.row(jj + 1)) / (1.0 - alpha_j);
      ++i;
      ++ii;
      --j;
      --jj;
    }
    // Removable if the two ends meet within the tolerance (P&T eq. 5.29 / 5.30).
    bool removable = false;
    if (j - i < tr) {
      removable = close(temp.row(ii - 1), temp.row(jj + 1));
    } else {
      const double alpha_i = (u - knot(i)) / (knot(i + order + tr) - knot(i));
      removable = close(points.row(i),
                        alpha_i * temp.row(ii + tr + 1) + (1.0 - alpha_i) * temp.row(ii - 1));
    }
    for (int k = 1; removable && k <= last - off; ++k) {
      removable = k >= ii && k <= jj ? true : positive_weights(temp.row(k));
    }
    if (!removable) {
      break;
    }
    // Successful removal: save the new control points.
    i = first;
    j = last;
    while (j - i > tr) {
      points.row(i) = temp.row(i - off);
      points.row(j) = temp.row(j - off);
      ++i;
      --j;
    }
    --first;
    ++last;
  }
  if (removed == 0) {
    return {std::move(t), std::move(points), 0};
  }
  // Shift the knots and the control points over the removed ones.
  for (int k = r + 1; k <= m; ++k) {
    t[static_cast<size_t>(k - removed)] = t[static_cast<size_t>(k)];
  }
  t.resize(t.size() - static_cast<size_t>(removed));
  int j = first_out;
  int i = j;  // points j..i are overwritten
  for (int k = 1; k < removed; ++k) {
    if (k % 2 == 1) {
      ++i;
    } else {
      --j;
    }
  }
  for (int k = i + 1; k <= n; ++k) {
    points.row(j) = points.row(k);
    ++j;
  }
  points.conservativeResize(n + 1 - removed, Eigen::NoChange);
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
// curve, removes u once at every copy inside it by A5.8 (each within the tolerance), and reads
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

// A5.8 on the control rows of an open or periodic knot vector.
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
