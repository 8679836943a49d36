// Tests of dynamics/swung/swung_gauge.h: the gauge direction moves no point of the surface (J g
// = 0 at random parameters), the choice of the gauge coordinate, and which fixed coordinates
// already remove the gauge.

#include "dnurbs/dynamics/swung/swung_gauge.h"

#include <gtest/gtest.h>

#include "dnurbs/nurbs/swung_shapes.h"
#include "tests/common/error_message.h"
#include "tests/nurbs/swung_sample_shapes.h"

namespace dnurbs {
namespace {

TEST(SwungGauge, DirectionMovesNoPointOfTheSurface) {
  for (const WeightMode mode : {WeightMode::kFixed, WeightMode::kFree}) {
    const SwungSurface surface = testing::random_swung_surface(3, 2, 29, true);
    const SwungLayout layout = swung_layout(surface, mode);
    const Eigen::VectorXd q = swung_coordinates(surface, mode);
    const Eigen::VectorXd g = swung_scaling_gauge_direction(layout, q);
    for (const auto& [u, v] : {std::pair{0.1, 0.2}, std::pair{0.5, 0.5}, std::pair{0.93, 0.71}}) {
      SwungJacobian jacobian;
      swung_jacobian(surface, u, v, 2, mode, jacobian);
      for (int quantity = 0; quantity < 6; ++quantity) {
        const Eigen::Vector3d moved =
            Eigen::MatrixXd(to_sparse_matrix(jacobian, static_cast<SurfaceQuantity>(quantity),
                                             layout.coordinate_count())) *
            g;
        // alpha x_i X_j - alpha X_j x_i: exact cancellation up to round-off of the sums.
        EXPECT_LT(moved.norm(), 1e-13 * g.norm()) << quantity;
      }
    }
    EXPECT_GT(g.norm(), 1.0);
  }
}

TEST(SwungGauge, CoordinateAndWhatRemovesTheGauge) {
  const SwungSurface sphere = swung_sphere(1.0);
  const SwungLayout layout = swung_layout(sphere, WeightMode::kFixed);
  const Eigen::VectorXd q = swung_coordinates(sphere, WeightMode::kFixed);
  const int gauge = swung_scaling_gauge_coordinate(layout, q);
  EXPECT_EQ(gauge, layout.profile_offset(2));  // the equator among three points with x = 1
  // Poles (x = 0), z coordinates and the gauge itself do not remove it...
  EXPECT_FALSE(fixes_swung_scaling_gauge(
      layout, q, gauge,
      {layout.profile_offset(0), layout.profile_offset(4), gauge, layout.profile_offset(2) + 1}));
  // ...another profile x off the axis or a trajectory point off the origin does.
  EXPECT_TRUE(fixes_swung_scaling_gauge(layout, q, gauge, {layout.profile_offset(1)}));
  EXPECT_TRUE(fixes_swung_scaling_gauge(layout, q, gauge, {layout.trajectory_offset(3) + 1}));
  EXPECT_NE(testing::error_message([&] {
              (void)swung_scaling_gauge_direction(layout, Eigen::VectorXd::Zero(4));
            }).find("coordinate vector has 4 entries"),
            std::string::npos);
}

}  // namespace
}  // namespace dnurbs
