#include "dnurbs/nurbs/triangular_knot_clouds.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/simplex_spline.h"

namespace dnurbs {

namespace {

// Relative area 2 area / (longest side)^2 of a triangle, signed (positive counter-clockwise).
double relative_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double longest =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return longest > 0.0 ? signed_double_area(a, b, c) / longest : 0.0;
}

// The knots of triangle t: knot b of corner c at row c (n + 1) + b.
Eigen::MatrixX2d triangle_knots(const Triangulation& triangulation,
                                const TriangularKnotClouds& clouds, int t) {
  const int n = clouds.degree();
  Eigen::MatrixX2d knots(3 * (n + 1), 2);
  for (int c = 0; c < 3; ++c) {
    for (int b = 0; b <= n; ++b) {
      knots.row(c * (n + 1) + b) = clouds.knot(triangulation.triangles()(t, c), b).transpose();
    }
  }
  return knots;
}

// Convex polygon clipped to the closed half-plane left of p -> q (Sutherland-Hodgman).
std::vector<Eigen::Vector2d> clip_left(const std::vector<Eigen::Vector2d>& polygon,
                                       const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  std::vector<Eigen::Vector2d> result;
  const size_t count = polygon.size();
  for (size_t k = 0; k < count; ++k) {
    const Eigen::Vector2d& a = polygon[k];
    const Eigen::Vector2d& b = polygon[(k + 1) % count];
    const double sa = signed_double_area(p, q, a);
    const double sb = signed_double_area(p, q, b);
    if (sa >= 0.0) {
      result.push_back(a);
    }
    if ((sa > 0.0 && sb < 0.0) || (sa < 0.0 && sb > 0.0)) {
      result.push_back(a + (b - a) * (sa / (sa - sb)));
    }
  }
  return result;
}

double polygon_area(const std::vector<Eigen::Vector2d>& polygon) {
  double twice = 0.0;
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d& a = polygon[k];
    const Eigen::Vector2d& b = polygon[(k + 1) % polygon.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

// Calls visit(beta_0, beta_1, beta_2) for every multi-index with |beta| <= n.
template <typename Visit>
void for_each_multi_index_up_to(int n, Visit visit) {
  for (int total = 0; total <= n; ++total) {
    for (int b0 = total; b0 >= 0; --b0) {
      for (int b1 = total - b0; b1 >= 0; --b1) {
        visit(b0, b1, total - b0 - b1);
      }
    }
  }
}

void check_triangle(const Triangulation& triangulation, const TriangularKnotClouds& clouds, int t) {
  const int n = clouds.degree();
  const Eigen::MatrixX2d knots = triangle_knots(triangulation, clouds, t);
  auto name = [&](int local) {
    return "t[" + std::to_string(triangulation.triangles()(t, local / (n + 1))) + "][" +
           std::to_string(local % (n + 1)) + "]";
  };
  auto point = [&](int local) -> Eigen::Vector2d { return knots.row(local).transpose(); };
  // Condition 2 (DMS (i)) and condition 3 (DMS (ii)): knot triangles positive, and the
  // intersection of them all has an interior.
  std::vector<Eigen::Vector2d> common = {point(0), point(n + 1), point(2 * (n + 1))};
  for_each_multi_index_up_to(n, [&](int b0, int b1, int b2) {
    const int a = b0;
    const int b = (n + 1) + b1;
    const int c = 2 * (n + 1) + b2;
    const double area = relative_area(point(a), point(b), point(c));
    if (area <= TriangularKnotClouds::kGeneralPosition) {
      throw make_error("knot clouds violate the DMS condition in triangle ", t,
                       ": the knot triangle (", name(a), ", ", name(b), ", ", name(c),
                       ") has relative signed area ", area,
                       "; it must be counter-clockwise like the triangle and not degenerate");
    }
    for (int e = 0; e < 3 && !common.empty(); ++e) {
      const std::array<int, 3> corner = {a, b, c};
      common = clip_left(common, point(corner[static_cast<size_t>(e)]),
                         point(corner[static_cast<size_t>((e + 1) % 3)]));
    }
  });
  if (common.size() < 3 || polygon_area(common) <= 0.0) {
    throw make_error("knot clouds violate the DMS condition in triangle ", t,
                     ": the knot triangles (t[i][beta_0], t[j][beta_1], t[k][beta_2]), |beta| <= ",
                     n, ", have no interior point in common (the clouds are too large)");
  }
  // Condition 5: general position of all knots of the triangle.
  const int count = 3 * (n + 1);
  for (int a = 0; a < count; ++a) {
    for (int b = a + 1; b < count; ++b) {
      for (int c = b + 1; c < count; ++c) {
        const double area = std::abs(relative_area(point(a), point(b), point(c)));
        if (area <= TriangularKnotClouds::kGeneralPosition) {
          throw make_error("knots ", name(a), ", ", name(b), " and ", name(c), " of triangle ", t,
                           " are collinear (relative area ", area,
                           "): knots must be in general position");
        }
      }
    }
  }
}

// The lowest smallest relative area of the knot triples of vertex i's fan triangles that
// involve knots t_{i,1..n} (clouds of vertices not yet placed contribute only t_{j,0}); -1 if a
// knot triangle of condition 2 is not positive.
double placement_quality(const Triangulation& triangulation, const Eigen::MatrixX2d& knots,
                         const std::vector<bool>& placed, int n, int i) {
  double quality = 1.0;
  std::vector<Eigen::Vector2d> points;
  std::vector<int> corner_of;
  std::vector<int> index_of;
  for (const int t : triangulation.vertex_triangles(i)) {
    points.clear();
    corner_of.clear();
    index_of.clear();
    for (int c = 0; c < 3; ++c) {
      const int v = triangulation.triangles()(t, c);
      const int available = (v == i || placed[static_cast<size_t>(v)]) ? n : 0;
      for (int b = 0; b <= available; ++b) {
        points.emplace_back(knots.row(v * (n + 1) + b).transpose());
        corner_of.push_back(v == i && b > 0 ? 1 : 0);
        index_of.push_back(c * (n + 1) + b);
      }
    }
    const size_t count = points.size();
    for (size_t a = 0; a < count; ++a) {
      for (size_t b = a + 1; b < count; ++b) {
        for (size_t c = b + 1; c < count; ++c) {
          if (corner_of[a] + corner_of[b] + corner_of[c] == 0) {
            continue;
          }
          const double area = relative_area(points[a], points[b], points[c]);
          // A knot triangle of condition 2 takes one knot of each corner in corner order.
          const bool dms =
              index_of[a] / (n + 1) == 0 && index_of[b] / (n + 1) == 1 &&
              index_of[c] / (n + 1) == 2 &&
              index_of[a] % (n + 1) + index_of[b] % (n + 1) + index_of[c] % (n + 1) <= n;
          if (dms && area <= 0.0) {
            return -1.0;
          }
          quality = std::min(quality, std::abs(area));
        }
      }
    }
  }
  return quality;
}

}  // namespace

TriangularKnotClouds::TriangularKnotClouds(const Triangulation& triangulation, int degree,
                                           Eigen::MatrixX2d knots)
    : degree_(degree), knots_(std::move(knots)) {
  if (degree < 1 || degree > kMaxTriangularDegree) {
    throw make_error("triangular B-spline degree ", degree, " is outside 1..",
                     kMaxTriangularDegree);
  }
  if (knots_.rows() != static_cast<Eigen::Index>(triangulation.vertex_count()) * (degree + 1)) {
    throw make_error("knot clouds have ", knots_.rows(), " knots; ", triangulation.vertex_count(),
                     " vertices of degree ", degree, " need ",
                     triangulation.vertex_count() * (degree + 1));
  }
  for (int i = 0; i < triangulation.vertex_count(); ++i) {
    for (int b = 0; b <= degree; ++b) {
      if (!knots_.row(i * (degree + 1) + b).allFinite()) {
        throw make_error("knot t[", i, "][", b, "] is not finite");
      }
    }
    if (knot(i, 0) != triangulation.vertex(i)) {
      throw make_error("knot t[", i, "][0] = (", knot(i, 0).x(), ", ", knot(i, 0).y(),
                       ") must be vertex ", i, " (", triangulation.vertex(i).x(), ", ",
                       triangulation.vertex(i).y(), ")");
    }
  }
}

TriangularKnotClouds standard_knot_clouds(const Triangulation& triangulation, int degree,
                                          const KnotCloudSettings& settings) {
  if (degree < 1 || degree > kMaxTriangularDegree) {
    throw make_error("triangular B-spline degree ", degree, " is outside 1..",
                     kMaxTriangularDegree);
  }
  if (!(settings.radius > 0.0 && settings.radius < 0.5)) {
    throw make_error("knot cloud radius ", settings.radius, " is outside (0, 0.5)");
  }
  if (settings.candidates < 1 || settings.candidates > 1000) {
    throw make_error("knot cloud candidates ", settings.candidates, " is outside 1..1000");
  }
  const int n = degree;
  const double two_pi = 2.0 * std::numbers::pi;
  const double golden = std::numbers::phi - 1.0;
  Eigen::MatrixX2d knots(triangulation.vertex_count() * (n + 1), 2);
  std::vector<bool> placed(static_cast<size_t>(triangulation.vertex_count()), false);
  for (int i = 0; i < triangulation.vertex_count(); ++i) {
    const Eigen::Vector2d v = triangulation.vertex(i);
    for (int b = 0; b <= n; ++b) {
      knots.row(i * (n + 1) + b) = v.transpose();
    }
  }
  for (int i = 0; i < triangulation.vertex_count(); ++i) {
    const Eigen::Vector2d v = triangulation.vertex(i);
    // Local size: the smallest height at vertex i of its triangles.
    double size = std::numeric_limits<double>::infinity();
    for (const int t : triangulation.vertex_triangles(i)) {
      const int c =
          triangulation.triangles()(t, 0) == i ? 0 : (triangulation.triangles()(t, 1) == i ? 1 : 2);
      const Eigen::Vector2d p = triangulation.corner(t, (c + 1) % 3);
      const Eigen::Vector2d q = triangulation.corner(t, (c + 2) % 3);
      size = std::min(size, signed_double_area(v, p, q) / (q - p).norm());
    }
    // Allowed angles: the full circle, or the wedge outside both boundary edges at i.
    double start = 0.0;
    double width = two_pi;
    double margin = 0.0;
    if (triangulation.is_boundary_vertex(i)) {
      const Eigen::Vector2d next = triangulation.vertex(triangulation.boundary_next(i)) - v;
      const Eigen::Vector2d previous = triangulation.vertex(triangulation.boundary_previous(i)) - v;
      const double theta_next = std::atan2(next.y(), next.x());
      const double interior =
          std::fmod(std::atan2(previous.y(), previous.x()) - theta_next + 2.0 * two_pi, two_pi);
      start = theta_next + std::max(interior, std::numbers::pi);
      width = std::min(two_pi, std::numbers::pi + interior) - std::max(interior, std::numbers::pi);
      margin = 0.15;
    }
    double best_quality = -2.0;
    Eigen::MatrixX2d best(n, 2);
    for (int candidate = 0; candidate < settings.candidates; ++candidate) {
      const double offset = static_cast<double>(candidate) / settings.candidates;
      for (int b = 1; b <= n; ++b) {
        const double fraction = std::fmod(offset + b * golden, 1.0);
        const double angle = start + width * (margin + (1.0 - 2.0 * margin) * fraction);
        const double radius = settings.radius * size * (0.5 + 0.5 * b / n);
        knots.row(i * (n + 1) + b) =
            (v + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle))).transpose();
      }
      const double quality = placement_quality(triangulation, knots, placed, n, i);
      if (quality > best_quality) {
        best_quality = quality;
        best = knots.block(i * (n + 1) + 1, 0, n, 2);
      }
    }
    knots.block(i * (n + 1) + 1, 0, n, 2) = best;
    placed[static_cast<size_t>(i)] = true;
  }
  TriangularKnotClouds clouds(triangulation, degree, std::move(knots));
  check_knot_clouds(triangulation, clouds);
  return clouds;
}

void check_knot_clouds(const Triangulation& triangulation, const TriangularKnotClouds& clouds) {
  if (clouds.vertex_count() != triangulation.vertex_count()) {
    throw make_error("knot clouds for ", clouds.vertex_count(),
                     " vertices used with a triangulation of ", triangulation.vertex_count(),
                     " vertices");
  }
  const int n = clouds.degree();
  for (int i = 0; i < triangulation.vertex_count(); ++i) {
    if (clouds.knot(i, 0) != triangulation.vertex(i)) {
      throw make_error("knot t[", i, "][0] is not vertex ", i);
    }
  }
  // Condition 4: the knots of boundary edges lie strictly outside across the edge.
  const Eigen::MatrixX2i boundary = triangulation.boundary_edges();
  for (Eigen::Index e = 0; e < boundary.rows(); ++e) {
    const Eigen::Vector2d p = triangulation.vertex(boundary(e, 0));
    const Eigen::Vector2d q = triangulation.vertex(boundary(e, 1));
    for (int end = 0; end < 2; ++end) {
      const int v = boundary(e, end);
      for (int b = 1; b <= n; ++b) {
        const double side = signed_double_area(p, q, clouds.knot(v, b)) / (q - p).squaredNorm();
        if (side >= -TriangularKnotClouds::kGeneralPosition) {
          throw make_error("knot t[", v, "][", b,
                           "] lies inside the domain across the boundary edge (", boundary(e, 0),
                           ", ", boundary(e, 1), ") (relative signed distance ", side,
                           "): knots of boundary vertices must lie outside every boundary edge at "
                           "the vertex, or the B-splines do not sum to one near the boundary");
        }
      }
    }
  }
  for (int t = 0; t < triangulation.triangle_count(); ++t) {
    check_triangle(triangulation, clouds, t);
  }
}

}  // namespace dnurbs
