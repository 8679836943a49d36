#include "dnurbs/vision/tetrahedral_decomposition.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "dnurbs/vision/mesh_topology.h"

namespace dnurbs {
namespace {

/// Marching tetrahedra of the vertices inside a sphere, nodes where the distance is linear 0.
TriangleMesh sphere_mesh(const TetrahedralGrid& grid, const Eigen::Vector3d& center, double radius,
                         std::vector<char>* inside_out) {
  std::vector<char> inside(static_cast<std::size_t>(grid.vertex_count()), 0);
  const auto level = [&](const Eigen::Vector3i& g) {
    return (grid.vertex_position(g) - center).norm() - radius;
  };
  const Eigen::Vector3i n = grid.cells();
  for (int k = 0; k <= n.z(); ++k) {
    for (int j = 0; j <= n.y(); ++j) {
      for (int i = 0; i <= n.x(); ++i) {
        const Eigen::Vector3i g(i, j, k);
        inside[static_cast<std::size_t>(grid.vertex_index(g))] =
            (level(g) < 0.0 && !grid.on_border(g)) ? 1 : 0;
      }
    }
  }
  *inside_out = inside;
  return boundary_mesh(grid, inside, [&](int family, const Eigen::Vector3i& first, bool) {
    const double a = level(first);
    const double b = level(first + TetrahedralGrid::direction(family));
    return std::clamp(a / (a - b), kAcidEdgeMargin, 1.0 - kAcidEdgeMargin);
  });
}

TEST(MarchingTetrahedra, OneInsideVertexGivesA24TriangleSphere) {
  const TetrahedralGrid grid(Eigen::Vector3d::Zero(), 1.0, Eigen::Vector3i(4, 4, 4));
  std::vector<char> inside(static_cast<std::size_t>(grid.vertex_count()), 0);
  inside[static_cast<std::size_t>(grid.vertex_index(Eigen::Vector3i(2, 2, 2)))] = 1;
  const TriangleMesh mesh =
      boundary_mesh(grid, inside, [](int, const Eigen::Vector3i&, bool) { return 0.5; });
  // A Kuhn vertex has 14 edges and 24 tetrahedra: 14 nodes, 24 triangles, chi = 14 - 36 + 24.
  EXPECT_EQ(mesh.vertex_count(), 14);
  EXPECT_EQ(mesh.triangle_count(), 24);
  std::string reason;
  EXPECT_TRUE(is_closed_oriented_manifold(mesh.triangles, mesh.vertex_count(), &reason)) << reason;
  EXPECT_EQ(mesh_topology(mesh.triangles, mesh.vertex_count()).euler_characteristic, 2);
  // The midpoint polytope around a vertex of the 6-tetrahedra split: each of the 24 tetrahedra
  // (volume 1/6) contributes the corner (1/2)^3 of it, 1/48: total 1/2.
  EXPECT_NEAR(enclosed_volume(mesh.vertices, mesh.triangles), 0.5, 1e-14);
}

TEST(TetrahedralReparameterization, ClassifiesTheSphereAndIsIdempotent) {
  const TetrahedralGrid grid(Eigen::Vector3d(-0.5, -0.5, -0.5), 1.0, Eigen::Vector3i(14, 14, 14));
  std::vector<char> inside;
  const TriangleMesh mesh = sphere_mesh(grid, Eigen::Vector3d(6.6, 6.3, 6.7), 4.6, &inside);
  std::string reason;
  ASSERT_TRUE(is_closed_oriented_manifold(mesh.triangles, mesh.vertex_count(), &reason)) << reason;
  EXPECT_GT(enclosed_volume(mesh.vertices, mesh.triangles), 0.0);
  // Phase I on the mesh recovers the same inside set, and phase II the same mesh: the winding
  // count is exact although every mesh vertex lies on a grid line.
  const TetrahedralCrossings crossings(grid, mesh);
  EXPECT_EQ(inside_vertices(grid, crossings), inside);
  const TriangleMesh again =
      boundary_mesh(grid, inside, [&](int family, const Eigen::Vector3i& first, bool in) {
        return crossing_fraction(crossings, family, first, in);
      });
  ASSERT_EQ(again.vertex_count(), mesh.vertex_count());
  ASSERT_EQ(again.triangle_count(), mesh.triangle_count());
  EXPECT_EQ(again.triangles, mesh.triangles);
  EXPECT_LT((again.vertices - mesh.vertices).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(TetrahedralReparameterization, AxisAlignedBoxWithVerticesOnGridLinesWindsOnce) {
  // A box whose corners and edges lie exactly on grid lines: lines through its edges and corners
  // must be counted once (top-left rule), so strictly interior vertices are inside and the rest
  // outside.
  const TetrahedralGrid grid(Eigen::Vector3d::Zero(), 1.0, Eigen::Vector3i(8, 8, 8));
  TriangleMesh box;
  box.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) {
    box.vertices.row(i) << (2 + 3 * (i & 1)), (2 + 3 * ((i >> 1) & 1)), (2 + 3 * ((i >> 2) & 1));
  }
  box.triangles.resize(12, 3);
  box.triangles << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2,
      2, 4, 6, 1, 3, 5, 3, 7, 5;
  const std::vector<char> inside = inside_vertices(grid, TetrahedralCrossings(grid, box));
  for (int k = 0; k <= 8; ++k) {
    for (int j = 0; j <= 8; ++j) {
      for (int i = 0; i <= 8; ++i) {
        const Eigen::Vector3i g(i, j, k);
        const bool strictly_inside = g.minCoeff() > 2 && g.maxCoeff() < 5;
        const bool strictly_outside = g.minCoeff() < 2 || g.maxCoeff() > 5;
        const bool flag = inside[static_cast<std::size_t>(grid.vertex_index(g))] != 0;
        if (strictly_inside) {
          EXPECT_TRUE(flag) << i << " " << j << " " << k;
        }
        if (strictly_outside) {
          EXPECT_FALSE(flag) << i << " " << j << " " << k;
        }
      }
    }
  }
}

}  // namespace
}  // namespace dnurbs
