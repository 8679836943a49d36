#include "dnurbs/nurbs/triangular_bspline_basis.h"

#include <algorithm>
#include <cstdint>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

// Convex hull, counter-clockwise (Andrew's monotone chain).
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  size_t k = 0;
  for (size_t pass = 0; pass < 2; ++pass) {
    const size_t start = k;
    for (size_t s = 0; s < points.size(); ++s) {
      const Eigen::Vector2d& p = pass == 0 ? points[s] : points[points.size() - 1 - s];
      while (k >= start + 2 && signed_double_area(hull[k - 2], hull[k - 1], p) <= 0.0) {
        --k;
      }
      hull[k++] = p;
    }
    --k;  // the last point is the first of the other chain
  }
  hull.resize(k);
  return hull;
}

// True if some edge of `a` has all of `b` strictly on its right (farther than tolerance).
bool separated_by_edge_of(const std::vector<Eigen::Vector2d>& a,
                          const std::vector<Eigen::Vector2d>& b, double tolerance) {
  for (size_t e = 0; e < a.size(); ++e) {
    const Eigen::Vector2d& p = a[e];
    const Eigen::Vector2d& q = a[(e + 1) % a.size()];
    const double limit = -tolerance * (q - p).norm();
    if (std::all_of(b.begin(), b.end(), [&](const Eigen::Vector2d& x) {
          return signed_double_area(p, q, x) < limit;
        })) {
      return true;
    }
  }
  return false;
}

}  // namespace

TriangularBSplineBasis::TriangularBSplineBasis(Triangulation triangulation,
                                               TriangularKnotClouds clouds)
    : triangulation_(std::move(triangulation)), clouds_(std::move(clouds)) {
  check_knot_clouds(triangulation_, clouds_);
  const int n = clouds_.degree();
  per_triangle_ = (n + 1) * (n + 2) / 2;
  for (int b0 = n; b0 >= 0; --b0) {
    for (int b1 = n - b0; b1 >= 0; --b1) {
      multi_indices_.push_back({b0, b1, n - b0 - b1});
    }
  }
  tolerance_ = kSnapTolerance * triangulation_.diameter();

  // Per triangle: the knot sets V_beta^I as masks over its 3 (n + 1) knots (knot b of corner c
  // is bit c (n + 1) + b), grouped by corner so that the recurrence removes the last knot of a
  // cloud (Dahmen, Micchelli & Seidel 1992, the recurrence behind their Theorem 4.1).
  const int triangles = triangulation_.triangle_count();
  std::vector<int> group(static_cast<size_t>(3 * (n + 1)));
  for (size_t k = 0; k < group.size(); ++k) {
    group[k] = static_cast<int>(k) / (n + 1);
  }
  splines_.reserve(static_cast<size_t>(triangles));
  normalization_.resize(static_cast<size_t>(function_count()));
  std::vector<std::vector<Eigen::Vector2d>> hulls(static_cast<size_t>(triangles));
  for (int t = 0; t < triangles; ++t) {
    Eigen::MatrixX2d knots(3 * (n + 1), 2);
    std::vector<Eigen::Vector2d> points;
    for (int c = 0; c < 3; ++c) {
      for (int b = 0; b <= n; ++b) {
        const Eigen::Vector2d knot = clouds_.knot(triangulation_.triangles()(t, c), b);
        knots.row(c * (n + 1) + b) = knot.transpose();
        points.push_back(knot);
      }
    }
    std::vector<std::uint32_t> sets;
    for (int b = 0; b < per_triangle_; ++b) {
      const std::array<int, 3>& beta = multi_indices_[static_cast<size_t>(b)];
      std::uint32_t mask = 0;
      for (int c = 0; c < 3; ++c) {
        for (int k = 0; k <= beta[static_cast<size_t>(c)]; ++k) {
          mask |= 1U << static_cast<unsigned>(c * (n + 1) + k);
        }
      }
      sets.push_back(mask);
      const int function = t * per_triangle_ + b;
      normalization_[static_cast<size_t>(function)] = signed_double_area(
          knots.row(beta[0]).transpose(), knots.row((n + 1) + beta[1]).transpose(),
          knots.row(2 * (n + 1) + beta[2]).transpose());
    }
    splines_.emplace_back(knots, sets, group);
    const Eigen::Vector2d lo = knots.colwise().minCoeff().transpose();
    const Eigen::Vector2d hi = knots.colwise().maxCoeff().transpose();
    knot_box_.emplace_back(lo.x(), lo.y(), hi.x(), hi.y());
    hulls[static_cast<size_t>(t)] = convex_hull(points);
  }

  // Which triangles each knot hull meets (separating-axis test of two convex polygons).
  overlapping_.assign(static_cast<size_t>(triangles), {});
  std::vector<int> near;
  for (int s = 0; s < triangles; ++s) {
    const Eigen::Vector4d& box = knot_box_[static_cast<size_t>(s)];
    near.clear();
    triangulation_.triangles_near_box(box.head<2>(), box.tail<2>(), near);
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    const auto& hull = hulls[static_cast<size_t>(s)];
    for (const int t : near) {
      const std::vector<Eigen::Vector2d> corners = {
          triangulation_.corner(t, 0), triangulation_.corner(t, 1), triangulation_.corner(t, 2)};
      if (!separated_by_edge_of(hull, corners, tolerance_) &&
          !separated_by_edge_of(corners, hull, tolerance_)) {
        overlapping_[static_cast<size_t>(t)].push_back(s);
      }
    }
  }
  for (auto& list : overlapping_) {
    std::sort(list.begin(), list.end());
  }
}

int TriangularBSplineBasis::local_index(const std::array<int, 3>& beta) const {
  const auto found = std::find(multi_indices_.begin(), multi_indices_.end(), beta);
  if (found == multi_indices_.end()) {
    throw make_error("multi-index (", beta[0], ", ", beta[1], ", ", beta[2], ") is not of degree ",
                     degree());
  }
  return static_cast<int>(found - multi_indices_.begin());
}

Eigen::MatrixX2d TriangularBSplineBasis::knot_set(int function) const {
  const int n = degree();
  const int t = triangle_of(function);
  const std::array<int, 3>& beta = multi_indices_[static_cast<size_t>(function % per_triangle_)];
  Eigen::MatrixX2d result(n + 3, 2);
  int row = 0;
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k <= beta[static_cast<size_t>(c)]; ++k) {
      result.row(row++) = clouds_.knot(triangulation_.triangles()(t, c), k).transpose();
    }
  }
  return result;
}

Eigen::MatrixX2d TriangularBSplineBasis::blossom_arguments(int function) const {
  const int n = degree();
  const int t = triangle_of(function);
  const std::array<int, 3>& beta = multi_indices_[static_cast<size_t>(function % per_triangle_)];
  Eigen::MatrixX2d result(n, 2);
  int row = 0;
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < beta[static_cast<size_t>(c)]; ++k) {
      result.row(row++) = clouds_.knot(triangulation_.triangles()(t, c), k).transpose();
    }
  }
  return result;
}

Eigen::MatrixX2d TriangularBSplineBasis::domain_points() const {
  Eigen::MatrixX2d points(function_count(), 2);
  for (int f = 0; f < function_count(); ++f) {
    points.row(f) = blossom_arguments(f).colwise().mean();
  }
  return points;
}

void TriangularBSplineBasis::evaluate(const Eigen::Vector2d& u, int order,
                                      TriangularBasisValues& values) const {
  const int t = triangulation_.locate(u);
  if (t < 0) {
    throw make_error("point (", u.x(), ", ", u.y(), ") is outside the triangulated domain");
  }
  evaluate_in_triangle(t, u, order, values);
}

void TriangularBSplineBasis::evaluate_in_triangle(int t, const Eigen::Vector2d& u, int order,
                                                  TriangularBasisValues& values) const {
  if (t < 0 || t >= triangulation_.triangle_count()) {
    throw make_error("triangle ", t, " is outside 0..", triangulation_.triangle_count() - 1);
  }
  // Follow the pieces from u towards the centroid: inside t for u in its closure.
  Eigen::Vector2d direction = triangulation_.centroid(t) - u;
  if (direction.norm() <= tolerance_) {
    direction = Triangulation::half_open_direction();
  }
  evaluate_in_triangle(t, u, direction, order, values);
}

void TriangularBSplineBasis::check_point(int t, const Eigen::Vector2d& u,
                                         const Eigen::Vector2d& direction) const {
  if (t < 0 || t >= triangulation_.triangle_count()) {
    throw make_error("triangle ", t, " is outside 0..", triangulation_.triangle_count() - 1);
  }
  if (!u.allFinite() || !direction.allFinite() || direction.squaredNorm() == 0.0) {
    throw make_error("cannot evaluate triangular B-splines at (", u.x(), ", ", u.y(),
                     ") in direction (", direction.x(), ", ", direction.y(), ")");
  }
}

bool TriangularBSplineBasis::outside_knot_box(int s, const Eigen::Vector2d& u) const {
  // Outside the knot box every B-spline of triangle s is zero.
  const Eigen::Vector4d& box = knot_box_[static_cast<size_t>(s)];
  return u.x() < box[0] - tolerance_ || u.y() < box[1] - tolerance_ ||
         u.x() > box[2] + tolerance_ || u.y() > box[3] + tolerance_;
}

void TriangularBSplineBasis::evaluate_in_triangle(int t, const Eigen::Vector2d& u,
                                                  const Eigen::Vector2d& direction, int order,
                                                  TriangularBasisValues& values) const {
  check_point(t, u, direction);
  if (order < 0 || order > 2) {
    throw make_error("triangular B-spline derivative order ", order, " is outside 0..2");
  }
  const auto& overlapping = overlapping_[static_cast<size_t>(t)];
  values.triangle = t;
  values.count = static_cast<int>(overlapping.size()) * per_triangle_;
  values.function.resize(static_cast<size_t>(values.count));
  values.value.setZero(6, values.count);
  for (size_t k = 0; k < overlapping.size(); ++k) {
    const int s = overlapping[k];
    const int first = static_cast<int>(k) * per_triangle_;
    for (int b = 0; b < per_triangle_; ++b) {
      values.function[static_cast<size_t>(first) + static_cast<size_t>(b)] = s * per_triangle_ + b;
    }
    if (outside_knot_box(s, u)) {
      continue;
    }
    splines_[static_cast<size_t>(s)].evaluate(u, direction, tolerance_, order, values.simplex,
                                              values.scratch);
    for (int b = 0; b < per_triangle_; ++b) {
      values.value.col(first + b) = normalization(s * per_triangle_ + b) * values.simplex.col(b);
    }
  }
}

void TriangularBSplineBasis::derivatives_in_triangle(int t, const Eigen::Vector2d& u,
                                                     const Eigen::Vector2d& direction, int order,
                                                     std::vector<int>& functions,
                                                     Eigen::MatrixXd& derivatives,
                                                     std::vector<double>& scratch) const {
  check_point(t, u, direction);
  const auto& overlapping = overlapping_[static_cast<size_t>(t)];
  const auto count = static_cast<Eigen::Index>(overlapping.size()) * per_triangle_;
  functions.resize(static_cast<size_t>(count));
  derivatives.setZero(derivative_count(order), count);
  Eigen::MatrixXd simplex;
  for (size_t k = 0; k < overlapping.size(); ++k) {
    const int s = overlapping[k];
    const auto first = static_cast<Eigen::Index>(k) * per_triangle_;
    for (int b = 0; b < per_triangle_; ++b) {
      functions[static_cast<size_t>(first + b)] = s * per_triangle_ + b;
    }
    if (outside_knot_box(s, u)) {
      continue;
    }
    splines_[static_cast<size_t>(s)].evaluate_derivatives(u, direction, tolerance_, order, simplex,
                                                          scratch);
    for (int b = 0; b < per_triangle_; ++b) {
      derivatives.col(first + b) = normalization(s * per_triangle_ + b) * simplex.col(b);
    }
  }
}

}  // namespace dnurbs
