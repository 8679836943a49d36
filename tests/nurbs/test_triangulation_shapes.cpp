// Tests of nurbs/triangulation_shapes.h: grids, an L-shape, a square with a hole and uniform
// refinement, checked by counts, areas and boundary loops.

#include "dnurbs/nurbs/triangulation_shapes.h"

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// Sum over the boundary edges of (x_a y_b - y_a x_b) / 2: the enclosed area (holes subtract).
double boundary_area(const Triangulation& triangulation) {
  const Eigen::MatrixX2i edges = triangulation.boundary_edges();
  double area = 0.0;
  for (Eigen::Index k = 0; k < edges.rows(); ++k) {
    const Eigen::Vector2d p = triangulation.vertex(edges(k, 0));
    const Eigen::Vector2d q = triangulation.vertex(edges(k, 1));
    area += 0.5 * (p.x() * q.y() - p.y() * q.x());
  }
  return area;
}

TEST(TriangulationShapes, GridsLShapeAndHoleHaveTheirAreasAndCounts) {
  const Triangulation grid = rectangle_triangulation(Eigen::Vector2d(-1, 0), Eigen::Vector2d(2, 1),
                                                     6, 2, DiagonalPattern::kUniform);
  EXPECT_EQ(grid.vertex_count(), 21);
  EXPECT_EQ(grid.triangle_count(), 24);
  EXPECT_NEAR(grid.domain_area(), 3.0, 1e-14);
  const Triangulation l_shape = l_shape_triangulation(2);
  EXPECT_EQ(l_shape.triangle_count(), 2 * 12);
  EXPECT_NEAR(l_shape.domain_area(), 3.0, 1e-14);
  EXPECT_NEAR(boundary_area(l_shape), 3.0, 1e-14);
  const Triangulation hole = square_with_hole_triangulation(1);
  EXPECT_EQ(hole.triangle_count(), 16);
  EXPECT_NEAR(hole.domain_area(), 8.0, 1e-14);
  // Outer loop 9 minus the hole 1: the hole's loop runs clockwise.
  EXPECT_NEAR(boundary_area(hole), 8.0, 1e-14);
  EXPECT_EQ(hole.boundary_edges().rows(), 16);  // 12 outer + 4 inner unit edges
  EXPECT_THROW(rectangle_triangulation(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), 0, 2), Error);
  EXPECT_THROW(rectangle_triangulation(Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 1), 2, 2), Error);
}

TEST(TriangulationShapes, RefinementQuadruplesTrianglesAndKeepsTheDomain) {
  const Triangulation coarse = l_shape_triangulation(1);
  const Triangulation fine = refine_triangulation(coarse);
  EXPECT_EQ(fine.triangle_count(), 4 * coarse.triangle_count());
  // Euler: V - E + F = 1 for a disk; each edge adds one midpoint.
  const int edges =
      (3 * coarse.triangle_count() + static_cast<int>(coarse.boundary_edges().rows())) / 2;
  EXPECT_EQ(fine.vertex_count(), coarse.vertex_count() + edges);
  EXPECT_NEAR(fine.domain_area(), coarse.domain_area(), 1e-14);
  EXPECT_EQ(fine.boundary_edges().rows(), 2 * coarse.boundary_edges().rows());
  for (int t = 0; t < fine.triangle_count(); ++t) {
    EXPECT_NEAR(fine.area(t), 0.125, 1e-15);  // unit cells cut in two, then in four
  }
}

}  // namespace
}  // namespace dnurbs
