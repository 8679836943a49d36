// The D-NURBS forces (gravity, point force, spring) and the point constraints act on deformable
// superquadrics unchanged, through L^T and the Model contract.

#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "constraints/constraint_solver.h"
#include "constraints/point_constraints.h"
#include "dynamics/superquadric/deformable_superquadric_model.h"
#include "dynamics/core/forces.h"
#include "dynamics/integrators/integrator.h"
#include "dynamics/core/system.h"
#include "tests/common/superquadric_test_helpers.h"

namespace dnurbs {
namespace {

using test::some_rotation;
using test::superellipsoid;

TEST(SuperquadricForces, GravityMakesARigidSuperquadricFallWithoutTurning) {
  const DeformableSuperquadricModel model(superellipsoid(1.0, 1.4, 1.0, 0.7, 0.6, 1.8),
                                          Eigen::Vector3d::Zero(), some_rotation());
  System system(model);
  system.add_force(0, gravity(Eigen::Vector3d(0.0, 0.0, -9.81)));
  Integrator integrator;  // newmark, linearly implicit
  for (int i = 0; i < 100; ++i) {
    integrator.step(system, 0.01);
  }
  // Average-acceleration Newmark is exact for a constant acceleration: round-off only.
  EXPECT_NEAR(system.coordinates()[2], -0.5 * 9.81 * 1.0, 1e-10);
  EXPECT_LT(system.coordinates().head<2>().norm(), 1e-10);
  // The weight acts through the centre of mass (at the origin for this symmetric shape): no spin.
  EXPECT_LT(system.velocities().tail<3>().norm(), 1e-10);
}

TEST(SuperquadricForces, PointForceGivesForceOnCentreAndBodyTorque) {
  DeformableSuperquadricSettings settings;
  settings.parts = DeformableSuperquadricParts::global();
  const DeformableSuperquadricModel model(test::deformed_shape(0.8, 1.2), Eigen::Vector3d(1, 0, 0),
                                          some_rotation(), settings);
  const Eigen::VectorXd q = model.initial_coordinates();
  const Eigen::Vector2d u(0.2, 1.0);
  const Eigen::Vector3d f(0.3, -1.0, 2.0);
  Eigen::VectorXd generalized = Eigen::VectorXd::Zero(model.velocity_count());
  point_force(u, f)(model, 0.0, q, Eigen::VectorXd::Zero(model.velocity_count()), generalized);
  const Eigen::Matrix3d rotation = model.orientation(q).toRotationMatrix();
  const Eigen::Vector3d p =
      rotation.transpose() * (model.position(q, u) - Eigen::Vector3d(1, 0, 0));
  // L^T f = [f, p x R^T f, J^T R^T f]: round-off only.
  EXPECT_LT((generalized.head<3>() - f).norm(), 1e-14);
  EXPECT_LT((generalized.segment<3>(3) - p.cross(rotation.transpose() * f)).norm(), 1e-13);
  EXPECT_GT(generalized.tail(model.velocity_count() - 6).norm(), 0.0);  // it deforms the shape
}

TEST(SuperquadricConstraints, PinnedRigidSuperquadricSwingsAsAPendulumKeepingItsPin) {
  // A rigid ellipsoid pinned at its north pole to a fixed point, released sideways under gravity.
  const DeformableSuperquadricModel model(
      superellipsoid(1.0, 0.5, 0.5, 1.0, 1.0, 1.0), Eigen::Vector3d::Zero(),
      Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX())));
  System system(model);
  system.add_force(0, gravity(Eigen::Vector3d(0.0, 0.0, -9.81)));
  const Eigen::Vector2d pole(1.5707963267948966, 0.0);
  const Eigen::Vector3d pin = model.position(model.initial_coordinates(), pole);
  ConstraintSolver solver;
  solver.add(system, PointTargetConstraint(0, pole, TargetTrajectory::fixed(pin)));
  IntegratorSettings settings;
  settings.newton_iterations = 3;
  Integrator integrator(settings);
  double largest_violation = 0.0;
  double lowest = 0.0;
  for (int i = 0; i < 200; ++i) {
    solver.step(integrator, system, 0.005);
    largest_violation = std::max(largest_violation, solver.max_violation(system));
    lowest = std::min(lowest, system.coordinates()[2]);
  }
  std::cout << "pinned superquadric pendulum, 1 s: largest pin violation " << largest_violation
            << "\n";
  // Baumgarte-stabilised acceleration-level constraint: drift O(dt^2) per step, corrected.
  EXPECT_LT(largest_violation, 1e-4);
  EXPECT_LT(lowest, -0.05);  // it swung down
  EXPECT_TRUE(system.coordinates().allFinite());
}

}  // namespace
}  // namespace dnurbs
