#include "dnurbs/vision/mesh_topology.h"

#include <string>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

/// The boundary of the unit cube, 12 triangles counter-clockwise from outside.
std::pair<Eigen::MatrixX3d, Eigen::MatrixX3i> unit_cube() {
  Eigen::MatrixX3d v(8, 3);
  for (int i = 0; i < 8; ++i) {
    v.row(i) << (i & 1), ((i >> 1) & 1), ((i >> 2) & 1);
  }
  Eigen::MatrixX3i f(12, 3);
  f << 0, 2, 1, 1, 2, 3,  // z = 0, normal -z
      4, 5, 6, 5, 7, 6,   // z = 1
      0, 1, 4, 1, 5, 4,   // y = 0
      2, 6, 3, 3, 6, 7,   // y = 1
      0, 4, 2, 2, 4, 6,   // x = 0
      1, 3, 5, 3, 7, 5;   // x = 1
  return {v, f};
}

/// An n by m torus of quads split into triangles (periodic both ways).
Eigen::MatrixX3i torus_triangles(int n, int m) {
  Eigen::MatrixX3i f(2 * n * m, 3);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const int a = i * m + j;
      const int b = ((i + 1) % n) * m + j;
      const int c = ((i + 1) % n) * m + (j + 1) % m;
      const int d = i * m + (j + 1) % m;
      const Eigen::Index row = 2 * static_cast<Eigen::Index>(a);
      f.row(row) << a, b, c;
      f.row(row + 1) << a, c, d;
    }
  }
  return f;
}

TEST(MeshTopology, CubeIsAClosedOrientedSphere) {
  const auto [v, f] = unit_cube();
  std::string reason;
  EXPECT_TRUE(is_closed_oriented_manifold(f, 8, &reason)) << reason;
  const MeshTopology t = mesh_topology(f, 8);
  EXPECT_EQ(t.edges, 18);
  EXPECT_EQ(t.euler_characteristic, 2);
  EXPECT_EQ(t.components, 1);
  EXPECT_NEAR(enclosed_volume(v, f), 1.0, 1e-15);
}

TEST(MeshTopology, TorusHasEulerCharacteristicZero) {
  const Eigen::MatrixX3i f = torus_triangles(6, 5);
  EXPECT_TRUE(is_closed_oriented_manifold(f, 30));
  EXPECT_EQ(mesh_topology(f, 30).euler_characteristic, 0);
}

TEST(MeshTopology, DefectsAreFoundAndNamed) {
  const auto [v, f] = unit_cube();
  std::string reason;
  EXPECT_FALSE(is_closed_oriented_manifold(f.topRows(11), 8, &reason));  // a hole
  EXPECT_NE(reason.find("open boundary"), std::string::npos) << reason;
  Eigen::MatrixX3i flipped = f;
  flipped.row(3) = flipped.row(3).reverse().eval();
  EXPECT_FALSE(is_closed_oriented_manifold(flipped, 8, &reason));
  EXPECT_NE(reason.find("used twice"), std::string::npos) << reason;
  // Two cubes sharing only vertex 7 of the first (= vertex 0 of the second): pinched.
  Eigen::MatrixX3i two(24, 3);
  two.topRows(12) = f;
  two.bottomRows(12) = (f.array() + 7).matrix();
  EXPECT_FALSE(is_closed_oriented_manifold(two, 15, &reason));
  EXPECT_NE(reason.find("vertex 7 joins two fans"), std::string::npos) << reason;
  EXPECT_FALSE(is_closed_oriented_manifold(f, 9, &reason));  // vertex 8 unused
  EXPECT_NE(reason.find("vertex 8 is in no triangle"), std::string::npos) << reason;
  EXPECT_THROW(mesh_topology(f, 7), Error);
}

}  // namespace
}  // namespace dnurbs
