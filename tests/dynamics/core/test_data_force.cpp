// Data forces (dynamics/core/data_force.h): the nearest material points against closed forms on
// a flat sheet and a sphere, the generalized force as the sum of the point springs, a deformable
// superquadric fitted to an ellipsoid's points, and tracking a moving point cloud with the lag
// of a damped spring.

#include "dnurbs/dynamics/core/data_force.h"

#include <cmath>
#include <cstdio>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"
#include "tests/common/error_message.h"
#include "tests/common/superquadric_test_helpers.h"

namespace dnurbs {
namespace {

// n points spread evenly over the unit sphere (the Fibonacci lattice).
Eigen::MatrixX3d sphere_points(int n) {
  Eigen::MatrixX3d points(n, 3);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < n; ++k) {
    const double z = 1.0 - 2.0 * (k + 0.5) / n;
    const double r = std::sqrt(1.0 - z * z);
    points.row(k) << r * std::cos(golden * k), r * std::sin(golden * k), z;
  }
  return points;
}

DeformableSuperquadricModel unit_sphere(const DeformableSuperquadricSettings& settings) {
  return DeformableSuperquadricModel(test::superellipsoid(1, 1, 1, 1, 1, 1),
                                     Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(),
                                     settings);
}

// The rms and largest distance from the points to the model's nearest material points.
std::pair<double, double> distances(const Model& model, const Eigen::VectorXd& q,
                                    const Eigen::MatrixX3d& points) {
  const auto nearest = nearest_material_points(model, q, points);
  double sum = 0.0;
  double largest = 0.0;
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const double d = (points.row(k).transpose() - nearest[k].position).norm();
    sum += d * d;
    largest = std::max(largest, d);
  }
  return {std::sqrt(sum / static_cast<double>(points.rows())), largest};
}

TEST(NearestMaterialPoint, IsTheFootOfThePerpendicularOnAFlatSheet) {
  // A flat grid sheet: x(u) = origin + (u, v, 0) (bilinear between nodes), so the nearest point of
  // z is (z_x, z_y, 0) inside the sheet and the clamped foot outside it.
  const Grid grid(6, 5, 0.25);
  const TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d(1, 2, 0)));
  const Eigen::VectorXd q = sheet.initial_coordinates();
  Eigen::MatrixX3d points(3, 3);
  points << 1.3, 2.6, 0.5, 1.913, 2.05, -0.25, 3.0, 2.5, 1.0;
  const auto nearest = nearest_material_points(sheet, q, points);
  // (to the round-off of the difference tangents, step 1e-6 of the domain: ~1e-10 relative)
  EXPECT_LT((nearest[0].parameter - Eigen::Vector2d(0.3, 0.6)).norm(), 1e-10);
  EXPECT_LT((nearest[0].position - Eigen::Vector3d(1.3, 2.6, 0)).norm(), 1e-10);
  EXPECT_LT((nearest[1].parameter - Eigen::Vector2d(0.913, 0.05)).norm(), 1e-10);
  // Beyond the sheet's edge u = 1.25: the foot on the edge
  EXPECT_LT((nearest[2].parameter - Eigen::Vector2d(1.25, 0.5)).norm(), 1e-10);
}

TEST(NearestMaterialPoint, LiesOnTheRayToTheCentreOfASphere) {
  // The nearest point of z on the unit sphere is z / |z|: the coarse grid (24 cells) is refined
  // by Newton steps to the error of the difference tangents, O(h^2) at h = 1e-5 of the domain
  // (measured 3.2e-9).
  const auto sphere = unit_sphere({});
  const Eigen::VectorXd q = sphere.initial_coordinates();
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  Eigen::MatrixX3d points(40, 3);
  for (int k = 0; k < 40; ++k) {
    points.row(k) << normal(random), normal(random), normal(random);
  }
  points.row(0) << 0, 0, 3;  // on the pole's ray
  const auto nearest = nearest_material_points(sphere, q, points);
  double worst = 0.0;
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector3d z = points.row(k).transpose();
    worst = std::max(worst, (nearest[k].position - z.normalized()).norm());
  }
  std::printf("nearest points on the unit sphere: largest error %.2e\n", worst);
  EXPECT_LT(worst, 1e-7);
}

TEST(DataForce, IsTheSumOfTheSpringsAtTheNearestPoints) {
  const auto sphere = unit_sphere({});
  const Eigen::VectorXd q = sphere.initial_coordinates();
  const Eigen::MatrixX3d points = 1.3 * sphere_points(20);
  DataForceSettings settings;
  settings.stiffness = 2.5;
  Eigen::VectorXd force = Eigen::VectorXd::Zero(sphere.velocity_count());
  const Eigen::VectorXd qd = Eigen::VectorXd::Zero(sphere.velocity_count());
  data_force(points, settings)(sphere, 0.0, q, qd, force);
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(sphere.velocity_count());
  const auto nearest = nearest_material_points(sphere, q, points, settings);
  for (int k = 0; k < 20; ++k) {
    point_force(nearest[k].parameter,
                Eigen::Vector3d(2.5 * (points.row(k).transpose() - nearest[k].position)))(
        sphere, 0.0, q, qd, expected);
  }
  EXPECT_LT((force - expected).norm(), 1e-12 * expected.norm());
  // Points all 0.3 outside the unit sphere along their directions n_k: the net force on the
  // centre is k 0.3 sum_k n_k (the lattice's small asymmetry)
  const Eigen::Vector3d net = 2.5 * 0.3 * (points / 1.3).colwise().sum().transpose();
  EXPECT_LT((force.head<3>() - net).norm(), 1e-8 * (1.0 + net.norm()));
}

TEST(DataForce, FitsASuperquadricToAnEllipsoidsPoints) {
  // A unit sphere with free translation, rotation and sizes a1, a2, a3 (no shape springs) pulled
  // by 300 points of the ellipsoid with semi-axes (1.3, 0.8, 1.0) about (0.2, -0.1, 0.1): at rest
  // the data forces balance, which for a model that can take the data's shape exactly means
  // every point on the surface (Terzopoulos & Metaxas 1991). Measured: rms distance 2.4e-5
  // (largest 4.8e-5) after 5 s, from 0.205 at the start; the slowest mode still decays as about
  // exp(-0.57 t) (7.5e-5 at 3 s), which the bounds leave room for.
  DeformableSuperquadricSettings settings;
  settings.parts = DeformableSuperquadricParts::rigid();
  for (const int k : {SuperquadricShapeParameter::kAspect1, SuperquadricShapeParameter::kAspect2,
                      SuperquadricShapeParameter::kAspect3}) {
    settings.parts.shape[k] = true;
  }
  settings.shape_stiffness = SuperquadricShapeParameters::Zero();
  settings.damping_alpha = 20.0;
  System system(unit_sphere(settings));
  const Eigen::Vector3d centre(0.2, -0.1, 0.1);
  Eigen::MatrixX3d data = sphere_points(300);
  data = (data.array().rowwise() * Eigen::RowVector3d(1.3, 0.8, 1.0).array()).matrix();
  data.rowwise() += centre.transpose();
  const auto [start_rms, start_largest] = distances(system.model(0), system.coordinates(0), data);
  DataForceSettings fit;
  fit.stiffness = 20.0;
  system.add_force(0, data_force(data, fit));
  Integrator integrator(IntegratorSettings{IntegratorScheme::kImplicitEuler});
  for (int step = 0; step < 500; ++step) {
    integrator.step(system, 0.01);
  }
  const Eigen::VectorXd q = system.coordinates(0);
  const auto [rms, largest] = distances(system.model(0), q, data);
  std::printf("superquadric fit: rms distance %.2e (largest %.2e), from %.3f at the start\n", rms,
              largest, start_rms);
  EXPECT_GT(start_rms, 0.1);
  EXPECT_LT(rms, 1e-4);
  EXPECT_LT(largest, 2e-4);
  EXPECT_LT((q.head<3>() - centre).norm(), 1e-4);
}

TEST(DataForce, TrackingAMovingCloudLagsLikeADampedSpring) {
  // A rigid unit sphere, damping D = alpha M, pulled by the points of a unit sphere that moves at
  // velocity v. At small offsets delta = c_data - c the springs pull with sum_k k n_k n_k^T delta
  // (only the offset along each point's normal stretches its spring), so the steady lag balances
  // the damping: delta = (k sum_k n_k n_k^T)^-1 alpha m v, m the sphere's mass (M's translation
  // block). The lag is ~0.01, so the linearization is good to O(delta) ~ 1 %.
  DeformableSuperquadricSettings settings;
  settings.damping_alpha = 20.0;
  System system(unit_sphere(settings));
  const Eigen::MatrixX3d cloud = sphere_points(200);
  const Eigen::Vector3d velocity(0.5, 0.2, 0.0);
  DataForceSettings track;
  track.stiffness = 200.0;
  system.add_force(0, moving_data_force(
                          [cloud, velocity](double t) {
                            Eigen::MatrixX3d moved = cloud;
                            moved.rowwise() += (t * velocity).transpose();
                            return moved;
                          },
                          track));
  Integrator integrator(IntegratorSettings{IntegratorScheme::kImplicitEuler});
  const double dt = 0.005;
  for (int step = 0; step < 400; ++step) {
    integrator.step(system, dt);
  }
  ModelMatrices matrices;
  system.model(0).assemble_matrices(system.coordinates(0), matrices);
  const double mass = matrices.mass.coeff(0, 0);
  const Eigen::Matrix3d spring = track.stiffness * cloud.transpose() * cloud;
  const Eigen::Vector3d expected = spring.ldlt().solve(settings.damping_alpha * mass * velocity);
  const double t = system.time();
  const Eigen::Vector3d lag = t * velocity - system.coordinates(0).head<3>();
  std::printf("tracking: lag (%.5f, %.5f, %.5f), damped-spring lag (%.5f, %.5f, %.5f)\n", lag.x(),
              lag.y(), lag.z(), expected.x(), expected.y(), expected.z());
  EXPECT_LT((lag - expected).norm(), 0.03 * expected.norm());
  // Implicit Euler's velocity lags the cloud's by O(dt) only in the transient: at steady state
  // the sphere moves with the cloud.
  EXPECT_LT((system.velocities(0).head<3>() - velocity).norm(), 1e-3 * velocity.norm());
}

TEST(DataForce, BadInputIsNamed) {
  DataForceSettings settings;
  settings.stiffness = -1.0;
  EXPECT_THAT(testing::error_message([&] { data_force(Eigen::MatrixX3d::Zero(2, 3), settings); }),
              ::testing::HasSubstr("stiffness -1"));
  settings.stiffness = 1.0;
  settings.search_segments = 1;
  EXPECT_THAT(testing::error_message([&] { data_force(Eigen::MatrixX3d::Zero(2, 3), settings); }),
              ::testing::HasSubstr("search segments 1"));
  Eigen::MatrixX3d bad = Eigen::MatrixX3d::Zero(3, 3);
  bad(2, 1) = NAN;
  EXPECT_THAT(testing::error_message([&] { data_force(bad); }),
              ::testing::HasSubstr("point 2 (0, nan, 0)"));
  EXPECT_THAT(testing::error_message([&] { moving_data_force(PointsOfTime{}); }),
              ::testing::HasSubstr("no point function"));
}

}  // namespace
}  // namespace dnurbs
