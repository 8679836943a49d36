// The integrator factors A block by block (one block per model): a constant D-NURBS block is
// factored once per (dt, scheme) even beside a state-dependent deformable superquadric whose block
// is re-factored at every solve, and, the models being uncoupled in M, D, K, the trajectory of
// the mixed System is that of each model stepped alone in its own System.

#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "dynamics/superquadric/deformable_superquadric_model.h"
#include "dynamics/dnurbs/dnurbs_surface.h"
#include "dynamics/core/forces.h"
#include "dynamics/integrators/integrator.h"
#include "dynamics/core/system.h"
#include "tests/common/dynamics_test_helpers.h"
#include "core/error.h"

namespace dnurbs {
namespace {

constexpr double kDt = 0.01;
const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);

// A point load on the sheet.
Force sheet_load() {
  return point_force(Eigen::Vector2d(0.4, 0.65), Eigen::Vector3d(0.1, 0.0, -2.0));
}

// Model 0: a 7 x 7 fixed-weight D-NURBS membrane with its border fixed (constant M, D, K with the
// S (x) I_3 structure) under a point load; model 1: a deformable superquadric with its global
// deformations free (state-dependent matrices) under gravity, spinning and deforming.
System sheet_and_superquadric() {
  DNurbsSurfaceMaterial material;
  material.damping_density = 0.1;
  material.a10 = 1.0;
  material.a01 = 1.0;
  material.b20 = 0.01;
  material.b02 = 0.01;
  DNurbsSurface sheet(test::flat_patch(3, 3, 4, 4), material);
  sheet.fix_border();
  SuperquadricShapeParameters shape = SuperquadricShapeParameters::Zero();
  shape << 1.0, 0.3, 0.25, 0.35, 0.8, 1.2, 0.1, -0.05, 0, 0, 0, 0.2, 0, 0;
  DeformableSuperquadricSettings settings;
  settings.parts = DeformableSuperquadricParts::global();
  const DeformableSuperquadricModel body(
      shape, Eigen::Vector3d(0.5, 0.5, 1.0),
      Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1.0, 2.0, 0.5).normalized())),
      settings);
  System system;
  system.add_model(sheet);
  system.add_model(body);
  system.add_force(0, sheet_load());
  system.add_force(1, gravity(kGravity));
  Eigen::VectorXd spin = Eigen::VectorXd::Zero(body.velocity_count());
  for (int i = 3; i < body.velocity_count(); ++i) {
    spin[i] = 0.5 * std::sin(1.7 * i);  // angular velocity and shape rates
  }
  system.set_velocities(1, spin);
  return system;
}

// Steps `system` `steps` times with a fresh integrator of `settings`.
Integrator run(System& system, const IntegratorSettings& settings, int steps) {
  Integrator integrator(settings);
  for (int k = 0; k < steps; ++k) {
    integrator.step(system, kDt);
  }
  return integrator;
}

double relative_difference(const Eigen::VectorXd& value, const Eigen::VectorXd& reference) {
  return (value - reference).norm() / reference.norm();
}

TEST(BlockFactorization, ConstantBlockIsFactoredOnceBesideAStateDependentOne) {
  System system = sheet_and_superquadric();
  ASSERT_FALSE(system.matrices_are_constant());
  IntegratorSettings settings;  // newmark
  settings.newton_iterations = 2;
  settings.newton_tolerance = 0.0;  // every iteration runs: 3 solves per step
  const int steps = 40;
  const Integrator integrator = run(system, settings, steps);
  EXPECT_EQ(integrator.block_factorization_count(0), 1);          // the D-NURBS sheet
  EXPECT_EQ(integrator.block_factorization_count(1), 3 * steps);  // the superquadric
  EXPECT_EQ(integrator.factorization_count(), 1 + 3 * steps);
  EXPECT_EQ(integrator.last_newton_iterations(), 2);
  EXPECT_THROW(static_cast<void>(integrator.block_factorization_count(2)), Error);
  EXPECT_THROW(static_cast<void>(integrator.block_factorization_count(-1)), Error);
}

TEST(BlockFactorization, NewTimeStepRefactorsTheConstantBlockOnce) {
  System system = sheet_and_superquadric();
  Integrator integrator;
  for (int k = 0; k < 5; ++k) {
    integrator.step(system, kDt);
  }
  for (int k = 0; k < 5; ++k) {
    integrator.step(system, 2.0 * kDt);
  }
  EXPECT_EQ(integrator.block_factorization_count(0), 2);
  EXPECT_EQ(integrator.block_factorization_count(1), 10);
}

TEST(BlockFactorization, MixedTrajectoryEqualsEachModelSteppedAlone) {
  // Uncoupled models: the block solves of the mixed System are the solves of the single-model
  // Systems, so the states agree to rounding (assert 1e-12 relative).
  for (const IntegratorScheme scheme :
       {IntegratorScheme::kNewmark, IntegratorScheme::kImplicitEuler, IntegratorScheme::kCentral}) {
    System mixed = sheet_and_superquadric();
    System sheet(mixed.model(0));
    System body(mixed.model(1));
    sheet.add_force(0, sheet_load());
    body.add_force(0, gravity(kGravity));
    body.set_velocities(0, mixed.velocities(1));
    const IntegratorSettings settings{scheme};
    const int steps = 30;  // central goes unstable on the spinning superquadric near 60
    run(mixed, settings, steps);
    run(sheet, settings, steps);
    run(body, settings, steps);
    const int sheet_size = sheet.velocity_count();
    const int body_size = body.velocity_count();
    const double sheet_error =
        relative_difference(mixed.coordinates().head(sheet_size), sheet.coordinates());
    const double body_error =
        relative_difference(mixed.coordinates().tail(body.coordinate_count()), body.coordinates());
    const double velocity_error =
        std::max(relative_difference(mixed.velocities().head(sheet_size), sheet.velocities()),
                 relative_difference(mixed.velocities().tail(body_size), body.velocities()));
    std::cout << to_string(scheme) << ": mixed against alone, coordinates " << sheet_error << ", "
              << body_error << ", velocities " << velocity_error << "\n";
    EXPECT_LT(sheet_error, 1e-12) << to_string(scheme);
    EXPECT_LT(body_error, 1e-12) << to_string(scheme);
    EXPECT_LT(velocity_error, 1e-12) << to_string(scheme);
    // Both models moved (the comparison is not between two rest states).
    EXPECT_GT((sheet.coordinates() - mixed.model(0).initial_coordinates()).norm(), 1e-3);
    EXPECT_GT((body.coordinates() - mixed.model(1).initial_coordinates()).norm(), 1e-3);
  }
}

}  // namespace
}  // namespace dnurbs
