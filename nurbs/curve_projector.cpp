#include "dnurbs/nurbs/curve_projector.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/bezier_extraction.h"

namespace dnurbs {
namespace {

// Element i (an int index) of a std::array or std::vector.
template <typename Container>
auto& at(Container& container, int i) {
  return container[static_cast<size_t>(i)];
}

// Round-off allowance of a stationarity coefficient e_k - Q.f_k: each is a sum of a few dozen
// products, so 256 ulps of the magnitudes involved bound its error.
constexpr double kNoise = 256.0 * std::numeric_limits<double>::epsilon();
// Halvings of a segment before an unresolved interval (a double root) is settled by its midpoint.
constexpr int kMaxDepth = 60;
constexpr int kMaxNewtonSteps = 100;

void check_query(const Eigen::Vector3d& point) {
  if (!point.allFinite()) {
    throw make_error("closest point: query point (", point.x(), ", ", point.y(), ", ", point.z(),
                     ") is not finite");
  }
}

// Distance from `point` to the axis-aligned box [low, high].
double box_distance(const Eigen::Vector3d& point, const Eigen::Vector3d& low,
                    const Eigen::Vector3d& high) {
  return (point - point.cwiseMax(low).cwiseMin(high)).norm();
}

}  // namespace

CurveProjector::CurveProjector(NurbsCurve curve) : curve_(std::move(curve)) {
  const int p = curve_.degree();
  const bool rational = curve_.is_rational();
  condition_degree_ = rational ? 3 * p - 1 : 2 * p - 1;
  const Eigen::MatrixX3d& points = curve_.control_points();
  scale_ = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
  // Homogeneous rows (w x, w y, w z, w); a polynomial curve uses w = 1.
  Eigen::MatrixXd rows(points.rows(), 4);
  rows.leftCols<3>() =
      rational ? Eigen::MatrixX3d(points.array().colwise() * curve_.weights().array()) : points;
  rows.col(3) = rational ? curve_.weights() : Eigen::VectorXd::Ones(points.rows());
  for (const int span : curve_.knots().non_empty_spans()) {
    build_segment(span, rows);
  }
}

void CurveProjector::build_segment(int span, const Eigen::MatrixXd& homogeneous_rows) {
  const KnotVector& knots = curve_.knots();
  const int p = knots.degree();
  Segment segment;
  segment.start = knots[span];
  segment.end = knots[span + 1];
  segment.homogeneous = bezier_segment(knots, homogeneous_rows, span);
  const auto corner = [&](double knot) {
    const bool domain_end = knot == knots.domain_start() || knot == knots.domain_end();
    return (domain_end && !knots.is_periodic()) || knots.multiplicity(knot) >= p;
  };
  segment.start_is_corner = corner(segment.start);
  segment.end_is_corner = corner(segment.end);
  const auto& h = segment.homogeneous;
  segment.box_min = segment.box_max = h.row(0).head<3>().transpose() / h(0, 3);
  for (int i = 1; i <= p; ++i) {
    const Eigen::Vector3d projected = h.row(i).head<3>().transpose() / h(i, 3);
    segment.box_min = segment.box_min.cwiseMin(projected);
    segment.box_max = segment.box_max.cwiseMax(projected);
  }
  // Stationarity of |C - Q|^2: (C - Q).C' = (H - w Q).D / w^3 with D = H' w - H w' (degree
  // 2p - 1; D = C' of degree p - 1 for a polynomial curve, w = 1). Products of Bernstein forms
  // (Farouki & Rajan eq. 7) give g = (H - w Q).D = e - Q.f, e = H.D, f = w D.
  const auto hodograph = [&](int i) -> Eigen::Vector4d {
    return p * (h.row(i + 1) - h.row(i)).transpose();
  };
  const bool rational = curve_.is_rational();
  const int d_degree = rational ? 2 * p - 1 : p - 1;
  std::array<Eigen::Vector3d, kMaxBernsteinDegree + 1> d{};
  for (int k = 0; k <= d_degree; ++k) {
    d[static_cast<size_t>(k)].setZero();
  }
  for (int i = 0; i < p; ++i) {
    const Eigen::Vector4d derivative = hodograph(i);
    if (!rational) {
      d[static_cast<size_t>(i)] = derivative.head<3>();
      continue;
    }
    for (int j = 0; j <= p; ++j) {
      at(d, i + j) +=
          bernstein_product_weight(p - 1, i, p, j) *
          (derivative.head<3>() * h(j, 3) - h.row(j).head<3>().transpose() * derivative[3]);
    }
  }
  for (int k = 0; k <= condition_degree_; ++k) {
    segment.e[static_cast<size_t>(k)] = 0.0;
    segment.f[static_cast<size_t>(k)].setZero();
  }
  for (int i = 0; i <= p; ++i) {
    for (int j = 0; j <= d_degree; ++j) {
      const double weight = bernstein_product_weight(p, i, d_degree, j);
      const Eigen::Vector3d& dj = d[static_cast<size_t>(j)];
      at(segment.e, i + j) += weight * h.row(i).head<3>().dot(dj.transpose());
      at(segment.f, i + j) += weight * h(i, 3) * dj;
    }
  }
  for (int k = 0; k <= condition_degree_; ++k) {
    segment.e_magnitude =
        std::max(segment.e_magnitude, std::abs(segment.e[static_cast<size_t>(k)]));
    segment.f_magnitude = std::max(segment.f_magnitude, segment.f[static_cast<size_t>(k)].norm());
  }
  segments_.push_back(segment);
}

CurveProjector::SegmentPoint CurveProjector::evaluate(const Segment& segment, double t) const {
  const int p = curve_.degree();
  BernsteinBasis basis;
  bernstein_basis(p, t, basis);
  Eigen::Vector4d h = Eigen::Vector4d::Zero();
  Eigen::Vector4d h1 = Eigen::Vector4d::Zero();
  Eigen::Vector4d h2 = Eigen::Vector4d::Zero();
  for (int i = 0; i <= p; ++i) {
    const Eigen::Vector4d row = segment.homogeneous.row(i).transpose();
    h += basis[0][static_cast<size_t>(i)] * row;
    h1 += basis[1][static_cast<size_t>(i)] * row;
    h2 += basis[2][static_cast<size_t>(i)] * row;
  }
  // Quotient rule (Piegl & Tiller eq. 4.8): C = H / w, C' = (H' - w' C) / w,
  // C'' = (H'' - 2 w' C' - w'' C) / w.
  SegmentPoint result;
  result.point = h.head<3>() / h[3];
  result.first = (h1.head<3>() - h1[3] * result.point) / h[3];
  result.second = (h2.head<3>() - 2.0 * h1[3] * result.first - h2[3] * result.point) / h[3];
  return result;
}

void CurveProjector::consider(const Segment& segment, double t, const Eigen::Vector3d& point,
                              const Eigen::Vector3d& query, bool exact, Best& best) const {
  double parameter = t >= 1.0 ? segment.end : segment.start + t * (segment.end - segment.start);
  const KnotVector& knots = curve_.knots();
  if (knots.is_periodic() && parameter >= knots.domain_end()) {
    parameter = knots.domain_start();  // the seam is reported as the period start
  }
  best.offer((point - query).norm(), parameter, exact);
}

double CurveProjector::solve_bracketed(const Segment& segment, const Eigen::Vector3d& query,
                                       double low, double high) const {
  // Safeguarded Newton (rtsafe) on phi(t) = (C - Q).C', phi' = |C'|^2 + (C - Q).C'', with
  // phi(low) < 0 < phi(high): a Newton step that leaves the bracket is replaced by bisection.
  double t = 0.5 * (low + high);
  for (int step = 0; step < kMaxNewtonSteps; ++step) {
    const SegmentPoint value = evaluate(segment, t);
    const Eigen::Vector3d offset = value.point - query;
    const double phi = offset.dot(value.first);
    const double slope = value.first.squaredNorm() + offset.dot(value.second);
    if (phi == 0.0) {
      return t;
    }
    (phi < 0.0 ? low : high) = t;
    if (slope > 0.0) {
      const double newton = t - phi / slope;
      if (std::abs(newton - t) <= 2.0 * std::numeric_limits<double>::epsilon()) {
        return std::clamp(newton, low, high);  // converged
      }
      if (newton > low && newton < high) {
        t = newton;
        continue;
      }
    }
    if (high - low <= 2.0 * std::numeric_limits<double>::epsilon()) {
      return t;
    }
    t = 0.5 * (low + high);
  }
  return t;
}

void CurveProjector::isolate(const Segment& segment, const Eigen::Vector3d& query,
                             const double* coefficients, double noise, double low, double high,
                             int depth, Best& best) const {
  const int degree = condition_degree_;
  const int changes = bernstein_sign_changes(coefficients, degree + 1, noise);
  if (changes == 0) {
    return;  // no stationary point inside: the ends (already candidates) hold the minimum
  }
  if (changes == 1 || depth >= kMaxDepth) {
    // One root (Descartes): a minimum of the distance if g goes from - to +.
    int first = 0;
    while (std::abs(coefficients[first]) <= noise) {
      ++first;
    }
    if (coefficients[first] < 0.0 || depth >= kMaxDepth) {
      // At the depth limit (an unresolved double root) the result is only approximate.
      const double t = solve_bracketed(segment, query, low, high);
      consider(segment, t, evaluate(segment, t).point, query, depth < kMaxDepth, best);
    }
    return;
  }
  std::array<double, kMaxBernsteinDegree + 1> left{};
  std::array<double, kMaxBernsteinDegree + 1> right{};
  split_bernstein_half(coefficients, degree, 1, left.data(), right.data());
  const double middle = 0.5 * (low + high);
  isolate(segment, query, left.data(), noise, low, middle, depth + 1, best);
  isolate(segment, query, right.data(), noise, middle, high, depth + 1, best);
}

void CurveProjector::search_segment(const Segment& segment, const Eigen::Vector3d& query,
                                    Best& best) const {
  const int p = curve_.degree();
  const auto& h = segment.homogeneous;
  std::array<double, kMaxBernsteinDegree + 1> coefficients{};
  for (int k = 0; k <= condition_degree_; ++k) {
    coefficients[static_cast<size_t>(k)] =
        segment.e[static_cast<size_t>(k)] - query.dot(segment.f[static_cast<size_t>(k)]);
  }
  const double noise = kNoise * (segment.e_magnitude + query.norm() * segment.f_magnitude);
  // The ends are candidates where the minimum may sit unstationary (curve ends, C^0 knots) or
  // where they are stationary to round-off (g = c_0 or c_last vanishes); else they only bound.
  const Eigen::Vector3d start = h.row(0).head<3>().transpose() / h(0, 3);
  const Eigen::Vector3d end = h.row(p).head<3>().transpose() / h(p, 3);
  if (segment.start_is_corner || std::abs(coefficients[0]) <= noise) {
    consider(segment, 0.0, start, query, true, best);
  } else {
    best.bound_by((start - query).norm());
  }
  if (segment.end_is_corner ||
      std::abs(coefficients[static_cast<size_t>(condition_degree_)]) <= noise) {
    consider(segment, 1.0, end, query, true, best);
  } else {
    best.bound_by((end - query).norm());
  }
  isolate(segment, query, coefficients.data(), noise, 0.0, 1.0, 0, best);
}

std::optional<CurveProjection> CurveProjector::closest_point_within(const Eigen::Vector3d& point,
                                                                    double bound) const {
  check_query(point);
  // Segments in the order of their lower bounds (box distances; ties by index).
  std::vector<std::pair<double, int>> order;
  order.reserve(segments_.size());
  for (size_t i = 0; i < segments_.size(); ++i) {
    const double lower = box_distance(point, segments_[i].box_min, segments_[i].box_max);
    if (lower <= bound * (1.0 + kProjectionTieTolerance) + kProjectionTieTolerance * scale_) {
      order.emplace_back(lower, static_cast<int>(i));
    }
  }
  std::sort(order.begin(), order.end());
  Best best;
  best.bound = bound;
  best.absolute_tie = kProjectionTieTolerance * scale_;
  for (const auto& [lower, index] : order) {
    if (lower > best.pruning_bound()) {
      break;  // no remaining segment can hold a nearer point
    }
    search_segment(segments_[static_cast<size_t>(index)], point, best);
  }
  if (!best.found || best.distance > bound * (1.0 + kProjectionTieTolerance) + best.absolute_tie) {
    return std::nullopt;
  }
  CurveProjection result;
  result.parameter = best.parameter;
  result.point = curve_.point(best.parameter);
  result.distance = (result.point - point).norm();
  return result;
}

CurveProjection CurveProjector::closest_point(const Eigen::Vector3d& point) const {
  return *closest_point_within(point, std::numeric_limits<double>::infinity());
}

double CurveProjector::invert(const Eigen::Vector3d& point, double tolerance) const {
  const CurveProjection projection = closest_point(point);
  if (!(projection.distance <= tolerance)) {
    throw make_error("point (", point.x(), ", ", point.y(), ", ", point.z(), ") is ",
                     projection.distance, " from the curve, farther than the tolerance ",
                     tolerance);
  }
  return projection.parameter;
}

}  // namespace dnurbs
