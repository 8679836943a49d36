#include "dnurbs/nurbs/triangular_polynomial_cells.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/simplex_spline.h"

namespace dnurbs {

namespace {

double polygon_area(const ConvexPolygon& polygon) {
  double twice = 0.0;
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d& a = polygon[k];
    const Eigen::Vector2d& b = polygon[(k + 1) % polygon.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

// The part of segment [p, q] inside the convex polygon (Cyrus-Beck), or false if it is shorter
// than `tolerance`.
bool clip_segment(const ConvexPolygon& polygon, const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                  double tolerance, Eigen::Vector2d& a, Eigen::Vector2d& b) {
  double enter = 0.0;
  double leave = 1.0;
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d& e0 = polygon[k];
    const Eigen::Vector2d& e1 = polygon[(k + 1) % polygon.size()];
    const double length = (e1 - e0).norm();
    const double f0 = signed_double_area(e0, e1, p) / length;  // distance inside (> 0)
    const double f1 = signed_double_area(e0, e1, q) / length;
    if (f0 < 0.0 && f1 < 0.0) {
      return false;
    }
    if (f0 < 0.0) {
      enter = std::max(enter, f0 / (f0 - f1));
    } else if (f1 < 0.0) {
      leave = std::min(leave, f0 / (f0 - f1));
    }
  }
  if (leave <= enter) {
    return false;
  }
  a = p + enter * (q - p);
  b = p + leave * (q - p);
  return (b - a).norm() > tolerance;
}

// Distances of the polygon's vertices from the line p -> q (positive on its left).
std::vector<double> side_distances(const ConvexPolygon& polygon, const Eigen::Vector2d& p,
                                   const Eigen::Vector2d& q) {
  const double length = (q - p).norm();
  std::vector<double> side;
  side.reserve(polygon.size());
  for (const Eigen::Vector2d& x : polygon) {
    side.push_back(signed_double_area(p, q, x) / length);
  }
  return side;
}

// True if segment [p, q] crosses the interior of the polygon: its line has vertices farther
// than `tolerance` on both sides and a piece of the segment lies inside.
bool crosses(const ConvexPolygon& polygon, const Eigen::Vector2d& p, const Eigen::Vector2d& q,
             double tolerance) {
  const std::vector<double> side = side_distances(polygon, p, q);
  const auto [low, high] = std::minmax_element(side.begin(), side.end());
  if (*low >= -tolerance || *high <= tolerance) {
    return false;
  }
  Eigen::Vector2d a;
  Eigen::Vector2d b;
  return clip_segment(polygon, p, q, tolerance, a, b);
}

// The two halves of the polygon on the left and right of the line p -> q (vertices within
// `tolerance` of the line go to both).
std::pair<ConvexPolygon, ConvexPolygon> split(const ConvexPolygon& polygon,
                                              const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                                              double tolerance) {
  const std::vector<double> side = side_distances(polygon, p, q);
  ConvexPolygon left;
  ConvexPolygon right;
  const size_t count = polygon.size();
  for (size_t k = 0; k < count; ++k) {
    const double s0 = std::abs(side[k]) <= tolerance ? 0.0 : side[k];
    const double s1 = std::abs(side[(k + 1) % count]) <= tolerance ? 0.0 : side[(k + 1) % count];
    if (s0 >= 0.0) {
      left.push_back(polygon[k]);
    }
    if (s0 <= 0.0) {
      right.push_back(polygon[k]);
    }
    if ((s0 > 0.0 && s1 < 0.0) || (s0 < 0.0 && s1 > 0.0)) {
      const Eigen::Vector2d x =
          polygon[k] + (polygon[(k + 1) % count] - polygon[k]) * (s0 / (s0 - s1));
      left.push_back(x);
      right.push_back(x);
    }
  }
  return {std::move(left), std::move(right)};
}

}  // namespace

Eigen::MatrixX4d knot_segments_in_triangle(const TriangularBSplineBasis& basis, int t) {
  const Triangulation& triangulation = basis.triangulation();
  if (t < 0 || t >= triangulation.triangle_count()) {
    throw make_error("triangle ", t, " is outside 0..", triangulation.triangle_count() - 1);
  }
  const int n = basis.degree();
  const double tolerance = TriangularBSplineBasis::kSnapTolerance * triangulation.diameter();
  const ConvexPolygon triangle = {triangulation.corner(t, 0), triangulation.corner(t, 1),
                                  triangulation.corner(t, 2)};
  std::set<std::array<double, 4>> seen;
  std::vector<std::array<double, 4>> segments;
  auto add = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    const bool swap = q.x() < p.x() || (q.x() == p.x() && q.y() < p.y());
    const std::array<double, 4> key = swap ? std::array<double, 4>{q.x(), q.y(), p.x(), p.y()}
                                           : std::array<double, 4>{p.x(), p.y(), q.x(), q.y()};
    if (!seen.insert(key).second) {
      return;
    }
    Eigen::Vector2d a;
    Eigen::Vector2d b;
    if (!clip_segment(triangle, p, q, tolerance, a, b)) {
      return;
    }
    // Parts on an edge of the triangle cut nothing.
    for (int e = 0; e < 3; ++e) {
      const Eigen::Vector2d& e0 = triangle[static_cast<size_t>(e)];
      const Eigen::Vector2d& e1 = triangle[static_cast<size_t>((e + 1) % 3)];
      const double length = (e1 - e0).norm();
      if (std::abs(signed_double_area(e0, e1, a)) <= tolerance * length &&
          std::abs(signed_double_area(e0, e1, b)) <= tolerance * length) {
        return;
      }
    }
    segments.push_back({a.x(), a.y(), b.x(), b.y()});
  };
  const TriangularKnotClouds& clouds = basis.knot_clouds();
  for (const int s : basis.overlapping_triangles(t)) {
    std::array<int, 3> vertex{};
    for (int c = 0; c < 3; ++c) {
      vertex[static_cast<size_t>(c)] = triangulation.triangles()(s, c);
    }
    for (int c = 0; c < 3; ++c) {
      const int v = vertex[static_cast<size_t>(c)];
      const int w = vertex[static_cast<size_t>((c + 1) % 3)];
      for (int a = 0; a <= n; ++a) {
        for (int b = a + 1; b <= n; ++b) {
          add(clouds.knot(v, a), clouds.knot(v, b));  // two knots of one cloud
        }
        for (int b = 0; a + b <= n; ++b) {
          add(clouds.knot(v, a), clouds.knot(w, b));  // t_{v,a}, t_{w,b} with a + b <= n
        }
      }
    }
  }
  Eigen::MatrixX4d result(static_cast<Eigen::Index>(segments.size()), 4);
  for (size_t k = 0; k < segments.size(); ++k) {
    for (int c = 0; c < 4; ++c) {
      result(static_cast<Eigen::Index>(k), c) = segments[k][static_cast<size_t>(c)];
    }
  }
  return result;
}

std::vector<ConvexPolygon> polynomial_cells(const TriangularBSplineBasis& basis, int t) {
  const Eigen::MatrixX4d segments = knot_segments_in_triangle(basis, t);
  const Triangulation& triangulation = basis.triangulation();
  const double tolerance = TriangularBSplineBasis::kSnapTolerance * triangulation.diameter();
  const double minimum_area = 1e-16 * triangulation.area(t);
  std::vector<ConvexPolygon> cells;
  // Depth-first splitting: a polygon with the segments that may still cross it.
  std::vector<std::pair<ConvexPolygon, std::vector<int>>> stack;
  std::vector<int> all(static_cast<size_t>(segments.rows()));
  for (size_t k = 0; k < all.size(); ++k) {
    all[k] = static_cast<int>(k);
  }
  stack.emplace_back(ConvexPolygon{triangulation.corner(t, 0), triangulation.corner(t, 1),
                                   triangulation.corner(t, 2)},
                     std::move(all));
  while (!stack.empty()) {
    auto [polygon, candidates] = std::move(stack.back());
    stack.pop_back();
    std::vector<int> crossing;
    for (const int k : candidates) {
      if (crosses(polygon, segments.row(k).head<2>(), segments.row(k).tail<2>(), tolerance)) {
        crossing.push_back(k);
      }
    }
    if (crossing.empty()) {
      if (polygon_area(polygon) > minimum_area) {
        cells.push_back(std::move(polygon));
      }
      continue;
    }
    const int cut = crossing.front();
    crossing.erase(crossing.begin());
    auto [left, right] =
        split(polygon, segments.row(cut).head<2>(), segments.row(cut).tail<2>(), tolerance);
    stack.emplace_back(std::move(left), crossing);
    stack.emplace_back(std::move(right), std::move(crossing));
  }
  return cells;
}

}  // namespace dnurbs
