#include "dnurbs/vision/affine_cell_decomposition.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace dnurbs {
namespace {

Contour circle(const Eigen::Vector2d& center, double radius, int nodes) {
  Contour contour(nodes, 2);
  for (int k = 0; k < nodes; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / nodes;
    contour.row(k) =
        (center + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle))).transpose();
  }
  return contour;
}

TEST(AcidPhaseTwo, OneInsideVertexGivesTheHexagonOfEdgeMidpoints) {
  const FreudenthalGrid grid(Eigen::Vector2d::Zero(), 2.0, 4, 4);
  std::vector<char> inside(static_cast<std::size_t>(grid.vertex_count()), 0);
  inside[static_cast<std::size_t>(grid.vertex_index(2, 2))] = 1;
  const std::vector<Contour> contours = boundary_contours(grid, inside, grid_crossings(grid, {}));
  ASSERT_EQ(contours.size(), 1U);
  EXPECT_EQ(contours[0].rows(), 6);  // a Freudenthal vertex has 6 edges
  // The nodes at the 6 edge midpoints (no crossings) enclose 3/4 of a cell: 3 in grid units of 2.
  EXPECT_DOUBLE_EQ(signed_area(contours[0]), 0.75 * 4.0);
}

TEST(AcidPhaseTwo, BorderVerticesStayOutside) {
  const FreudenthalGrid grid(Eigen::Vector2d::Zero(), 1.0, 3, 3);
  const std::vector<char> all(static_cast<std::size_t>(grid.vertex_count()), 1);
  const std::vector<Contour> contours = boundary_contours(grid, all, grid_crossings(grid, {}));
  ASSERT_EQ(contours.size(), 1U);  // only the 2 by 2 interior vertices: one square-ish region
  EXPECT_GT(signed_area(contours[0]), 0.0);
}

TEST(AcidReparameterization, NodesLieOnGridEdgesAndOnTheContour) {
  const FreudenthalGrid grid(Eigen::Vector2d(0.0, 0.0), 1.0, 20, 20);
  const Eigen::Vector2d center(10.2, 9.7);
  const Contour polygon = circle(center, 6.3, 400);
  const GridCrossings crossings = grid_crossings(grid, {polygon});
  const std::vector<char> inside = inside_vertices(grid, crossings);
  // Inside flags are the vertices within the polygon (the 400-gon is within 2e-4 of the circle).
  for (int j = 0; j <= 20; ++j) {
    for (int i = 0; i <= 20; ++i) {
      const double r = (Eigen::Vector2d(i, j) - center).norm();
      if (std::abs(r - 6.3) > 1e-3) {
        EXPECT_EQ(inside[static_cast<std::size_t>(grid.vertex_index(i, j))] != 0, r < 6.3)
            << i << ", " << j;
      }
    }
  }
  const std::vector<Contour> contours = boundary_contours(grid, inside, crossings);
  ASSERT_EQ(contours.size(), 1U);
  for (Eigen::Index k = 0; k < contours[0].rows(); ++k) {
    const Eigen::Vector2d node = contours[0].row(k);
    // On a grid line of one of the three families (to rounding) ...
    const bool on_line = std::abs(node.x() - std::round(node.x())) < 1e-12 ||
                         std::abs(node.y() - std::round(node.y())) < 1e-12 ||
                         std::abs((node.x() - node.y()) - std::round(node.x() - node.y())) < 1e-12;
    EXPECT_TRUE(on_line);
    // ... and on the 400-gon, which is within 1 - cos(pi / 400) R = 2e-4 of the circle.
    EXPECT_NEAR((node - center).norm(), 6.3, 2e-4);
  }
  EXPECT_FALSE(contours_intersect(contours));
  // Reparameterizing the new contour changes nothing: the same inside set, the same nodes.
  const GridCrossings again = grid_crossings(grid, contours);
  EXPECT_EQ(inside_vertices(grid, again), inside);
  const std::vector<Contour> same = boundary_contours(grid, inside, again);
  ASSERT_EQ(same.size(), 1U);
  ASSERT_EQ(same[0].rows(), contours[0].rows());
  EXPECT_LT((same[0] - contours[0]).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(AcidReparameterization, OverlapMergesAndFoldsSplit) {
  const FreudenthalGrid grid(Eigen::Vector2d::Zero(), 1.0, 30, 20);
  // Two overlapping counter-clockwise circles: winding 2 in the overlap, one merged region.
  const std::vector<Contour> overlapping{circle({10.0, 10.0}, 5.0, 100),
                                         circle({17.0, 10.0}, 5.0, 100)};
  const GridCrossings crossings = grid_crossings(grid, overlapping);
  const std::vector<Contour> merged =
      boundary_contours(grid, inside_vertices(grid, crossings), crossings);
  EXPECT_EQ(merged.size(), 1U);
  // A counter-clockwise rectangle whose bottom edge has been pushed up through its top in the
  // middle splits into two regions.
  Contour folded(8, 2);
  folded << 2.5, 5.5, 12.5, 5.5, 12.5, 14.5, 17.5, 14.5, 17.5, 5.5, 27.5, 5.5, 27.5, 14.5, 2.5,
      14.5;
  // Nodes 1..4 run up to the top and back down: the band 12.5 < x < 17.5 is wound 0 times (the
  // crossings at x = 17.5 and 27.5 cancel), so it is outside.
  const GridCrossings fold_crossings = grid_crossings(grid, {folded});
  const std::vector<Contour> split =
      boundary_contours(grid, inside_vertices(grid, fold_crossings), fold_crossings);
  EXPECT_EQ(split.size(), 2U);
  for (const Contour& part : split) {
    EXPECT_GT(signed_area(part), 0.0);
  }
}

TEST(AcidReparameterization, HoleIsClockwise) {
  const FreudenthalGrid grid(Eigen::Vector2d::Zero(), 1.0, 30, 30);
  const std::vector<Contour> ring{circle({15.0, 15.0}, 10.0, 200),
                                  circle({15.0, 15.0}, 5.0, 200).colwise().reverse()};
  const GridCrossings crossings = grid_crossings(grid, ring);
  const std::vector<Contour> contours =
      boundary_contours(grid, inside_vertices(grid, crossings), crossings);
  ASSERT_EQ(contours.size(), 2U);
  const double a0 = signed_area(contours[0]);
  const double a1 = signed_area(contours[1]);
  // Nodes on the 200-gons: areas within ~perimeter * 1 cell^2 / (12 R) of pi R^2.
  EXPECT_NEAR(std::max(a0, a1), std::numbers::pi * 100.0, 3.0);
  EXPECT_NEAR(std::min(a0, a1), -std::numbers::pi * 25.0, 3.0);
}

}  // namespace
}  // namespace dnurbs
