#include "dnurbs/surface/compliant_triangulation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "tests/surface/random_triangulation.h"

namespace dnurbs {
namespace {

using testing::random_triangulation;
using testing::Triangulation;

std::vector<std::array<int, 3>> rows(const Eigen::MatrixX3i& triangles) {
  std::vector<std::array<int, 3>> result;
  result.reserve(static_cast<size_t>(triangles.rows()));
  for (int t = 0; t < triangles.rows(); ++t) {
    result.push_back({triangles(t, 0), triangles(t, 1), triangles(t, 2)});
  }
  return result;
}

// The size of a maximum matching of the dual graph, by exhaustive search over subsets (memoized):
// an answer independent of the blossom algorithm, for up to about 24 triangles.
int exhaustive_maximum_matching(const Eigen::MatrixX3i& triangles) {
  const auto edges = testing::edge_triangles(rows(triangles));
  const int count = static_cast<int>(triangles.rows());
  std::vector<std::uint32_t> neighbors(static_cast<size_t>(count), 0);
  for (const auto& [edge, users] : edges) {
    if (users.size() == 2) {
      neighbors[static_cast<size_t>(users[0])] |= 1U << users[1];
      neighbors[static_cast<size_t>(users[1])] |= 1U << users[0];
    }
  }
  std::unordered_map<std::uint32_t, int> memo;
  auto best = [&](auto&& self, std::uint32_t free) -> int {
    if (free == 0) {
      return 0;
    }
    if (const auto found = memo.find(free); found != memo.end()) {
      return found->second;
    }
    const int v = __builtin_ctz(free);
    const std::uint32_t rest = free & ~(1U << v);
    int result = self(self, rest);  // v stays unmatched
    for (std::uint32_t options = neighbors[static_cast<size_t>(v)] & rest; options != 0;
         options &= options - 1) {
      const int u = __builtin_ctz(options);
      result = std::max(result, 1 + self(self, rest & ~(1U << u)));
    }
    memo.emplace(free, result);
    return result;
  };
  return best(best, count == 32 ? ~0U : (1U << count) - 1U);
}

double total_area(const Eigen::MatrixX2d& uv, const Eigen::MatrixX3i& triangles) {
  double area = 0.0;
  for (int t = 0; t < triangles.rows(); ++t) {
    area += testing::signed_area(uv.row(triangles(t, 0)).transpose(),
                                 uv.row(triangles(t, 1)).transpose(),
                                 uv.row(triangles(t, 2)).transpose());
  }
  return area;
}

TEST(CompliantTriangulation, SmallRandomTriangulationsPairTheMostTrianglesTheMatchingCan) {
  // 3 x 3 jittered cells (18 triangles) with 0-4 boundary triangles removed: the blocks are a
  // maximum matching (checked exhaustively) and every left-over triangle costs one boundary split
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    SCOPED_TRACE(seed);
    const Triangulation input = random_triangulation(3, 12, static_cast<int>(seed % 5), seed);
    const CompliantTriangulation result = make_compliant(input.uv, input.triangles);
    const int count = static_cast<int>(input.triangles.rows());
    EXPECT_FALSE(result.barycentric);
    EXPECT_EQ(result.paired_blocks, exhaustive_maximum_matching(input.triangles));
    EXPECT_EQ(2 * result.paired_blocks + result.boundary_splits, count);
    EXPECT_EQ(result.added_vertices, result.boundary_splits);
    EXPECT_EQ(result.mesh.triangles.rows(), count + result.boundary_splits);
    EXPECT_EQ(compliance_violations(result.mesh), 0);
    // The input's vertices unchanged and first; the region unchanged (area to rounding)
    EXPECT_EQ(result.mesh.uv.topRows(input.uv.rows()), input.uv);
    EXPECT_NEAR(total_area(result.mesh.uv, result.mesh.triangles),
                std::abs(total_area(input.uv, input.triangles)), 1e-14);
  }
}

TEST(CompliantTriangulation, LargerRandomTriangulationsNeedFewSplits) {
  // 12 x 12 cells (288 triangles), 200 flips and 0-9 removals; each added vertex is the midpoint
  // of an input boundary edge. Measured: 11 vertices added for 2835 triangles
  int total_added = 0;
  int total_triangles = 0;
  for (std::uint32_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE(seed);
    const Triangulation input = random_triangulation(12, 200, static_cast<int>(seed - 1), seed);
    const CompliantTriangulation result = make_compliant(input.uv, input.triangles);
    EXPECT_FALSE(result.barycentric);
    EXPECT_EQ(compliance_violations(result.mesh), 0);
    EXPECT_EQ(2 * result.paired_blocks + result.boundary_splits, input.triangles.rows());
    const auto edges = testing::edge_triangles(rows(input.triangles));
    for (int k = static_cast<int>(input.uv.rows()); k < result.mesh.uv.rows(); ++k) {
      const bool on_boundary = std::any_of(edges.begin(), edges.end(), [&](const auto& entry) {
        const Eigen::RowVector2d midpoint =
            0.5 * (input.uv.row(entry.first.first) + input.uv.row(entry.first.second));
        return entry.second.size() == 1 && midpoint == result.mesh.uv.row(k);
      });
      EXPECT_TRUE(on_boundary) << "added vertex " << k;
    }
    total_added += result.added_vertices;
    total_triangles += static_cast<int>(input.triangles.rows());
  }
  std::cout << "[ compliant ] 10 random triangulations, " << total_triangles
            << " triangles: " << total_added
            << " vertices added by boundary splits (the 1-to-3 split would add " << total_triangles
            << ")\n";
}

TEST(CompliantTriangulation, BarycentricSplitIsCompliantWithOneVertexPerTriangle) {
  const Triangulation input = random_triangulation(5, 40, 3, 7);
  const CompliantTriangulation result =
      make_compliant_by_barycentric_split(input.uv, input.triangles);
  EXPECT_TRUE(result.barycentric);
  EXPECT_EQ(compliance_violations(result.mesh), 0);
  EXPECT_EQ(result.added_vertices, input.triangles.rows());
  EXPECT_EQ(result.mesh.triangles.rows(), 3 * input.triangles.rows());
  // Each centroid is the mean of its triangle's corners
  for (int t = 0; t < input.triangles.rows(); ++t) {
    const Eigen::RowVector2d centroid =
        (input.uv.row(input.triangles(t, 0)) + input.uv.row(input.triangles(t, 1)) +
         input.uv.row(input.triangles(t, 2))) /
        3.0;
    EXPECT_EQ(result.mesh.uv.row(input.uv.rows() + t), centroid);
  }
}

TEST(CompliantTriangulation, ViolationsAreCounted) {
  // The unit square cut along its diagonal 0-2: compliant when both apexes face the diagonal
  Eigen::MatrixX2d uv(4, 2);
  uv << 0, 0, 1, 0, 1, 1, 0, 1;
  BlockTriangulation square{uv, Eigen::MatrixX3i(2, 3)};
  square.triangles << 1, 2, 0, 3, 0, 2;
  EXPECT_EQ(compliance_violations(square), 0);
  // Apex 0 in the first: its refinement edge 1-2 is on the boundary, but the second's (0-2) now
  // faces a side that is not the first's refinement edge
  square.triangles << 0, 1, 2, 3, 0, 2;
  EXPECT_EQ(compliance_violations(square), 1);
  // Clockwise
  square.triangles << 1, 0, 2, 3, 2, 0;
  EXPECT_EQ(compliance_violations(square), 2);
  const CompliantTriangulation made = make_compliant(uv, square.triangles);
  EXPECT_EQ(made.paired_blocks, 1);
  EXPECT_EQ(made.added_vertices, 0);
  EXPECT_EQ(compliance_violations(made.mesh), 0);
}

TEST(CompliantTriangulation, BadInputNamesTheValue) {
  Eigen::MatrixX2d uv(6, 2);
  uv << 0, 0, 1, 0, 1, 1, 0, 1, 2, 0.5, 2, 0;
  Eigen::MatrixX3i out_of_range(1, 3);
  out_of_range << 0, 1, 7;
  EXPECT_THROW(make_compliant(uv, out_of_range), Error);
  Eigen::MatrixX3i collinear(1, 3);
  collinear << 0, 1, 5;  // (0, 0), (1, 0), (2, 0)
  EXPECT_THROW(make_compliant(uv, collinear), Error);
  Eigen::MatrixX3i fin(3, 3);  // edge 0-2 shared by three triangles
  fin << 0, 1, 2, 0, 2, 3, 2, 0, 4;
  try {
    make_compliant(uv, fin);
    ADD_FAILURE() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("edge (2, 0)"), std::string::npos) << error.what();
  }
  EXPECT_THROW(make_compliant_by_barycentric_split(uv, fin), Error);
  EXPECT_THROW(compliance_violations(BlockTriangulation{uv, fin}), Error);
}

}  // namespace
}  // namespace dnurbs
