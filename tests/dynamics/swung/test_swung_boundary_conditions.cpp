// Tests of dynamics/swung/swung_boundary_conditions.h: the points of a swung model, and the
// border coordinates of open, capped and closed surfaces; fixing them holds every border edge
// exactly while the rest of the coordinates move.

#include "dnurbs/dynamics/swung/swung_boundary_conditions.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "dnurbs/dynamics/swung/swung_parametric_surface.h"
#include "dnurbs/nurbs/swung_shapes.h"
#include "tests/common/error_message.h"
#include "tests/nurbs/swung_sample_shapes.h"

namespace dnurbs {
namespace {

TEST(SwungBoundaryConditions, PointsMapToInPlaneCoordinates) {
  const SwungLayout layout = swung_layout(swung_sphere(1.0), WeightMode::kFree);
  EXPECT_EQ(swung_point_coordinates(layout, 0), (std::vector<int>{0, 1}));
  EXPECT_EQ(swung_point_coordinates(layout, 4), (std::vector<int>{12, 13}));
  EXPECT_EQ(swung_point_coordinates(layout, 5), (std::vector<int>{15, 16}));  // trajectory 0
  EXPECT_NE(testing::error_message([&] {
              (void)swung_point_coordinates(layout, 13);
            }).find("point 13 does not exist"),
            std::string::npos);
}

// Every border edge stays where it is when every other position coordinate moves; returns how
// many moved.
int expect_border_held(const SwungSurface& surface, WeightMode mode) {
  const SwungLayout layout = swung_layout(surface, mode);
  const ParameterDomain domain = swung_parameter_domain(surface);
  const std::vector<int> border = swung_border_coordinates(surface, layout, domain);
  Eigen::VectorXd q = swung_coordinates(surface, mode);
  int moved_count = 0;
  for (int k = 0; k < q.size(); ++k) {
    const bool weight = mode == WeightMode::kFree && k % 3 == 2;
    if (!weight && !std::binary_search(border.begin(), border.end(), k)) {
      q[k] += 0.1 * std::sin(3.0 * k + 1.0);
      ++moved_count;
    }
  }
  const SwungSurface moved = swung_surface_at(surface, mode, q);
  for (int k = 0; k <= 10; ++k) {
    const double t = k / 10.0;
    const double u = domain.u_at(t);
    const double v = domain.v_at(t);
    if (!domain.periodic_u && !domain.pole_u_min) {
      EXPECT_EQ(moved.point(domain.u_min, v), surface.point(domain.u_min, v));
    }
    if (!domain.periodic_u && !domain.pole_u_max) {
      EXPECT_EQ(moved.point(domain.u_max, v), surface.point(domain.u_max, v));
    }
    if (!domain.periodic_v) {
      EXPECT_EQ(moved.point(u, domain.v_min), surface.point(u, domain.v_min));
      EXPECT_EQ(moved.point(u, domain.v_max), surface.point(u, domain.v_max));
    }
  }
  return moved_count;
}

TEST(SwungBoundaryConditions, BorderEdgesOfOpenSurfacesAreHeld) {
  // The cylinder: both profile ends and the trajectory.
  const SwungSurface cylinder = swung_cylinder(1.0, 2.0, 5);
  const SwungLayout layout = swung_layout(cylinder, WeightMode::kFixed);
  const std::vector<int> border =
      swung_border_coordinates(cylinder, layout, swung_parameter_domain(cylinder));
  std::vector<int> expected = {0, 1, 8, 9};
  for (int k = layout.trajectory_offset(0); k < layout.coordinate_count(); ++k) {
    expected.push_back(k);
  }
  EXPECT_EQ(border, expected);
  EXPECT_EQ(expect_border_held(cylinder, WeightMode::kFixed), 6);  // profile points 1..3
  // The hat (a pole at the apex): everything but the brim's edge point and the trajectory.
  EXPECT_EQ(expect_border_held(swung_hat(1.5, 0.8, 1.0), WeightMode::kFixed), 2 * 7);
  // Capped at both poles, open around the axis: edges along v hold the whole profile and the
  // trajectory's end points; its interior points move (free weights stay free).
  const SwungSurface sphere = swung_sphere(1.0);
  const SwungSurface segment(sphere.profile(), testing::random_trajectory(2, 31, false));
  EXPECT_EQ(expect_border_held(segment, WeightMode::kFree),
            2 * (segment.trajectory().control_point_count() - 2));
  // Open in both directions with no pole: every position coordinate is on the border.
  EXPECT_EQ(expect_border_held(testing::random_swung_surface(3, 2, 31, false), WeightMode::kFree),
            0);
}

TEST(SwungBoundaryConditions, ClosedSurfacesHaveNoBorderCoordinates) {
  for (const SwungSurface& surface : {swung_sphere(1.0), swung_torus(2.0, 0.5)}) {
    EXPECT_TRUE(swung_border_coordinates(surface, swung_layout(surface, WeightMode::kFixed),
                                         swung_parameter_domain(surface))
                    .empty());
  }
}

}  // namespace
}  // namespace dnurbs
