#include "dnurbs/vision/tetrahedral_grid.h"

#include <map>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "../common/error_message.h"

namespace dnurbs {
namespace {

using testing::error_message;

TEST(TetrahedralGrid, SixTetrahedraFillTheCubeAndShareFaces) {
  const auto tetrahedra = TetrahedralGrid::cube_tetrahedra(Eigen::Vector3i(0, 0, 0));
  int total_volume_times_6 = 0;
  std::map<std::array<int, 3>, int> faces;  // sorted vertex codes x + 2y + 4z
  for (const auto& t : tetrahedra) {
    const int det = (t[1] - t[0]).dot((t[2] - t[0]).cross(t[3] - t[0]));
    EXPECT_EQ(std::abs(det), 1);  // each has volume 1/6
    total_volume_times_6 += std::abs(det);
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> face{};
      int n = 0;
      for (int k = 0; k < 4; ++k) {
        if (k != skip) {
          const auto& v = t[static_cast<std::size_t>(k)];
          face[static_cast<std::size_t>(n++)] = v.x() + 2 * v.y() + 4 * v.z();
        }
      }
      std::sort(face.begin(), face.end());
      ++faces[face];
    }
    // Every edge of every tetrahedron is a step of one of the 7 families.
    for (int a = 0; a < 4; ++a) {
      for (int b = a + 1; b < 4; ++b) {
        EXPECT_GE(TetrahedralGrid::family_of(t[static_cast<std::size_t>(b)] -
                                             t[static_cast<std::size_t>(a)]),
                  0);
      }
    }
  }
  EXPECT_EQ(total_volume_times_6, 6);  // they tile the unit cube
  // 6 tetrahedra have 24 faces: 12 on the cube's surface (2 per cube face) once, 6 inner twice.
  int outer = 0;
  for (const auto& [face, count] : faces) {
    EXPECT_TRUE(count == 1 || count == 2);
    outer += count == 1 ? 1 : 0;
  }
  EXPECT_EQ(outer, 12);
  EXPECT_EQ(faces.size(), 18U);
}

TEST(TetrahedralGrid, BadSizesAreNamed) {
  EXPECT_NE(error_message([] {
              TetrahedralGrid(Eigen::Vector3d::Zero(), 0.0, Eigen::Vector3i(3, 3, 3));
            }).find("cell size 0"),
            std::string::npos);
  EXPECT_NE(error_message([] {
              TetrahedralGrid(Eigen::Vector3d::Zero(), 1.0, Eigen::Vector3i(3, 1, 3));
            }).find("3 by 1 by 3"),
            std::string::npos);
  EXPECT_NE(error_message([] {
              TetrahedralGrid(Eigen::Vector3d::Zero(), 1.0, Eigen::Vector3i(300, 300, 300));
            }).find("2^24"),
            std::string::npos);
}

}  // namespace
}  // namespace dnurbs
