#include "dnurbs/dynamics/triangular/triangular_local_sculpting.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "triangular_model_helpers.h"

namespace dnurbs {
namespace {

// 40 points along every boundary edge (its start included).
std::vector<Eigen::Vector2d> boundary_samples(const Triangulation& triangulation) {
  std::vector<Eigen::Vector2d> samples;
  const Eigen::MatrixX2i edges = triangulation.boundary_edges();
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    const Eigen::Vector2d a = triangulation.vertex(edges(e, 0));
    const Eigen::Vector2d b = triangulation.vertex(edges(e, 1));
    for (int k = 0; k < 40; ++k) {
      samples.emplace_back(a + (k / 40.0) * (b - a));
    }
  }
  return samples;
}

// Moving every control point that border_control_points leaves free moves no boundary point,
// and every listed control point moves some boundary point (the list is not larger than it
// must be), on each test domain and degree.
TEST(TriangularBorderControlPoints, HoldTheBorderCurveAndNoMore) {
  for (const auto& [name, triangulation] :
       {std::pair{std::string("square"), test::unit_square(3)},
        std::pair{std::string("l_shape"), l_shape_triangulation(2)},
        std::pair{std::string("hole"), square_with_hole_triangulation(2)}}) {
    for (int n = 1; n <= 3; ++n) {
      const auto basis = test::triangular_basis(triangulation, n);
      const std::vector<int> border = border_control_points(*basis);
      ASSERT_TRUE(std::is_sorted(border.begin(), border.end()));
      std::vector<char> on_border(static_cast<size_t>(basis->function_count()), 0);
      for (const int i : border) {
        on_border[static_cast<size_t>(i)] = 1;
      }
      std::vector<double> largest(static_cast<size_t>(basis->function_count()), 0.0);
      double free_trace = 0.0;
      TriangularBasisValues values;
      for (const Eigen::Vector2d& u : boundary_samples(triangulation)) {
        basis->evaluate(u, 0, values);
        for (int a = 0; a < values.count; ++a) {
          const auto f = static_cast<size_t>(values.function[static_cast<size_t>(a)]);
          largest[f] = std::max(largest[f], std::abs(values.value(0, a)));
          if (!on_border[f]) {
            free_trace = std::max(free_trace, std::abs(values.value(0, a)));
          }
        }
      }
      // A free B-spline is zero on the boundary: below the tolerance, at rounding level.
      EXPECT_LE(free_trace, kBorderTraceTolerance) << name << " n = " << n;
      // A listed one is seen at the sample points (its trace is a non-zero polynomial on a
      // piece of an edge, which 40 samples per edge meet).
      int unseen = 0;
      for (const int i : border) {
        unseen += largest[static_cast<size_t>(i)] <= kBorderTraceTolerance ? 1 : 0;
      }
      EXPECT_EQ(unseen, 0) << name << " n = " << n;
      std::cout << "[ border   ] " << name << " n = " << n << ": " << border.size() << " of "
                << basis->function_count() << " control points\n";
    }
  }
}

TEST(TriangularSculptedControlPoints, MarginZeroIsTheSupportAndRingsGrowIt) {
  const auto basis = test::triangular_basis(l_shape_triangulation(3), 2);
  SculptedRegion region;
  region.parameters = {Eigen::Vector2d(0.5, 0.5)};
  const std::vector<int> support = triangular_sculpted_control_points(*basis, region, 0);
  // Margin 0: exactly the B-splines that are non-zero at the parameter
  TriangularBasisValues values;
  basis->evaluate(region.parameters[0], 0, values);
  std::vector<int> expected;
  for (int a = 0; a < values.count; ++a) {
    if (values.value(0, a) != 0.0) {
      expected.push_back(values.function[static_cast<size_t>(a)]);
    }
  }
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(support, expected);
  // Listed control points are kept; rings grow the set monotonically up to everything
  region.control_points = {0};
  std::vector<int> previous = triangular_sculpted_control_points(*basis, region, 0);
  EXPECT_TRUE(std::binary_search(previous.begin(), previous.end(), 0));
  for (int margin = 1; margin <= 12; ++margin) {
    const std::vector<int> grown = triangular_sculpted_control_points(*basis, region, margin);
    EXPECT_TRUE(std::includes(grown.begin(), grown.end(), previous.begin(), previous.end()));
    EXPECT_GE(grown.size(), previous.size());
    previous = grown;
  }
  EXPECT_EQ(static_cast<int>(previous.size()), basis->function_count());
}

TEST(TriangularSculptedControlPoints, BadInputThrowsErrorNamingTheValue) {
  const auto basis = test::triangular_basis(l_shape_triangulation(1), 2);
  SculptedRegion region;
  region.parameters = {Eigen::Vector2d(1.5, 1.5)};  // in the L-shape's missing quadrant
  EXPECT_THROW(triangular_sculpted_control_points(*basis, region, 1), Error);
  region.parameters = {Eigen::Vector2d(std::nan(""), 0.5)};
  EXPECT_THROW(triangular_sculpted_control_points(*basis, region, 1), Error);
  region.parameters.clear();
  region.control_points = {basis->function_count()};
  EXPECT_THROW(triangular_sculpted_control_points(*basis, region, 1), Error);
  region.control_points.clear();
  try {
    triangular_sculpted_control_points(*basis, region, -1);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("margin -1"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace dnurbs
