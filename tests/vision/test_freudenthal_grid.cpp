#include "dnurbs/vision/freudenthal_grid.h"

#include <map>
#include <string>

#include <gtest/gtest.h>

#include "../common/error_message.h"

namespace dnurbs {
namespace {

using testing::error_message;

TEST(FreudenthalGrid, TrianglesAreCounterClockwiseAndEveryInteriorEdgeHasTwo) {
  const FreudenthalGrid grid(Eigen::Vector2d(1.0, -2.0), 0.5, 4, 3);
  std::map<int, int> triangles_per_edge;
  double total_area = 0.0;
  for (int j = 0; j < grid.cells_y(); ++j) {
    for (int i = 0; i < grid.cells_x(); ++i) {
      for (const auto& t : grid.cell_triangles(i, j)) {
        const Eigen::Vector2d a = grid.vertex_position(t[0].x(), t[0].y());
        const Eigen::Vector2d b = grid.vertex_position(t[1].x(), t[1].y());
        const Eigen::Vector2d c = grid.vertex_position(t[2].x(), t[2].y());
        const Eigen::Vector2d ab = b - a;
        const Eigen::Vector2d ac = c - a;
        const double area = 0.5 * (ab.x() * ac.y() - ab.y() * ac.x());
        EXPECT_DOUBLE_EQ(area, 0.125);  // half a 0.5 by 0.5 cell, counter-clockwise
        total_area += area;
        for (int k = 0; k < 3; ++k) {
          ++triangles_per_edge[grid.edge_between(t[static_cast<std::size_t>(k)],
                                                 t[static_cast<std::size_t>((k + 1) % 3)])];
        }
      }
    }
  }
  EXPECT_DOUBLE_EQ(total_area, 4 * 3 * 0.25);
  // Edges: 4*4 horizontal + 5*3 vertical + 4*3 diagonal; boundary ones (2*4 + 2*3) have one
  // triangle, the rest two.
  EXPECT_EQ(triangles_per_edge.size(), 16U + 15U + 12U);
  int boundary = 0;
  for (const auto& [edge, count] : triangles_per_edge) {
    EXPECT_TRUE(count == 1 || count == 2);
    boundary += count == 1 ? 1 : 0;
  }
  EXPECT_EQ(boundary, 14);
  EXPECT_EQ(grid.edge_between({2, 1}, {3, 2}), grid.edge_id(FreudenthalGrid::kDiagonal, 2, 1));
  EXPECT_EQ(grid.edge_between({3, 2}, {2, 2}), grid.edge_id(FreudenthalGrid::kHorizontal, 2, 2));
}

TEST(FreudenthalGrid, BadSizesAreNamed) {
  EXPECT_NE(error_message([] {
              FreudenthalGrid(Eigen::Vector2d::Zero(), -1.0, 4, 4);
            }).find("cell size -1"),
            std::string::npos);
  EXPECT_NE(
      error_message([] { FreudenthalGrid(Eigen::Vector2d::Zero(), 1.0, 1, 4); }).find("1 by 4"),
      std::string::npos);
  EXPECT_NE(
      error_message([] { FreudenthalGrid(Eigen::Vector2d(NAN, 0.0), 1.0, 4, 4); }).find("origin"),
      std::string::npos);
}

}  // namespace
}  // namespace dnurbs
