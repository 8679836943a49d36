// Deformable superquadrics under the general Integrator: release from a spring returns the rest
// shape with non-increasing energy, and internal forces leave the momenta unchanged.

#include <algorithm>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "dnurbs/constraints/constraint_solver.h"
#include "dnurbs/constraints/point_constraints.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"
#include "tests/common/superquadric_test_helpers.h"

namespace dnurbs {
namespace {

using test::pattern_vector;
using test::superellipsoid;

DeformableSuperquadricSettings small_full_settings() {
  DeformableSuperquadricSettings settings;
  settings.parts = DeformableSuperquadricParts::full();
  settings.mesh_cells_u = 4;
  settings.mesh_cells_v = 8;
  settings.quadrature_points = 2;
  settings.shape_stiffness = SuperquadricShapeParameters::Constant(20.0);
  settings.local_stiffness = {2.0, 2.0, 20.0};
  return settings;
}

/// Distance of a state from the rest shape: |q_s - rest| + |q_d| (infinity norms).
double shape_distance(const DeformableSuperquadricModel& model, const Eigen::VectorXd& q) {
  const double global = (model.shape_parameters(q) - model.rest_shape()).lpNorm<Eigen::Infinity>();
  const double local = q.segment(model.local_coordinate_offset(), model.mesh().coordinate_count())
                           .lpNorm<Eigen::Infinity>();
  return global + local;
}

TEST(DeformableSuperquadric, PulledBySpringThenReleasedReturnsToRestWithEnergyNeverIncreasing) {
  DeformableSuperquadricSettings settings = small_full_settings();
  settings.damping_alpha = 2.0;
  settings.damping_beta = 0.05;
  const DeformableSuperquadricModel model(superellipsoid(1.0, 1.0, 0.8, 1.2, 0.8, 1.5),
                                          Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(),
                                          settings);
  System system(model);
  // A spring pulls the material point u = (0.3, 0.5) toward a target that moves 0.4 outwards
  // over 0.5 s and then rests, for 1 s.
  const Eigen::Vector2d grip(0.3, 0.5);
  const Eigen::Vector3d start = model.position(model.initial_coordinates(), grip);
  const Eigen::Vector3d direction = start.normalized();
  system.add_force(0, spring_force(
                          grip,
                          [start, direction](double t) -> Eigen::Vector3d {
                            return start + 0.4 * std::min(t / 0.5, 1.0) * direction;
                          },
                          50.0));
  IntegratorSettings integrator_settings;
  integrator_settings.newton_iterations = 4;
  integrator_settings.newton_tolerance = 1e-10;
  Integrator integrator(integrator_settings);
  const double dt = 0.01;
  for (int i = 0; i < 100; ++i) {
    integrator.step(system, dt);
  }
  const auto& stepped = dynamic_cast<const DeformableSuperquadricModel&>(system.model(0));
  const double pulled = shape_distance(stepped, system.coordinates());
  // Release: no applied force from here on, only damping.
  system.clear_forces();
  double energy = system.kinetic_energy() + system.potential_energy();
  const double released_energy = energy;
  double largest_increase = 0.0;
  for (int i = 0; i < 600; ++i) {
    integrator.step(system, dt);
    const double next = system.kinetic_energy() + system.potential_energy();
    largest_increase = std::max(largest_increase, (next - energy) / released_energy);
    energy = next;
  }
  const double final_distance = shape_distance(stepped, system.coordinates());
  std::cout << "spring release: shape distance pulled " << pulled << ", after 6 s "
            << final_distance << "; energy " << released_energy << " -> " << energy
            << ", largest relative step increase " << largest_increase << "\n";
  EXPECT_GT(pulled, 1e-2);
  // Damped decay e^{-alpha t / 2} over 6 s: ~e^-6, plus the slowest K-damped local modes.
  EXPECT_LT(final_distance, 1e-2 * pulled);
  EXPECT_LT(energy, 1e-3 * released_energy);
  // Never increases (Newton converged to 1e-10: a relative slack of 1e-9 for its residual).
  EXPECT_LE(largest_increase, 1e-9);
}

struct MomentumDrift {
  double linear = 0.0;   ///< largest |P| (the initial P is 0)
  double angular = 0.0;  ///< largest |L| about the origin (initially 0)
  double shift = 0.0;    ///< largest centre-of-mass displacement
  double scale = 0.0;    ///< m * largest speed of a coordinate * size
};

/// Starts deformed (q_s off rest and, with `local`, random local displacements) and at rest,
/// free and undamped: the internal forces set the shape vibrating while the centre of mass
/// should stay put and both momenta stay zero.
MomentumDrift momentum_drift(bool local, double dt, double duration) {
  DeformableSuperquadricSettings settings = small_full_settings();
  settings.parts.local = local;
  SuperquadricShapeParameters rest = superellipsoid(1.0, 1.0, 0.8, 1.2, 0.8, 1.5);
  rest[test::Shape::kBendFrequency] = 0.5;  // b3 = 0 would make b1 a translation
  settings.rest_shape = rest;
  SuperquadricShapeParameters start = rest;
  start[test::Shape::kAspect1] = 1.2;
  start[test::Shape::kTaper1] = 0.2;
  start[test::Shape::kBendAmplitude] = 0.15;
  const DeformableSuperquadricModel model(start, Eigen::Vector3d(0.5, 0.0, 0.0),
                                          test::some_rotation(), settings);
  System system(model);
  Eigen::VectorXd q = model.initial_coordinates();
  if (local) {
    const int nd = model.mesh().coordinate_count();
    q.segment(model.local_coordinate_offset(), nd) = 0.05 * pattern_vector(nd, 4.0);
  }
  system.set_coordinates(0, q);
  const Eigen::Vector3d centre0 = model.centre_of_mass(q);
  const double size = 1.2;
  IntegratorSettings integrator_settings;
  integrator_settings.newton_iterations = 10;
  integrator_settings.newton_tolerance = 1e-12;
  Integrator integrator(integrator_settings);
  MomentumDrift drift;
  double largest_velocity = 0.0;
  const int steps = static_cast<int>(std::lround(duration / dt));
  for (int i = 0; i < steps; ++i) {
    integrator.step(system, dt);
    const Eigen::VectorXd& qi = system.coordinates();
    const Eigen::VectorXd& vi = system.velocities();
    drift.linear = std::max(drift.linear, model.linear_momentum(qi, vi).norm());
    drift.angular = std::max(drift.angular, model.angular_momentum(qi, vi).norm());
    drift.shift = std::max(drift.shift, (model.centre_of_mass(qi) - centre0).norm());
    largest_velocity = std::max(largest_velocity, vi.lpNorm<Eigen::Infinity>());
  }
  drift.scale = model.reference_mass_properties().mass * largest_velocity * size;
  std::cout << "internal forces only (" << (local ? "global + local" : "global") << "), dt = " << dt
            << ", " << duration << " s: largest |P| / (m v l) " << drift.linear / drift.scale
            << ", |L| / (m v l) " << drift.angular / drift.scale << ", centre of mass shift "
            << drift.shift << " (size " << size << ")\n";
  return drift;
}

TEST(DeformableSuperquadric, InternalForcesLeaveMomentaUnchangedUpToSecondOrderTruncation) {
  // The continuous equations conserve P and L exactly (f_int has no c or w part, and T is
  // invariant under rigid motions; see the model tests). Newmark (the trapezoidal rule with a
  // state-dependent M) conserves them only to O(dt^2): halving dt divides the drift by ~4.
  const MomentumDrift coarse = momentum_drift(false, 0.01, 0.5);
  const MomentumDrift fine = momentum_drift(false, 0.005, 0.5);
  EXPECT_LT(fine.linear, coarse.linear / 3.0);
  EXPECT_LT(fine.angular, coarse.angular / 3.0);
  // Measured ~1e-6 relative at dt = 0.005.
  EXPECT_LT(fine.linear, 1e-5 * fine.scale);
  EXPECT_LT(fine.angular, 1e-5 * fine.scale);
  EXPECT_LT(fine.shift, 1e-5);
}

TEST(DeformableSuperquadric, LocalDeformationAloneDoesNotMoveTheCentreOfMass) {
  // With local displacements the redundant uniform-d direction (regularized, default 1e-3)
  // vibrates fast; the drift stays at the scheme's truncation level.
  const MomentumDrift drift = momentum_drift(true, 0.005, 0.5);
  EXPECT_LT(drift.linear, 1e-3 * drift.scale);
  EXPECT_LT(drift.angular, 1e-3 * drift.scale);
  EXPECT_LT(drift.shift, 1e-4);
}

// ----------------------------------------------------------------------------------------------
// The D-NURBS forces (gravity, point force, spring) and the point constraints act on deformable
// superquadrics unchanged, through L^T and the Model contract.

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
  // Baumgarte-stabilized acceleration-level constraint: drift O(dt^2) per step, corrected.
  EXPECT_LT(largest_violation, 1e-4);
  EXPECT_LT(lowest, -0.05);  // it swung down
  EXPECT_TRUE(system.coordinates().allFinite());
}

}  // namespace
}  // namespace dnurbs
