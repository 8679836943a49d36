#include "dnurbs/surface/grid.h"

#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/surface/grid_difference_operators.h"
#include "dnurbs/surface/node_chain.h"

namespace dnurbs {
namespace {

TEST(Grid, IndexingParametersAndBorder) {
  const Grid grid(4, 3, 0.5);
  EXPECT_EQ(grid.node_count(), 12);
  EXPECT_EQ(grid.index(3, 2), 11);
  EXPECT_EQ(grid.node(7), std::make_pair(3, 1));
  EXPECT_EQ(grid.parameter(7), Eigen::Vector2d(1.5, 0.5));
  EXPECT_EQ(grid.border_nodes().size(), 10u);  // all but (1, 1) and (2, 1)
  EXPECT_FALSE(grid.on_border(2, 1));
}

TEST(Grid, BilinearWeightsInterpolateAndAreExactAtNodes) {
  const Grid grid(4, 3, 0.5);
  const NodePositions r = flat_grid_positions(grid, Eigen::Vector3d(1, 2, 3),
                                              Eigen::Vector3d(1, 0, 1), Eigen::Vector3d(0, 2, 0));
  // A flat grid is affine in (u, v): bilinear interpolation reproduces it (round-off only).
  const Eigen::Vector2d u(0.8, 0.3);
  EXPECT_LE((interpolate_grid(grid, r, u) - Eigen::Vector3d(1.8, 2.6, 3.8)).norm(), 1e-14);
  const auto weights = grid.bilinear_weights(grid.parameter(2, 1));
  double at_node = 0.0;
  for (const auto& [node, weight] : weights) {
    if (node == grid.index(2, 1)) {
      at_node = weight;
    }
  }
  EXPECT_EQ(at_node, 1.0);
  // Every node parameter i h of a spacing that is not a power of 2 hits its node exactly.
  const Grid twelfths(13, 13, 1.0 / 12);
  for (int k = 0; k < twelfths.node_count(); ++k) {
    bool exact = false;
    for (const auto& [node, weight] : twelfths.bilinear_weights(twelfths.parameter(k))) {
      exact = exact || (node == k && weight == 1.0);
    }
    EXPECT_TRUE(exact) << "node " << k;
  }
  // The far corner belongs to the last cell.
  const Eigen::Vector3d corner = interpolate_grid(grid, r, grid.parameter(3, 2));
  EXPECT_LE((corner - r.row(grid.index(3, 2)).transpose()).norm(), 1e-15);
}

TEST(GridDifferenceOperators, ExactOnQuadratics) {
  // Forward differences are exact for linear fields and central second differences for
  // quadratics; on f = u^2 + 3 u v - v^2 the results are exact up to round-off (1e-11 for
  // divisions by h^2 = 1/64 of values ~1).
  const Grid grid(6, 5, 0.125);
  const GridDifferenceOperators d = grid_difference_operators(grid);
  Eigen::VectorXd f(grid.node_count());
  for (int k = 0; k < grid.node_count(); ++k) {
    const Eigen::Vector2d p = grid.parameter(k);
    f[k] = p.x() * p.x() + 3 * p.x() * p.y() - p.y() * p.y();
  }
  const Eigen::VectorXd f11 = d.d11 * f;
  const Eigen::VectorXd f22 = d.d22 * f;
  const Eigen::VectorXd f12 = d.d12 * f;
  const Eigen::VectorXd f1 = d.d1 * f;
  for (int k = 0; k < grid.node_count(); ++k) {
    const auto [i, j] = grid.node(k);
    const Eigen::Vector2d p = grid.parameter(k);
    EXPECT_NEAR(f11[k], i > 0 && i < 5 ? 2.0 : 0.0, 1e-11);
    EXPECT_NEAR(f22[k], j > 0 && j < 4 ? -2.0 : 0.0, 1e-11);
    EXPECT_NEAR(f12[k], i < 5 && j < 4 ? 3.0 : 0.0, 1e-11);
    // Forward difference of u^2 + 3uv: 2u + h + 3v (exact); zero row on the last column.
    EXPECT_NEAR(f1[k], i < 5 ? 2 * p.x() + 0.125 + 3 * p.y() : 0.0, 1e-12);
  }
  EXPECT_THROW(grid_difference_operators(Grid(2, 5, 0.1)), Error);
}

TEST(Grid, TriangleMeshOfAFlatSheet) {
  const Grid grid(3, 4, 1.0);
  const TriangleMesh mesh =
      grid_triangle_mesh(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()));
  EXPECT_EQ(mesh.vertex_count(), 12);
  EXPECT_EQ(mesh.triangle_count(), 12);
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    EXPECT_EQ(mesh.normals.row(v), Eigen::RowVector3d(0, 0, 1));
  }
  const Eigen::Vector3i t = mesh.triangles.row(0);
  const Eigen::Vector3d a = mesh.vertices.row(t[0]);
  const Eigen::Vector3d b = mesh.vertices.row(t[1]);
  const Eigen::Vector3d c = mesh.vertices.row(t[2]);
  EXPECT_GT((b - a).cross(c - a).z(), 0.0);
}

TEST(Grid, BadInputNamesTheValue) {
  const auto message = [](auto&& make) -> std::string {
    try {
      make();
    } catch (const Error& error) {
      return error.what();
    }
    return "no error";
  };
  EXPECT_NE(message([] { Grid(1, 4, 0.1); }).find("1 by 4"), std::string::npos);
  EXPECT_NE(message([] { Grid(4, 4, -0.5); }).find("-0.5"), std::string::npos);
  EXPECT_NE(message([] { Grid(4, 4, std::nan("")); }).find("nan"), std::string::npos);
  const Grid grid(3, 3, 1.0);
  NodePositions bad = flat_grid_positions(grid, Eigen::Vector3d::Zero());
  bad(4, 2) = std::numeric_limits<double>::infinity();
  EXPECT_NE(message([&] { grid_triangle_mesh(grid, bad); }).find("(1, 1)"), std::string::npos);
}

TEST(NodeChain, NeighborsAndInterpolation) {
  const NodeChain open(5, false);
  EXPECT_DOUBLE_EQ(open.spacing(), 0.25);
  EXPECT_EQ(open.neighbor(4, 1), -1);
  EXPECT_EQ(open.neighbor(0, -1), -1);
  const NodeChain closed(5, true);
  EXPECT_DOUBLE_EQ(closed.spacing(), 0.2);
  EXPECT_EQ(closed.neighbor(4, 1), 0);
  EXPECT_EQ(closed.neighbor(0, -2), 3);
  const auto w = closed.linear_weights(0.9);  // between node 4 (s = 0.8) and node 0 (s = 1)
  EXPECT_EQ(w[0].first, 4);
  EXPECT_EQ(w[1].first, 0);
  EXPECT_NEAR(w[1].second, 0.5, 1e-12);
  const auto end = open.linear_weights(1.0);
  EXPECT_EQ(end[1].first, 4);
  EXPECT_DOUBLE_EQ(end[1].second, 1.0);
  EXPECT_THROW(NodeChain(2, false), Error);
}

}  // namespace
}  // namespace dnurbs
