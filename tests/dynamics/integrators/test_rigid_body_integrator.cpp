// Free rigid superquadrics: conservation of kinetic energy and angular momentum over 10 s of
// spin, and the tennis-racket effect (dynamics/integrators/rigid_body_integrator.h, and the general
// Integrator on the same model for comparison).

#include <chrono>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/integrators/rigid_body_integrator.h"
#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"
#include "tests/common/superquadric_test_helpers.h"

namespace dnurbs {
namespace {

using test::Shape;
using test::superellipsoid;

/// Spatial angular momentum about the world origin of a rigid model: m x_c x v_c + R I_c w.
Eigen::Vector3d rigid_angular_momentum(const DeformableSuperquadricModel& model,
                                       const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  const RigidMassProperties& props = model.reference_mass_properties();
  const Eigen::Matrix3d rotation = model.orientation(q).toRotationMatrix();
  const Eigen::Vector3d omega = qd.segment<3>(3);
  const Eigen::Vector3d x = q.head<3>() + rotation * props.centre_of_mass;
  const Eigen::Vector3d v = qd.head<3>() + rotation * omega.cross(props.centre_of_mass);
  return props.mass * x.cross(v) + rotation * (props.inertia_about_centre * omega);
}

/// An asymmetric rigid body with its centre of mass off the body origin (bent), spinning and
/// drifting.
System spinning_body() {
  SuperquadricShapeParameters shape = superellipsoid(1.0, 1.5, 1.0, 0.6, 0.7, 1.3);
  shape[Shape::kBendAmplitude] = 0.2;
  shape[Shape::kBendFrequency] = 0.5;
  const DeformableSuperquadricModel model(
      shape, Eigen::Vector3d(0.1, 0.2, 0.3),
      Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized())));
  System system(model);
  Eigen::VectorXd qd(6);
  qd << 0.2, -0.1, 0.05, 0.4, 2.0, -0.3;
  system.set_velocities(0, qd);
  return system;
}

struct Drift {
  double energy = 0.0;
  double momentum = 0.0;
};

template <typename Step>
Drift spin_drift(System system, double dt, double duration, Step&& step) {
  const auto& model = dynamic_cast<const DeformableSuperquadricModel&>(system.model(0));
  const double energy0 = system.kinetic_energy();
  const Eigen::Vector3d momentum0 =
      rigid_angular_momentum(model, system.coordinates(), system.velocities());
  Drift drift;
  const int steps = static_cast<int>(std::lround(duration / dt));
  for (int i = 0; i < steps; ++i) {
    step(system, dt);
    drift.energy = std::max(drift.energy, std::abs(system.kinetic_energy() - energy0) / energy0);
    drift.momentum = std::max(
        drift.momentum,
        (rigid_angular_momentum(model, system.coordinates(), system.velocities()) - momentum0)
                .norm() /
            momentum0.norm());
  }
  return drift;
}

TEST(RigidSuperquadric, SteppingCostsASixBySixSystem) {
  System system = spinning_body();
  EXPECT_EQ(system.velocity_count(), 6);
  ModelMatrices matrices;
  system.assemble_matrices(system.coordinates(), matrices);
  EXPECT_EQ(matrices.mass.rows(), 6);
  EXPECT_EQ(matrices.mass.cols(), 6);
  EXPECT_FALSE(system.matrices_are_constant());  // M depends on the rotation (c-w coupling)
}

TEST(RigidSuperquadric, SteppingDoesNotIntegrateOverTheSurface) {
  // 32 x 32 points in each of 8 x 16 cells: 131072 quadrature points, integrated once at
  // construction. If a step integrated over them, 1000 Newmark steps (with Newton iterations:
  // several M, g and f_int evaluations each) would take tens of seconds; from the precomputed
  // mass properties they take milliseconds. The 2 s bound leaves a wide margin for a loaded
  // machine.
  DeformableSuperquadricSettings settings;
  settings.quadrature_points = 32;
  const DeformableSuperquadricModel model(superellipsoid(1.0, 1.5, 1.0, 0.6, 0.7, 1.3),
                                          Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(),
                                          settings);
  ASSERT_EQ(model.quadrature_points().size(), 131072u);
  System system(model);
  Eigen::VectorXd qd(6);
  qd << 0.0, 0.0, 0.0, 0.4, 2.0, -0.3;
  system.set_velocities(0, qd);
  IntegratorSettings integrator_settings;
  integrator_settings.newton_iterations = 3;
  Integrator integrator(integrator_settings);
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < 1000; ++i) {
    integrator.step(system, 0.01);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "1000 newmark steps (3 Newton iterations) of a rigid superquadric with 131072 "
            << "quadrature points: " << seconds << " s\n";
  EXPECT_LT(seconds, 2.0);
}

TEST(RigidSuperquadric, NewmarkWithNewtonKeepsEnergyAndMomentumOnlyToTruncationError) {
  // The general integrator on the same free spin, for comparison: average-acceleration Newmark
  // with Newton iterations is the trapezoidal rule, which does not conserve the quadratic
  // invariants of Euler's equations exactly; its drift falls as dt^2 (measured, reported).
  IntegratorSettings settings;
  settings.scheme = IntegratorScheme::kNewmark;
  settings.newton_iterations = 20;
  settings.newton_tolerance = 1e-13;
  Drift previous;
  for (const double dt : {0.01, 0.005}) {
    Integrator integrator(settings);
    const Drift drift =
        spin_drift(spinning_body(), dt, 10.0, [&](System& s, double h) { integrator.step(s, h); });
    std::cout << "newmark + Newton, dt = " << dt << ", 10 s: relative energy drift " << drift.energy
              << ", angular momentum drift " << drift.momentum << "\n";
    // Trapezoidal truncation: O((w dt)^2) with |w| ~ 2: a few 1e-4 at dt = 0.01.
    EXPECT_LT(drift.energy, 1e-2);
    EXPECT_LT(drift.momentum, 1e-2);
    if (previous.energy > 0.0) {
      // Halving dt divides the drift by about 4 (second order); allow 3.
      EXPECT_LT(drift.energy, previous.energy / 3.0);
    }
    previous = drift;
  }
}

TEST(RigidSuperquadric, LieMidpointConservesEnergyAndAngularMomentumOverTenSeconds) {
  RigidBodyIntegrator integrator;
  const Drift drift =
      spin_drift(spinning_body(), 0.01, 10.0, [&](System& s, double h) { integrator.step(s, h); });
  std::cout << "Lie midpoint (Cayley), dt = 0.01, 10 s: relative energy drift " << drift.energy
            << ", angular momentum drift " << drift.momentum << "\n";
  // Exact invariants of the scheme: only the Newton tolerance (1e-15) and round-off over 1000
  // steps remain.
  EXPECT_LT(drift.energy, 1e-8);
  EXPECT_LT(drift.momentum, 1e-8);
}

TEST(RigidSuperquadric, LinearMomentumIsConservedAndCentreOfMassMovesUniformly) {
  System system = spinning_body();
  const auto& model = dynamic_cast<const DeformableSuperquadricModel&>(system.model(0));
  const Eigen::Vector3d x0 = model.centre_of_mass(system.coordinates());
  const Eigen::Vector3d p0 = model.linear_momentum(system.coordinates(), system.velocities());
  RigidBodyIntegrator integrator;
  for (int i = 0; i < 200; ++i) {
    integrator.step(system, 0.01);
  }
  const double mass = model.reference_mass_properties().mass;
  const Eigen::Vector3d x = model.centre_of_mass(system.coordinates());
  const Eigen::Vector3d p = model.linear_momentum(system.coordinates(), system.velocities());
  // Momenta by the model's quadrature (independent of the integrator's centre-of-mass state):
  // round-off only.
  EXPECT_LT((p - p0).norm(), 1e-12 * p0.norm());
  EXPECT_LT((x - (x0 + 2.0 * p0 / mass)).norm(), 1e-12);
}

/// First time the spin component about `axis` changes sign (or -1), and the smallest ratio of
/// that component to its initial value, over `duration` seconds.
struct FlipResult {
  double flip_time = -1.0;
  double smallest_ratio = 1.0;
};

FlipResult spin_about(int axis, double duration) {
  // Ellipsoid shell with semi-axes (1.5, 1, 0.6): smallest moment about x, largest about z,
  // intermediate about y.
  const DeformableSuperquadricModel model(superellipsoid(1.0, 1.5, 1.0, 0.6, 1.0, 1.0));
  System system(model);
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(6);
  qd.tail<3>() = Eigen::Vector3d::Constant(1e-3);  // the perturbation
  qd[3 + axis] = 5.0;
  system.set_velocities(0, qd);
  RigidBodyIntegrator integrator;
  FlipResult result;
  const double dt = 0.005;
  for (int i = 0; i < static_cast<int>(duration / dt); ++i) {
    integrator.step(system, dt);
    const double ratio = system.velocities()[3 + axis] / 5.0;
    result.smallest_ratio = std::min(result.smallest_ratio, ratio);
    if (ratio < 0.0 && result.flip_time < 0.0) {
      result.flip_time = system.time();
    }
  }
  return result;
}

TEST(RigidSuperquadric, SpinAboutIntermediateAxisFlipsWhileMajorAndMinorAxesAreStable) {
  const DeformableSuperquadricModel model(superellipsoid(1.0, 1.5, 1.0, 0.6, 1.0, 1.0));
  const Eigen::Vector3d moments = model.reference_mass_properties().inertia_about_centre.diagonal();
  ASSERT_LT(moments.x(), moments.y());
  ASSERT_LT(moments.y(), moments.z());
  const FlipResult intermediate = spin_about(1, 20.0);
  const FlipResult minor = spin_about(0, 20.0);
  const FlipResult major = spin_about(2, 20.0);
  // Linearized growth rate of the perturbation about the intermediate axis.
  const double rate = 5.0 * std::sqrt((moments.y() - moments.x()) * (moments.z() - moments.y()) /
                                      (moments.x() * moments.z()));
  std::cout << "tennis racket: intermediate axis flips at t = " << intermediate.flip_time
            << " s (growth rate " << rate << " /s, ln(5/1e-3)/rate = " << std::log(5e3) / rate
            << " s); smallest spin ratio about the minor axis " << minor.smallest_ratio
            << ", major axis " << major.smallest_ratio << "\n";
  EXPECT_GT(intermediate.flip_time, 0.0);
  EXPECT_LT(intermediate.smallest_ratio, -0.9);  // turned (nearly) all the way over
  // Stable axes: the 1e-3 perturbation only nutates, the spin stays within 1e-3 relative.
  EXPECT_GT(minor.smallest_ratio, 0.99);
  EXPECT_GT(major.smallest_ratio, 0.99);
  EXPECT_LT(minor.flip_time, 0.0);
  EXPECT_LT(major.flip_time, 0.0);
}

}  // namespace
}  // namespace dnurbs
