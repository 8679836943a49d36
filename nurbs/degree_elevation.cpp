#include "nurbs/degree_elevation.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "core/error.h"
#include "nurbs/periodic_window.h"

namespace dnurbs {
namespace {

/// A knot vector with the control rows it goes with.
struct ElevatedRows {
  KnotVector knots;
  Eigen::MatrixXd rows;
};

double binomial(int n, int k) {
  double value = 1.0;
  for (int i = 1; i <= k; ++i) {
    value = value * (n - k + i) / i;
  }
  return value;
}

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

// Piegl & Tiller A5.9 on control rows of a clamped knot vector: decompose into Bezier segments
// on the fly, elevate each, and remove the knots that the decomposition inserted.
ElevatedRows elevate_open_rows(const KnotVector& knots, const Eigen::MatrixXd& points, int t) {
  const int p = knots.degree();
  const std::vector<double>& u = knots.knots();
  const int n = static_cast<int>(points.rows()) - 1;  // last control point index
  const int m = n + p + 1;                            // last knot index
  const int ph = p + t;
  const int ph2 = ph / 2;
  const Eigen::Index dim = points.cols();
  const auto knot = [&](int i) { return u[static_cast<size_t>(i)]; };

  // Bezier degree elevation coefficients.
  Eigen::MatrixXd bezalfs = Eigen::MatrixXd::Zero(ph + 1, p + 1);
  bezalfs(0, 0) = 1.0;
  bezalfs(ph, p) = 1.0;
  for (int i = 1; i <= ph2; ++i) {
    const double inverse = 1.0 / binomial(ph, i);
    for (int j = std::max(0, i - t); j <= std::min(p, i); ++j) {
      bezalfs(i, j) = inverse * binomial(p, j) * binomial(t, i - j);
    }
  }
  for (int i = ph2 + 1; i <= ph - 1; ++i) {
    for (int j = std::max(0, i - t); j <= std::min(p, i); ++j) {
      bezalfs(i, j) = bezalfs(ph - i, p - j);
    }
  }

  // Every distinct knot gains t copies.
  int distinct = 1;
  for (int i = 1; i <= m; ++i) {
    distinct += knot(i) != knot(i - 1) ? 1 : 0;
  }
  const int new_count = n + 1 + t * (distinct - 1);
  Eigen::MatrixXd q(new_count, dim);
  std::vector<double> uh(static_cast<size_t>(new_count + ph + 1));
  const auto new_knot = [&](int i) -> double& { return uh[static_cast<size_t>(i)]; };

  Eigen::MatrixXd bpts = points.topRows(p + 1);
  Eigen::MatrixXd ebpts(ph + 1, dim);
  Eigen::MatrixXd next_bpts(std::max(p - 1, 1), dim);
  std::vector<double> alfs(static_cast<size_t>(std::max(p - 1, 1)));

  int mh = ph;
  int kind = ph + 1;
  int r = -1;
  int a = p;
  int b = p + 1;
  int cind = 1;
  double ua = knot(0);
  q.row(0) = points.row(0);
  for (int i = 0; i <= ph; ++i) {
    new_knot(i) = ua;
  }
  while (b < m) {
    const int start = b;
    while (b < m && knot(b) == knot(b + 1)) {
      ++b;
    }
    const int mul = b - start + 1;
    mh += mul + t;
    const double ub = knot(b);
    const int oldr = r;
    r = p - mul;
    const int lbz = oldr > 0 ? (oldr + 2) / 2 : 1;
    const int rbz = r > 0 ? ph - (r + 1) / 2 : ph;
    // Insert ub r times to get the Bezier segment [ua, ub].
    if (r > 0) {
      const double numer = ub - ua;
      for (int k = p; k > mul; --k) {
        alfs[static_cast<size_t>(k - mul - 1)] = numer / (knot(a + k) - ua);
      }
      for (int j = 1; j <= r; ++j) {
        const int save = r - j;
        const int s = mul + j;
        for (int k = p; k >= s; --k) {
          const double alpha = alfs[static_cast<size_t>(k - s)];
          bpts.row(k) = alpha * bpts.row(k) + (1.0 - alpha) * bpts.row(k - 1);
        }
        next_bpts.row(save) = bpts.row(p);
      }
    }
    // Degree-elevate the Bezier segment (only points lbz..ph are used below).
    for (int i = lbz; i <= ph; ++i) {
      ebpts.row(i).setZero();
      for (int j = std::max(0, i - t); j <= std::min(p, i); ++j) {
        ebpts.row(i) += bezalfs(i, j) * bpts.row(j);
      }
    }
    // Remove the knot ua oldr times.
    if (oldr > 1) {
      int first = kind - 2;
      int last = kind;
      const double den = ub - ua;
      const double bet = (ub - new_knot(kind - 1)) / den;
      for (int tr = 1; tr < oldr; ++tr) {
        int i = first;
        int j = last;
        int kj = j - kind + 1;
        while (j - i > tr) {
          if (i < cind) {
            const double alf = (ub - new_knot(i)) / (ua - new_knot(i));
            q.row(i) = alf * q.row(i) + (1.0 - alf) * q.row(i - 1);
          }
          if (j >= lbz) {
            if (j - tr <= kind - ph + oldr) {
              const double gam = (ub - new_knot(j - tr)) / den;
              ebpts.row(kj) = gam * ebpts.row(kj) + (1.0 - gam) * ebpts.row(kj + 1);
            } else {
              ebpts.row(kj) = bet * ebpts.row(kj) + (1.0 - bet) * ebpts.row(kj + 1);
            }
          }
          ++i;
          --j;
          --kj;
        }
        --first;
        ++last;
      }
    }
    // Load the knot ua and the control points of this segment.
    if (a != p) {
      for (int i = 0; i < ph - oldr; ++i) {
        new_knot(kind) = ua;
        ++kind;
      }
    }
    for (int j = lbz; j <= rbz; ++j) {
      q.row(cind) = ebpts.row(j);
      ++cind;
    }
    if (b < m) {
      // Set up the next segment.
      for (int j = 0; j < r; ++j) {
        bpts.row(j) = next_bpts.row(j);
      }
      for (int j = r; j <= p; ++j) {
        bpts.row(j) = points.row(b - p + j);
      }
      a = b;
      ++b;
      ua = ub;
    } else {
      for (int i = 0; i <= ph; ++i) {
        new_knot(kind + i) = ub;
      }
    }
  }
  const int count = mh - ph;  // P&T: nh = mh - ph - 1 is the last index
  if (count != new_count) {
    throw make_error("degree elevation produced ", count, " control points instead of ", new_count);
  }
  return {KnotVector(ph, std::move(uh)), std::move(q)};
}

// Periodic curves: the period's knots with every distinct knot raised by t (the seam by t copies
// at the start of the list, so that its multiplicity across the wrap grows by t).
KnotVector elevated_periodic_knots(const KnotVector& knots, int t) {
  const std::vector<double> period = knots.period_knots();
  std::vector<double> elevated;
  elevated.reserve(period.size() * static_cast<size_t>(t + 1));
  for (size_t i = 0; i + 1 < period.size(); ++i) {
    if (i == 0 || period[i] != period[i - 1]) {
      elevated.insert(elevated.end(), static_cast<size_t>(t), period[i]);
    }
    elevated.push_back(period[i]);
  }
  elevated.push_back(period.back());
  return KnotVector::periodic(knots.degree() + t, elevated);
}

// Periodic curves: three periods [t_p - T, t_{p+n} + T] of the bi-infinite spline as an open
// curve, clamped at both ends and elevated by A5.9; the middle of the result is the elevated
// periodic spline, whose control points are read off by matching knots (wrap_periodic).
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
