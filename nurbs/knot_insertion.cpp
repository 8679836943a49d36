#include "dnurbs/nurbs/knot_insertion.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

int count_index(Eigen::Index index) {
  return static_cast<int>(index);
}

// Weight shared by all control points of a polynomial shape (all weights equal).
double common_weight(const Eigen::VectorXd& weights) {
  return weights.size() > 0 ? weights[0] : 1.0;
}

// Block b of a flat surface point list along `direction`: control point index of (row, block).
int surface_point_index(const NurbsSurface& surface, SurfaceDirection direction, int row,
                        int block) {
  return direction == SurfaceDirection::kU ? surface.control_point_index(row, block)
                                           : surface.control_point_index(block, row);
}

void check_times(double u, int times) {
  if (times < 1) {
    throw make_error("knot ", u, " must be inserted at least once, got times = ", times);
  }
}

// Piegl & Tiller A5.1 on control rows, open or periodic. The new rows are those of the open
// algorithm; for a periodic vector they are read cyclically (the wrapped polygon index k is
// distinct point k mod n) and the new cyclic polygon is assembled from the new block and the
// unchanged points.
KnotsAndRows insert_knot_rows(const KnotVector& knots, const Eigen::MatrixXd& points, double u,
                              int times) {
  check_times(u, times);
  const int p = knots.degree();
  const std::vector<double>& t = knots.knots();
  const int n = knots.control_point_count();
  const bool periodic = knots.is_periodic();
  if (!std::isfinite(u)) {
    throw make_error("knot ", u, " to insert is not finite");
  }
  if (periodic) {
    // The seam given as the period end t_{p+n} (or within round-off of either end) is the knot
    // t_p: inserting it there keeps the period list's start and every index in range.
    u = knots.wrap_to_period(u);
  } else if (!(u >= knots.domain_start() && u <= knots.domain_end())) {
    throw make_error("knot ", u, " to insert is outside the domain [", knots.domain_start(), ", ",
                     knots.domain_end(), "]");
  }
  const int s = knots.multiplicity(u);
  if (s + times > p) {
    throw make_error("knot ", u, " has multiplicity ", s, "; inserting it ", times,
                     " more times would exceed the degree ", p);
  }
  // Span k: the last index with t_k <= u (so t_{k-s+1} = .. = t_k = u when s > 0).
  const int k = count_index(std::upper_bound(t.begin(), t.end(), u) - t.begin()) - 1;
  const auto point = [&](int index) { return points.row(periodic ? index % n : index); };
  const auto knot = [&](int index) { return t[static_cast<size_t>(index)]; };

  // A5.1: the p - s + 1 affected points R_i = P_{k-p+i}, updated in place `times` times; the
  // new points Q_{k-p+1}..Q_{k-s+times-1} are collected in `block`.
  Eigen::MatrixXd affected(p - s + 1, points.cols());
  for (int i = 0; i <= p - s; ++i) {
    affected.row(i) = point(k - p + i);
  }
  const int first_new = k - p + 1;
  const int new_count = p - s - 1 + times;
  Eigen::MatrixXd block(new_count, points.cols());
  int left = 0;
  for (int j = 1; j <= times; ++j) {
    left = k - p + j;
    for (int i = 0; i <= p - j - s; ++i) {
      const double alpha = (u - knot(left + i)) / (knot(i + k + 1) - knot(left + i));
      affected.row(i) = alpha * affected.row(i + 1) + (1.0 - alpha) * affected.row(i);
    }
    block.row(left - first_new) = affected.row(0);
    block.row(k + times - j - s - first_new) = affected.row(p - j - s);
  }
  for (int i = left + 1; i < k - s; ++i) {
    block.row(i - first_new) = affected.row(i - left);
  }

  // New knots: u inserted `times` times after t_k.
  std::vector<double> new_knots;
  std::vector<double> source = periodic ? knots.period_knots() : t;
  const int offset = periodic ? p : 0;  // index of source[0] in the stored vector
  new_knots.reserve(source.size() + static_cast<size_t>(times));
  new_knots.insert(new_knots.end(), source.begin(), source.begin() + (k - offset + 1));
  new_knots.insert(new_knots.end(), static_cast<size_t>(times), u);
  new_knots.insert(new_knots.end(), source.begin() + (k - offset + 1), source.end());

  const int new_n = n + times;
  Eigen::MatrixXd new_points(new_n, points.cols());
  if (periodic) {
    // Cyclic polygon: the new block at wrapped indices k-p+1..k-s+times-1, then the unchanged
    // points, Q_i = P_{i - times}, for the rest of one turn.
    for (int i = first_new; i < first_new + new_n; ++i) {
      new_points.row(i % new_n) = i - first_new < new_count
                                      ? Eigen::RowVectorXd(block.row(i - first_new))
                                      : Eigen::RowVectorXd(point(i - times));
    }
    return {KnotVector::periodic(p, new_knots), std::move(new_points)};
  }
  // Open: Q_i = P_i for i <= k-p, the new block, Q_{i+times} = P_i for i >= k-s.
  new_points.topRows(first_new) = points.topRows(first_new);
  new_points.middleRows(first_new, new_count) = block;
  new_points.bottomRows(n - (k - s)) = points.bottomRows(n - (k - s));
  return {KnotVector(p, std::move(new_knots)), std::move(new_points)};
}

// Checks a refinement list: non-decreasing, inside the domain (open), final multiplicity <= p.
void check_refinement(const KnotVector& knots, const std::vector<double>& new_knots) {
  for (size_t i = 0; i < new_knots.size(); ++i) {
    const double x = new_knots[i];
    if (!std::isfinite(x)) {
      throw make_error("refinement knot ", i, " is not finite (", x, ")");
    }
    if (i > 0 && x < new_knots[i - 1]) {
      throw make_error("refinement knots decrease at index ", i, ": ", new_knots[i - 1], " > ", x);
    }
    if (!knots.is_periodic() && !(x >= knots.domain_start() && x <= knots.domain_end())) {
      throw make_error("refinement knot ", x, " is outside the domain [", knots.domain_start(),
                       ", ", knots.domain_end(), "]");
    }
  }
  for (size_t i = 0; i < new_knots.size();) {
    size_t j = i;
    while (j < new_knots.size() && new_knots[j] == new_knots[i]) {
      ++j;
    }
    const int s = knots.multiplicity(new_knots[i]);
    const int added = static_cast<int>(j - i);
    if (s + added > knots.degree()) {
      throw make_error("knot ", new_knots[i], " has multiplicity ", s, "; inserting it ", added,
                       " more times would exceed the degree ", knots.degree());
    }
    i = j;
  }
}

// Piegl & Tiller A5.4 on control rows of an open knot vector; `x` is non-empty, sorted and
// checked. Periodic vectors insert the knots one at a time (A5.1 on the cyclic polygon).
KnotsAndRows refine_knot_rows(const KnotVector& knots, const Eigen::MatrixXd& points,
                              const std::vector<double>& x) {
  if (knots.is_periodic()) {
    KnotsAndRows result{knots, points};
    for (const double value : x) {
      result = insert_knot_rows(result.knots, result.rows, value, 1);
    }
    return result;
  }
  const int p = knots.degree();
  const std::vector<double>& t = knots.knots();
  const int n = count_index(points.rows()) - 1;  // last control point index, as in P&T
  const int m = n + p + 1;                       // last knot index
  const int r = static_cast<int>(x.size()) - 1;  // last new knot index
  const int a = knots.find_span(x.front());
  const int b = knots.find_span(x.back()) + 1;
  const auto knot = [&](int i) { return t[static_cast<size_t>(i)]; };

  Eigen::MatrixXd q(n + r + 2, points.cols());
  std::vector<double> refined(static_cast<size_t>(m) + static_cast<size_t>(r) + 2);
  const auto new_knot = [&](int index) -> double& { return refined[static_cast<size_t>(index)]; };
  const auto new_value = [&](int index) { return x[static_cast<size_t>(index)]; };
  for (int j = 0; j <= a - p; ++j) {
    q.row(j) = points.row(j);
  }
  for (int j = b - 1; j <= n; ++j) {
    q.row(j + r + 1) = points.row(j);
  }
  for (int j = 0; j <= a; ++j) {
    new_knot(j) = knot(j);
  }
  for (int j = b + p; j <= m; ++j) {
    new_knot(j + r + 1) = knot(j);
  }
  int i = b + p - 1;
  int k = b + p + r;
  for (int j = r; j >= 0; --j) {
    // Copy the points and knots past x_j unchanged, then blend the p new points (A5.4 inner loop).
    while (new_value(j) <= knot(i) && i > a) {
      q.row(k - p - 1) = points.row(i - p - 1);
      new_knot(k) = knot(i);
      --k;
      --i;
    }
    q.row(k - p - 1) = q.row(k - p);
    for (int l = 1; l <= p; ++l) {
      const int index = k - p + l;
      double alpha = new_knot(k + l) - new_value(j);
      if (alpha == 0.0) {
        q.row(index - 1) = q.row(index);
      } else {
        alpha /= new_knot(k + l) - knot(i - p + l);
        q.row(index - 1) = alpha * q.row(index - 1) + (1.0 - alpha) * q.row(index);
      }
    }
    new_knot(k) = new_value(j);
    --k;
  }
  return {KnotVector(p, std::move(refined)), std::move(q)};
}

}  // namespace

ControlRows control_rows(const NurbsCurve& curve) {
  ControlRows result;
  if (!curve.is_rational()) {
    result.rows = curve.control_points();
    result.common_weight = common_weight(curve.weights());
    return result;
  }
  result.block_size = 4;
  result.rows.resize(curve.control_point_count(), 4);
  result.rows.leftCols<3>() = curve.control_points().array().colwise() * curve.weights().array();
  result.rows.col(3) = curve.weights();
  return result;
}

ControlRows control_rows(const NurbsSurface& surface, SurfaceDirection direction) {
  ControlRows result;
  const bool along_u = direction == SurfaceDirection::kU;
  const int row_count = along_u ? surface.control_point_count_u() : surface.control_point_count_v();
  const int block_count =
      along_u ? surface.control_point_count_v() : surface.control_point_count_u();
  result.block_size = surface.is_rational() ? 4 : 3;
  if (!surface.is_rational()) {
    result.common_weight = common_weight(surface.weights());
  }
  result.rows.resize(row_count, static_cast<Eigen::Index>(block_count) * result.block_size);
  for (int i = 0; i < row_count; ++i) {
    for (int b = 0; b < block_count; ++b) {
      const int index = surface_point_index(surface, direction, i, b);
      const double w = surface.is_rational() ? surface.weights()[index] : 1.0;
      result.rows.block<1, 3>(i, static_cast<Eigen::Index>(b) * result.block_size) =
          w * surface.control_points().row(index);
      if (surface.is_rational()) {
        result.rows(i, static_cast<Eigen::Index>(b) * 4 + 3) = w;
      }
    }
  }
  return result;
}

NurbsCurve curve_from_control_rows(KnotVector knots, const ControlRows& rows) {
  const Eigen::Index n = rows.rows.rows();
  if (rows.block_size == 3) {
    Eigen::MatrixX3d points = rows.rows;
    Eigen::VectorXd weights = Eigen::VectorXd::Constant(n, rows.common_weight);
    return {std::move(knots), std::move(points), std::move(weights)};
  }
  Eigen::VectorXd weights = rows.rows.col(3);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(weights[i] > 0.0)) {
      throw make_error("control point ", i, " got the non-positive weight ", weights[i]);
    }
  }
  Eigen::MatrixX3d points = rows.rows.leftCols<3>().array().colwise() / weights.array();
  return {std::move(knots), std::move(points), std::move(weights)};
}

NurbsSurface surface_from_control_rows(const NurbsSurface& surface, SurfaceDirection direction,
                                       KnotVector knots, const ControlRows& rows) {
  const bool along_u = direction == SurfaceDirection::kU;
  const int row_count = count_index(rows.rows.rows());
  const int block_count = count_index(rows.rows.cols()) / rows.block_size;
  KnotVector knots_u = surface.knots_u();
  KnotVector knots_v = surface.knots_v();
  (along_u ? knots_u : knots_v) = std::move(knots);
  const int count_v = knots_v.control_point_count();
  const Eigen::Index total = static_cast<Eigen::Index>(row_count) * block_count;
  Eigen::MatrixX3d points(total, 3);
  Eigen::VectorXd weights(total);
  for (int i = 0; i < row_count; ++i) {
    for (int b = 0; b < block_count; ++b) {
      const int index = along_u ? i * count_v + b : b * count_v + i;
      if (rows.block_size == 3) {
        points.row(index) = rows.rows.block<1, 3>(i, static_cast<Eigen::Index>(b) * 3);
        weights[index] = rows.common_weight;
        continue;
      }
      const double w = rows.rows(i, static_cast<Eigen::Index>(b) * 4 + 3);
      if (!(w > 0.0)) {
        throw make_error("control point ", index, " got the non-positive weight ", w);
      }
      weights[index] = w;
      points.row(index) = rows.rows.block<1, 3>(i, static_cast<Eigen::Index>(b) * 4) / w;
    }
  }
  return {std::move(knots_u), std::move(knots_v), std::move(points), std::move(weights)};
}

KnotsAndRows refine_control_rows(const KnotVector& knots, const Eigen::MatrixXd& rows,
                                 const std::vector<double>& new_knots) {
  check_refinement(knots, new_knots);
  if (new_knots.empty()) {
    return {knots, rows};
  }
  return refine_knot_rows(knots, rows, new_knots);
}

NurbsCurve insert_knot(const NurbsCurve& curve, double u, int times) {
  ControlRows rows = control_rows(curve);
  KnotsAndRows result = insert_knot_rows(curve.knots(), rows.rows, u, times);
  rows.rows = std::move(result.rows);
  return curve_from_control_rows(std::move(result.knots), rows);
}

NurbsCurve refine_knots(const NurbsCurve& curve, const std::vector<double>& new_knots) {
  check_refinement(curve.knots(), new_knots);
  if (new_knots.empty()) {
    return curve;
  }
  ControlRows rows = control_rows(curve);
  KnotsAndRows result = refine_knot_rows(curve.knots(), rows.rows, new_knots);
  rows.rows = std::move(result.rows);
  return curve_from_control_rows(std::move(result.knots), rows);
}

NurbsSurface insert_knot(const NurbsSurface& surface, SurfaceDirection direction, double u,
                         int times) {
  const KnotVector& knots =
      direction == SurfaceDirection::kU ? surface.knots_u() : surface.knots_v();
  ControlRows rows = control_rows(surface, direction);
  KnotsAndRows result = insert_knot_rows(knots, rows.rows, u, times);
  rows.rows = std::move(result.rows);
  return surface_from_control_rows(surface, direction, std::move(result.knots), rows);
}

NurbsSurface refine_knots(const NurbsSurface& surface, SurfaceDirection direction,
                          const std::vector<double>& new_knots) {
  const KnotVector& knots =
      direction == SurfaceDirection::kU ? surface.knots_u() : surface.knots_v();
  check_refinement(knots, new_knots);
  if (new_knots.empty()) {
    return surface;
  }
  ControlRows rows = control_rows(surface, direction);
  KnotsAndRows result = refine_knot_rows(knots, rows.rows, new_knots);
  rows.rows = std::move(result.rows);
  return surface_from_control_rows(surface, direction, std::move(result.knots), rows);
}

}  // namespace dnurbs
