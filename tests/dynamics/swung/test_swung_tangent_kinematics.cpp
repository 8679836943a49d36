// Tests of dynamics/swung/swung_tangent_kinematics.h beyond the model's finite-difference test
// (tests/dynamics/swung/test_dnurbs_swung_surface_shape.cpp): the columns of a periodic curve's
// wrapped window come out ascending, and a coordinate listed twice has its columns summed.

#include "dnurbs/dynamics/swung/swung_tangent_kinematics.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "dnurbs/nurbs/swung_shapes.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

TEST(SwungTangentKinematics, WrappedColumnsAreSortedAndRepeatedOnesSummed) {
  // Near v = 1 the circle's window wraps: trajectory control points 7, 0 (and 1).
  const SwungSurface sphere = swung_sphere(1.0);
  SwungJacobian jacobian;
  swung_jacobian(sphere, 0.3, 0.99, 1, WeightMode::kFixed, jacobian);
  const SwungLayout layout = swung_layout(sphere, WeightMode::kFixed);
  const Eigen::VectorXd qd = Eigen::VectorXd::LinSpaced(layout.coordinate_count(), -1.0, 1.0);
  std::array<Eigen::Vector3d, 6> rates;
  swung_jacobian_rate(sphere, 0.3, 0.99, 1, WeightMode::kFixed, qd, rates);
  TangentKinematics tangents;
  swung_tangent_kinematics(jacobian, qd, rates, tangents);
  ASSERT_EQ(tangents.columns.size(), static_cast<size_t>(jacobian.column_count));
  EXPECT_TRUE(std::is_sorted(tangents.columns.begin(), tangents.columns.end()));
  EXPECT_EQ(tangents.columns.back(), layout.trajectory_offset(7) + 1);
  // A Jacobian that lists a coordinate twice (as a curve with fewer distinct control points
  // than its window would): the two columns are summed into one.
  SwungJacobian doubled = jacobian;
  doubled.coordinate[1] = doubled.coordinate[0];
  TangentKinematics merged;
  swung_tangent_kinematics(doubled, qd, rates, merged);
  ASSERT_EQ(merged.columns.size(), tangents.columns.size() - 1);
  const auto iu = static_cast<size_t>(SurfaceQuantity::kU);
  const int first = doubled.coordinate[0];
  const auto at = std::find(merged.columns.begin(), merged.columns.end(), first);
  ASSERT_NE(at, merged.columns.end());
  const Eigen::Vector3d expected = jacobian.columns[iu].col(0) + jacobian.columns[iu].col(1);
  EXPECT_EQ(merged.ju.col(at - merged.columns.begin()), expected);
  // Order 0 carries no tangents.
  SwungJacobian points;
  swung_jacobian(sphere, 0.3, 0.5, 0, WeightMode::kFixed, points);
  EXPECT_NE(testing::error_message([&] {
              swung_tangent_kinematics(points, qd, rates, tangents);
            }).find("order >= 1"),
            std::string::npos);
}

}  // namespace
}  // namespace dnurbs
