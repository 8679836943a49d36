// Tests of dynamics/swung/dnurbs_swung_surface_boundary.cpp: the swung model's points and border
// (Model::fix_point, Model::fix_border), the curve fixes, the release of the scaling gauge
// coordinate when a fix already removes the gauge (so the gauge coordinate never becomes a real
// constraint: M stays positive definite on the free coordinates and nothing extra is held), and
// the lower bounds of free weights.

#include <algorithm>
#include <iostream>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include "dnurbs/dynamics/swung/dnurbs_swung_surface.h"
#include "dnurbs/dynamics/swung/swung_gauge.h"
#include "dnurbs/nurbs/swung_shapes.h"
#include "tests/common/error_message.h"
#include "tests/dynamics/swung/swung_model_helpers.h"

namespace dnurbs {
namespace {

using testing::settings_for;

bool is_fixed(const Model& model, int k) {
  return std::binary_search(model.fixed_coordinates().begin(), model.fixed_coordinates().end(), k);
}

// Smallest eigenvalue of M over the free coordinates, relative to the largest.
double reduced_mass_conditioning(const DNurbsSwungSurface& model) {
  ModelMatrices matrices;
  model.assemble_matrices(model.initial_coordinates(), matrices);
  std::vector<int> free_indices;
  for (int k = 0; k < model.velocity_count(); ++k) {
    if (!is_fixed(model, k)) {
      free_indices.push_back(k);
    }
  }
  const Eigen::MatrixXd mass = Eigen::MatrixXd(matrices.mass)(free_indices, free_indices);
  const Eigen::VectorXd eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(mass).eigenvalues();
  return eigenvalues.minCoeff() / eigenvalues.maxCoeff();
}

TEST(SwungBoundary, PointsAreTheProfileThenTheTrajectoryControlPoints) {
  DNurbsSwungSurface model(swung_sphere(1.0), {}, settings_for(WeightMode::kFree));
  // 5 profile points (0..4), 8 trajectory points (5..12).
  model.fix_point(1);
  EXPECT_TRUE(is_fixed(model, model.profile_offset(1)));
  EXPECT_TRUE(is_fixed(model, model.profile_offset(1) + 1));
  EXPECT_FALSE(is_fixed(model, model.profile_offset(1) + 2));  // its free weight stays free
  EXPECT_EQ(model.gauge_coordinate(), -1);  // a profile point off the axis breaks the scaling
  model.fix_point(12);
  EXPECT_TRUE(is_fixed(model, model.trajectory_offset(7)));
  EXPECT_TRUE(is_fixed(model, model.trajectory_offset(7) + 1));
  EXPECT_NE(testing::error_message([&] { model.fix_point(13); })
                .find("point 13 does not exist: points 0..4 are the profile's control points, "
                      "5..12 the trajectory's"),
            std::string::npos);
  EXPECT_NE(testing::error_message([&] { model.fix_point(-1); }).find("point -1"),
            std::string::npos);
}

TEST(SwungBoundary, FixingAPointThatBreaksTheScalingReleasesTheGaugeCoordinate) {
  // The sphere's gauge is the equator's x (profile point 2). Profile point 1 has x = 1: with it
  // fixed the scaling is gone, and the gauge coordinate would hold the equator too.
  DNurbsSwungSurface model(swung_sphere(1.0));
  const int gauge = model.gauge_coordinate();
  EXPECT_EQ(gauge, model.profile_offset(2));
  model.fix_profile_point(1);
  EXPECT_EQ(model.gauge_coordinate(), -1);
  EXPECT_EQ(model.fixed_coordinates(),
            (std::vector<int>{model.profile_offset(1), model.profile_offset(1) + 1}));
  // The gauge is still removed: M is positive definite on the free coordinates.
  const double conditioning = reduced_mass_conditioning(model);
  std::cout << "sphere with profile point 1 fixed: reduced M conditioning " << conditioning << "\n";
  EXPECT_GT(conditioning, 1e-8);  // measured 1e-4; the gauge direction alone gives ~1e-17

  // The poles (x = 0) do not break the scaling: the gauge coordinate stays.
  DNurbsSwungSurface poles(swung_sphere(1.0));
  poles.fix_poles();
  EXPECT_EQ(poles.gauge_coordinate(), gauge);
  // A fix that lists the gauge coordinate itself keeps it through a later release.
  DNurbsSwungSurface equator(swung_sphere(1.0));
  equator.fix_profile_point(2);
  EXPECT_EQ(equator.gauge_coordinate(), gauge);
  equator.fix_trajectory_point(0);
  EXPECT_EQ(equator.gauge_coordinate(), -1);
  EXPECT_TRUE(is_fixed(equator, gauge));
  EXPECT_TRUE(is_fixed(equator, equator.profile_offset(2) + 1));
  EXPECT_TRUE(is_fixed(equator, equator.trajectory_offset(0)));
}

TEST(SwungBoundary, FixedTrajectoryReleasesTheGaugeAndKeepsTheWeightGauges) {
  DNurbsSwungSurface model(swung_sphere(1.0), {}, settings_for(WeightMode::kFree));
  model.fix_poles();
  model.fix_trajectory();
  EXPECT_EQ(model.gauge_coordinate(), -1);
  std::vector<int> expected = {model.profile_offset(0), model.profile_offset(0) + 2,
                               model.profile_offset(4)};
  for (int k = model.trajectory_offset(0); k < model.coordinate_count(); ++k) {
    expected.push_back(k);
  }
  EXPECT_EQ(model.fixed_coordinates(), expected);
  EXPECT_GT(reduced_mass_conditioning(model), 1e-10);  // measured 2e-7 (light weights)
}

TEST(SwungBoundary, BorderOfTheHatIsTheBrimEdge) {
  // The hat: apex on the axis at u = 0 (a pole), the brim's edge at u = 1, closed around z.
  DNurbsSwungSurface hat(swung_hat(1.5, 0.8, 1.0));
  hat.fix_border();
  std::vector<int> expected = {hat.profile_offset(7), hat.profile_offset(7) + 1};
  for (int k = hat.trajectory_offset(0); k < hat.coordinate_count(); ++k) {
    expected.push_back(k);
  }
  EXPECT_EQ(hat.fixed_coordinates(), expected);  // the gauge (the brim's x) is among them
  EXPECT_EQ(hat.gauge_coordinate(), -1);
  // Any motion of the free coordinates leaves the brim's edge where it is.
  Eigen::VectorXd q = hat.initial_coordinates();
  const Eigen::VectorXd step = testing::random_vector(q.size(), 5);
  for (int k = 0; k < q.size(); ++k) {
    if (!is_fixed(hat, k)) {
      q[k] += 0.3 * step[k];
    }
  }
  for (const double v : {0.0, 0.13, 0.5, 0.77}) {
    const Eigen::Vector2d edge(1.0, v);
    EXPECT_EQ(hat.position(q, edge), hat.position(hat.initial_coordinates(), edge));
  }
  EXPECT_GT((hat.position(q, Eigen::Vector2d(0.4, 0.2)) -
             hat.position(hat.initial_coordinates(), Eigen::Vector2d(0.4, 0.2)))
                .norm(),
            1e-3);  // the inside moved
}

TEST(SwungBoundary, ClosedSurfacesHaveNoBorder) {
  for (const SwungSurface& surface : {swung_sphere(1.0), swung_torus(2.0, 0.5)}) {
    DNurbsSwungSurface model(surface);
    EXPECT_NE(testing::error_message([&] { model.fix_border(); }).find("has no border"),
              std::string::npos);
  }
}

TEST(SwungBoundary, LowerBoundsAreTheMinimumOfEveryFreeWeight) {
  const DNurbsSwungSurface free(swung_sphere(1.0), {}, settings_for(WeightMode::kFree));
  Eigen::VectorXd lower =
      Eigen::VectorXd::Constant(free.velocity_count(), -std::numeric_limits<double>::infinity());
  free.coordinate_lower_bounds(lower);
  for (int k = 0; k < free.velocity_count(); ++k) {
    EXPECT_EQ(lower[k],
              k % 3 == 2 ? free.minimum_weight() : -std::numeric_limits<double>::infinity())
        << k;
  }
  const DNurbsSwungSurface fixed(swung_sphere(1.0));
  lower.setZero(fixed.velocity_count());
  fixed.coordinate_lower_bounds(lower);
  EXPECT_EQ(lower, Eigen::VectorXd::Zero(fixed.velocity_count()));  // untouched
}

}  // namespace
}  // namespace dnurbs
