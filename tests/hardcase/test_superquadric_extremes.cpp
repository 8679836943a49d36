// Hard cases, superquadrics: squareness exponents 0.1 and 4, bending at full strength, and a
// rigid body spinning at 100 rad/s.

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/integrators/rigid_body_integrator.h"
#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"
#include "hardcase_helpers.h"

namespace dnurbs {
namespace {

using hardcase::record_result;
using Shape = SuperquadricShapeParameter;

SuperquadricShapeParameters superellipsoid(double a1, double a2, double a3, double e1, double e2) {
  SuperquadricShapeParameters q = SuperquadricShapeParameters::Zero();
  q << 1.0, a1, a2, a3, e1, e2, 0, 0, 0, 0, 0, 0, 0, 0;
  return q;
}

struct VibrationRecord {
  double energy_change = 0.0;  // max |E(t) - E(0)| / E(0)
  double largest_coordinate = 0.0;
  double energy_gain = 0.0;  // max (E(t) - E(0)) / E(0)
};

// A free, undamped deformable superquadric (rigid motion and the global deformations free)
// released from `start` toward its rest shape `rest`, stepped 100 times at dt = 0.01 by newmark
// with Newton iterations.
VibrationRecord vibrate(const SuperquadricShapeParameters& start,
                        const SuperquadricShapeParameters& rest) {
  DeformableSuperquadricSettings settings;
  settings.parts = DeformableSuperquadricParts::global();
  settings.rest_shape = rest;
  const DeformableSuperquadricModel model(start, Eigen::Vector3d::Zero(),
                                          Eigen::Quaterniond::Identity(), settings);
  System system(model);
  IntegratorSettings integrator_settings;
  integrator_settings.newton_iterations = 10;
  integrator_settings.newton_tolerance = 1e-12;
  Integrator integrator(integrator_settings);
  const double energy0 = hardcase::total_energy(system);
  VibrationRecord record;
  for (int k = 0; k < 100; ++k) {
    integrator.step(system, 0.01);
    record.energy_change = std::max(record.energy_change,
                                    std::abs(hardcase::total_energy(system) - energy0) / energy0);
    record.largest_coordinate =
        std::max(record.largest_coordinate, system.coordinates().lpNorm<Eigen::Infinity>());
  }
  return record;
}

// Stable, in numbers (exponents and bending below): every step finite (the integrator throws
// otherwise), the total energy never above its start by more than 1e-8 relative (the O(dt^2)
// truncation of newmark with Newton on this non-linear model: 1.3e-9 measured for the full bend
// at dt = 0.01, 3e-10 at dt = 0.005), at most 10 % below it, and no coordinate beyond
// 10 (shape parameters are O(1)). Energy may be lost: the squareness bounds 0.1 and 4 are
// inelastic stops (DeformableSuperquadricModel::project_state), and at e = 4 a further
// dt-independent loss of 5e-4 is measured with the exponents held fixed.
void expect_bounded_vibration(const SuperquadricShapeParameters& start,
                              const SuperquadricShapeParameters& rest, const std::string& what,
                              double& worst) {
  const VibrationRecord record = vibrate(start, rest);
  std::printf("%s: max |dE|/E0 %.3e, max gain %.3e, max |q| %.3e\n", what.c_str(),
              record.energy_change, record.energy_gain, record.largest_coordinate);
  EXPECT_LE(record.energy_gain, 1e-8) << what;
  EXPECT_LE(record.energy_change, 0.1) << what;
  EXPECT_LE(record.largest_coordinate, 10.0) << what;
  worst = std::max(worst, record.energy_gain);
}

TEST(SuperquadricExtremes, SquarenessExponentsPointOneAndFourVibrateWithBoundedEnergy) {
  double worst = 0.0;
  for (const double e : {0.1, 4.0}) {
    SuperquadricShapeParameters rest = superellipsoid(1.0, 0.8, 1.2, e, e);
    rest[Shape::kBendFrequency] = 0.5;  // b3 = 0 would make b1 a translation
    SuperquadricShapeParameters start = rest;
    start[Shape::kAspect1] = 1.1;
    start[Shape::kTaper1] = 0.2;
    expect_bounded_vibration(start, rest, "exponents " + hardcase::format_number(e), worst);
  }
  record_result("max (E - E0)/E0 over 1 s, global superquadric with e1 = e2 = 0.1 and 4", worst,
                "<= 1e-8 (loss <= 10 %)");
}

TEST(SuperquadricExtremes, BendingAtFullStrengthVibratesWithBoundedEnergy) {
  // Full strength: the bend amplitude b1 equals the x semi-axis a a1 and b3 = 1 bends the body
  // through half a cosine wave over its height, so the centre line moves by the body's own
  // half-width; released from b1 = 1.2 a a1 toward it.
  double worst = 0.0;
  SuperquadricShapeParameters rest = superellipsoid(1.0, 0.8, 1.2, 0.8, 1.5);
  rest[Shape::kBendAmplitude] = 1.0;
  rest[Shape::kBendFrequency] = 1.0;
  SuperquadricShapeParameters start = rest;
  start[Shape::kBendAmplitude] = 1.2;
  expect_bounded_vibration(start, rest, "full bend", worst);
  record_result("max (E - E0)/E0 over 1 s, superquadric bent at b1 = a a1, b3 = 1", worst,
                "<= 1e-8 (loss <= 10 %)");
}

/// Spatial angular momentum about the world origin of a rigid model: m x_c x v_c + R I_c w.
Eigen::Vector3d angular_momentum(const DeformableSuperquadricModel& model, const Eigen::VectorXd& q,
                                 const Eigen::VectorXd& qd) {
  const RigidMassProperties& props = model.reference_mass_properties();
  const Eigen::Matrix3d rotation = model.orientation(q).toRotationMatrix();
  const Eigen::Vector3d omega = qd.segment<3>(3);
  const Eigen::Vector3d x = q.head<3>() + rotation * props.centre_of_mass;
  const Eigen::Vector3d v = qd.head<3>() + rotation * omega.cross(props.centre_of_mass);
  return props.mass * x.cross(v) + rotation * (props.inertia_about_centre * omega);
}

TEST(SuperquadricExtremes, SpinAtHundredRadiansPerSecondKeepsEnergyAndAngularMomentum) {
  // An asymmetric bent rigid superquadric (centre of mass off the body origin) spinning at
  // 100 rad/s about a tilted axis, stepped by the Lie midpoint rule for 1 s at dt = 1e-3
  // (0.1 rad per step, 16 turns). The scheme conserves kinetic energy and spatial angular
  // momentum exactly up to its Newton tolerance (1e-15) and round-off, which accumulates like
  // sqrt(steps) eps per step. Stable, in numbers: both relative drifts <= 1e-10 and the
  // quaternion stays unit to 1e-12.
  SuperquadricShapeParameters shape = superellipsoid(1.5, 1.0, 0.6, 0.7, 1.3);
  shape[Shape::kBendAmplitude] = 0.2;
  shape[Shape::kBendFrequency] = 0.5;
  const DeformableSuperquadricModel model(shape, Eigen::Vector3d(0.1, 0.2, 0.3),
                                          Eigen::Quaterniond::Identity());
  System system(model);
  Eigen::VectorXd qd(6);
  qd << 0.2, -0.1, 0.05, 10.0, 20.0, 97.5;  // |w| = 100.03 rad/s
  system.set_velocities(0, qd);
  const double energy0 = system.kinetic_energy();
  const Eigen::Vector3d momentum0 = angular_momentum(model, system.coordinates(), qd);
  RigidBodyIntegrator integrator;
  double energy_drift = 0.0;
  double momentum_drift = 0.0;
  double quaternion_error = 0.0;
  for (int k = 0; k < 1000; ++k) {
    integrator.step(system, 1e-3);
    energy_drift = std::max(energy_drift, std::abs(system.kinetic_energy() - energy0) / energy0);
    momentum_drift = std::max(
        momentum_drift,
        (angular_momentum(model, system.coordinates(), system.velocities()) - momentum0).norm() /
            momentum0.norm());
    quaternion_error = std::max(
        quaternion_error,
        std::abs(system.coordinates().segment<4>(model.quaternion_coordinate_offset()).norm() -
                 1.0));
  }
  std::printf("spin 100 rad/s: energy drift %.3e, angular momentum drift %.3e, |q| - 1 %.3e\n",
              energy_drift, momentum_drift, quaternion_error);
  EXPECT_LE(energy_drift, 1e-10);
  EXPECT_LE(momentum_drift, 1e-10);
  EXPECT_LE(quaternion_error, 1e-12);
  record_result("max relative energy / angular momentum drift, rigid spin 100 rad/s, 1 s",
                std::max(energy_drift, momentum_drift), "<= 1e-10");
}

}  // namespace
}  // namespace dnurbs
