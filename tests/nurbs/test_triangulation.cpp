// Tests of nurbs/triangulation.h: validation (orientation, degeneracy, conformity, simple
// boundary), connectivity (edge neighbours, counter-clockwise fans, boundary loops) and point
// location with the half-open convention.

#include "dnurbs/nurbs/triangulation.h"

#include <set>

#include <gtest/gtest.h>

#include "../common/error_message.h"
#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/triangulation_shapes.h"

namespace dnurbs {
namespace {

using testing::error_message;

// The unit square as two triangles (0, 1, 2), (0, 2, 3).
Triangulation two_triangles() {
  Eigen::MatrixX2d vertices(4, 2);
  vertices << 0, 0, 1, 0, 1, 1, 0, 1;
  Eigen::MatrixX3i triangles(2, 3);
  triangles << 0, 1, 2, 0, 2, 3;
  return {vertices, triangles};
}

TEST(TriangulationValidation, RejectsClockwiseDegenerateAndMalformedTriangles) {
  Eigen::MatrixX2d vertices(4, 2);
  vertices << 0, 0, 1, 0, 1, 1, 0, 1;
  Eigen::MatrixX3i clockwise(1, 3);
  clockwise << 0, 2, 1;
  EXPECT_NE(error_message([&] { Triangulation(vertices, clockwise); }).find("clockwise"),
            std::string::npos);
  Eigen::MatrixX2d collinear(3, 2);
  collinear << 0, 0, 1, 0, 2, 0;
  Eigen::MatrixX3i one(1, 3);
  one << 0, 1, 2;
  EXPECT_NE(error_message([&] { Triangulation(collinear, one); }).find("degenerate"),
            std::string::npos);
  Eigen::MatrixX3i out_of_range(1, 3);
  out_of_range << 0, 1, 7;
  EXPECT_NE(error_message([&] { Triangulation(vertices, out_of_range); }).find("vertex 7"),
            std::string::npos);
  Eigen::MatrixX2d not_finite = vertices;
  not_finite(2, 1) = std::nan("");
  EXPECT_NE(error_message([&] { Triangulation(not_finite, one); }).find("not finite"),
            std::string::npos);
  // Vertex 3 unused.
  EXPECT_NE(error_message([&] { Triangulation(vertices, one); }).find("used by no triangle"),
            std::string::npos);
}

TEST(TriangulationValidation, RejectsOverlapsTJunctionsAndPinchedBoundaries) {
  // A triangle listed twice shares its directed edges with itself.
  Eigen::MatrixX2d square(4, 2);
  square << 0, 0, 1, 0, 1, 1, 0, 1;
  Eigen::MatrixX3i twice(3, 3);
  twice << 0, 1, 2, 0, 2, 3, 0, 1, 2;
  EXPECT_NE(error_message([&] { Triangulation(square, twice); }).find("same direction"),
            std::string::npos);
  // Two triangles covering part of the same area: their edges cross.
  Eigen::MatrixX3i overlapping(3, 3);
  overlapping << 0, 1, 2, 0, 2, 3, 0, 1, 3;
  EXPECT_NE(error_message([&] { Triangulation(square, overlapping); }).find("overlap"),
            std::string::npos);
  // A T-junction: vertex 4 on the edge (0, 2) of triangle (0, 1, 2).
  Eigen::MatrixX2d t_vertices(5, 2);
  t_vertices << 0, 0, 1, 0, 1, 1, 0, 1, 0.5, 0.5;
  Eigen::MatrixX3i t_triangles(3, 3);
  t_triangles << 0, 1, 2, 0, 4, 3, 4, 2, 3;
  EXPECT_NE(error_message([&] { Triangulation(t_vertices, t_triangles); }).find("not conforming"),
            std::string::npos);
  // Crossing edges without a vertex inside: two triangles forming a star.
  Eigen::MatrixX2d star(6, 2);
  star << 0, 0, 2, 0, 1, 1.5, 0, 1, 2, 1, 1, -0.5;
  Eigen::MatrixX3i star_triangles(2, 3);
  star_triangles << 0, 1, 2, 3, 5, 4;
  EXPECT_NE(error_message([&] { Triangulation(star, star_triangles); }).find("overlap"),
            std::string::npos);
  // Two squares touching at one corner: the shared vertex has two boundary edges out.
  EXPECT_NE(error_message([&] {
              grid_cells_triangulation(Eigen::Vector2d(0, 0), Eigen::Vector2d(2, 2), 2, 2,
                                       [](int i, int j) { return i == j; });
            }).find("boundary vertex"),
            std::string::npos);
}

TEST(TriangulationConnectivity, NeighboursFansAndBoundaryOfAGrid) {
  const Triangulation grid = rectangle_triangulation(Eigen::Vector2d(0, 0), Eigen::Vector2d(3, 2),
                                                     3, 2, DiagonalPattern::kAlternating);
  EXPECT_EQ(grid.vertex_count(), 12);
  EXPECT_EQ(grid.triangle_count(), 12);
  EXPECT_NEAR(grid.domain_area(), 6.0, 1e-15);
  // Neighbours are mutual and share the edge opposite the corner.
  for (int t = 0; t < grid.triangle_count(); ++t) {
    for (int e = 0; e < 3; ++e) {
      const int s = grid.neighbor(t, e);
      if (s < 0) {
        continue;
      }
      const int a = grid.triangles()(t, (e + 1) % 3);
      const int b = grid.triangles()(t, (e + 2) % 3);
      bool back = false;
      for (int f = 0; f < 3; ++f) {
        back = back || (grid.neighbor(s, f) == t && grid.triangles()(s, (f + 1) % 3) == b &&
                        grid.triangles()(s, (f + 2) % 3) == a);
      }
      EXPECT_TRUE(back) << "triangle " << t << " edge " << e;
    }
  }
  // Boundary: one loop of 10 edges, the domain on the left (perimeter 10 of unit edges).
  const Eigen::MatrixX2i boundary = grid.boundary_edges();
  EXPECT_EQ(boundary.rows(), 10);
  double signed_area = 0.0;
  for (Eigen::Index k = 0; k < boundary.rows(); ++k) {
    const Eigen::Vector2d p = grid.vertex(boundary(k, 0));
    const Eigen::Vector2d q = grid.vertex(boundary(k, 1));
    signed_area += 0.5 * (p.x() * q.y() - p.y() * q.x());
  }
  EXPECT_NEAR(signed_area, 6.0, 1e-14);  // counter-clockwise outer loop encloses the area
  // Fans are counter-clockwise and consecutive triangles share an edge through the vertex.
  for (int i = 0; i < grid.vertex_count(); ++i) {
    const auto& fan = grid.vertex_triangles(i);
    for (size_t k = 0; k + 1 < fan.size(); ++k) {
      std::set<int> shared;
      for (int c = 0; c < 3; ++c) {
        for (int d = 0; d < 3; ++d) {
          if (grid.triangles()(fan[k], c) == grid.triangles()(fan[k + 1], d)) {
            shared.insert(grid.triangles()(fan[k], c));
          }
        }
      }
      EXPECT_EQ(shared.size(), 2U) << "vertex " << i;
      EXPECT_TRUE(shared.count(i) == 1);
    }
  }
  // The interior vertex (1, 1) of the alternating pattern has 6 or 8 triangles around it.
  EXPECT_FALSE(grid.is_boundary_vertex(4));
  EXPECT_EQ(grid.boundary_next(4), -1);
}

TEST(TriangulationLocate, HalfOpenConventionPicksExactlyOneTriangleOnSharedEdges) {
  const Triangulation square = two_triangles();
  EXPECT_EQ(square.locate(Eigen::Vector2d(0.7, 0.2)), 0);
  EXPECT_EQ(square.locate(Eigen::Vector2d(0.2, 0.7)), 1);
  // On the diagonal both closures contain the point; the half-open direction (cos 35, sin 35)
  // points below the diagonal (35 < 45 degrees), into triangle 0.
  EXPECT_EQ(square.locate(Eigen::Vector2d(0.5, 0.5)), 0);
  // On the edge x = 0.5 of a column of two cells, the direction (positive x) picks the right
  // cell's triangle.
  const Triangulation column = rectangle_triangulation(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1),
                                                       2, 1, DiagonalPattern::kUniform);
  EXPECT_GT(column.centroid(column.locate(Eigen::Vector2d(0.5, 0.3))).x(), 0.5);
  // The shared vertex (0, 0): u + eps d lies in triangle 0 (below the diagonal, angle 35 < 45).
  EXPECT_EQ(square.locate(Eigen::Vector2d(0.0, 0.0)), 0);
  // On the boundary where u + eps d leaves the domain: the lowest closed triangle.
  EXPECT_EQ(square.locate(Eigen::Vector2d(1.0, 1.0)), 0);
  EXPECT_EQ(square.locate(Eigen::Vector2d(1.5, 0.5)), -1);
  EXPECT_THROW(square.locate(Eigen::Vector2d(std::nan(""), 0.0)), Error);
  // Barycentric coordinates of the located triangle reproduce the point.
  const Eigen::Vector3d l = square.barycentric(0, Eigen::Vector2d(0.7, 0.2));
  EXPECT_NEAR(l.sum(), 1.0, 1e-15);
  const Eigen::Vector2d back =
      l[0] * square.corner(0, 0) + l[1] * square.corner(0, 1) + l[2] * square.corner(0, 2);
  EXPECT_NEAR((back - Eigen::Vector2d(0.7, 0.2)).norm(), 0.0, 1e-15);
}

TEST(TriangulationLocate, EveryPointOfAGridIsFoundInATriangleThatContainsIt) {
  const Triangulation l_shape = l_shape_triangulation(3);
  int outside = 0;
  for (int i = 0; i <= 40; ++i) {
    for (int j = 0; j <= 40; ++j) {
      const Eigen::Vector2d u(0.05 * i, 0.05 * j);
      const int t = l_shape.locate(u);
      const bool in_domain = u.x() <= 1.0 + 1e-12 || u.y() <= 1.0 + 1e-12;
      if (!in_domain) {
        EXPECT_EQ(t, -1) << u.transpose();
        ++outside;
        continue;
      }
      ASSERT_GE(t, 0) << u.transpose();
      // Barycentric coordinates of a containing triangle are >= 0 up to round-off.
      EXPECT_GE(l_shape.barycentric(t, u).minCoeff(), -1e-12) << u.transpose();
    }
  }
  EXPECT_EQ(outside, 20 * 20);  // the notch (1, 2] x (1, 2] sampled at 1.05, 1.1, ..., 2
}

}  // namespace
}  // namespace dnurbs
