// Multibody assembly with superquadric parts (seed 001 eqs 1.39-1.40): an articulated figure
// assembled from misplaced, rotated (and, with global deformations on, misshaped) parts.
#include <cmath>
#include <iostream>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "constraints/constraint_solver.h"
#include "constraints/point_constraints.h"
#include "dynamics/superquadric/deformable_superquadric_model.h"
#include "dynamics/core/forces.h"
#include "dynamics/integrators/integrator.h"

namespace dnurbs {
namespace {

const double kHalfPi = 0.5 * std::numbers::pi;
const Eigen::Vector2d kTopPole(kHalfPi, 0.0);      // body point (0, 0, a a3)
const Eigen::Vector2d kBottomPole(-kHalfPi, 0.0);  // body point (0, 0, -a a3)

SuperquadricShapeParameters ellipsoid(double a1, double a2, double a3) {
  SuperquadricShapeParameters q = SuperquadricShapeParameters::Zero();
  q << 1.0, a1, a2, a3, 1.0, 1.0, 0, 0, 0, 0, 0, 0, 0, 0;
  return q;
}

// Total energy of rigid parts under gravity g: kinetic plus sum m (-g . c) (the parts are
// symmetric, so the centre of mass is the model's centre c).
double total_energy(const System& system, const Eigen::Vector3d& g) {
  double energy = system.kinetic_energy();
  for (int i = 0; i < system.model_count(); ++i) {
    const auto& part = dynamic_cast<const DeformableSuperquadricModel&>(system.model(i));
    energy -= part.reference_mass_properties().mass * g.dot(system.coordinates(i).head<3>());
  }
  return energy;
}

TEST(Multibody, PendulumChainOfTenRigidPartsConservesEnergy) {
  // Ten slender ellipsoids (half length 0.25) hanging from a pivot, released from 40 degrees off
  // the vertical as one straight rod. Ball joints join the bottom pole of each part to the top
  // pole of the next; the first top pole is held at the pivot. No damping.
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  const double angle = 40.0 * std::numbers::pi / 180.0;
  const Eigen::Vector3d down(std::sin(angle), 0.0, -std::cos(angle));
  const Eigen::Quaterniond orientation =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), -down);
  System system;
  for (int i = 0; i < 10; ++i) {
    const DeformableSuperquadricModel part(ellipsoid(0.08, 0.08, 0.25), (0.5 * i + 0.25) * down,
                                           orientation);
    // Gravity on a rigid symmetric part is m g at its centre: a force on the translation
    // coordinates (the distributed form would integrate over the surface every evaluation).
    const double weight = part.reference_mass_properties().mass * g.z();
    system.add_model(part);
    system.add_force(i, coordinate_force({2}, [weight](double) { return weight; }));
  }
  ConstraintSolver solver;
  BaumgarteParameters parameters;
  parameters.alpha = 10.0;
  solver.add(system,
             PointTargetConstraint(0, kTopPole, TargetTrajectory::fixed(Eigen::Vector3d::Zero())),
             parameters);
  for (int i = 0; i + 1 < 10; ++i) {
    solver.add(system, PointToPointConstraint(i, kBottomPole, i + 1, kTopPole), parameters);
  }
  // Rotating joints are non-linear in q: Baumgarte alone leaves a violation of ~1e-5 here
  // (measured with alpha 10 and 40), so the state is projected back after each step.
  solver.set_projection(true, 1e-12);
  IntegratorSettings settings;
  settings.newton_iterations = 4;
  settings.newton_tolerance = 1e-12;
  Integrator integrator(settings);
  const double initial = total_energy(system, g);
  const double scale = std::abs(initial);
  double worst_drift = 0.0;
  double worst_violation = 0.0;
  const double dt = 2.5e-3;
  for (int k = 0; k < 4000; ++k) {  // 10 s
    solver.step(integrator, system, dt);
    worst_drift = std::max(worst_drift, std::abs(total_energy(system, g) - initial) / scale);
    worst_violation = std::max(worst_violation, solver.max_violation(system));
  }
  std::cout << "pendulum chain, 10 s: energy drift " << worst_drift << ", violation "
            << worst_violation << "\n";
  EXPECT_LT(worst_drift, 1e-4);
  EXPECT_LT(worst_violation, 1e-6);
  // The chain did swing: the lowest part moved far from where it started.
  EXPECT_GT((system.coordinates(9).head<3>() - 4.75 * down).norm(), 0.5);
}

// An articulated figure: torso, head, two arms (ball joints), two legs (hinges), each part
// started misplaced and rotated; damping brings the assembly to rest.
void assemble_figure(DeformableSuperquadricParts parts, double* violation, double* speed) {
  DeformableSuperquadricSettings settings;
  settings.parts = parts;
  settings.damping_alpha = 2.0;
  settings.mesh_cells_u = 4;
  settings.mesh_cells_v = 8;
  settings.quadrature_points = 2;
  const auto part = [&](const SuperquadricShapeParameters& shape, const Eigen::Vector3d& centre,
                        double angle, const Eigen::Vector3d& axis) {
    return DeformableSuperquadricModel(
        shape, centre, Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())), settings);
  };
  System system;
  // Torso: a1 = 0.3 (x), a2 = 0.2 (y), a3 = 0.5 (z). Each leg hangs from a hinge through two
  // torso points at u = -1 and v = v0 -+ 0.2; the leg's half length a3 is half their distance,
  // so the hinge's two point pairs are consistent.
  const auto torso_point = [](double u, double v) {
    return Eigen::Vector3d(0.3 * std::cos(u) * std::cos(v), 0.2 * std::cos(u) * std::sin(v),
                           0.5 * std::sin(u));
  };
  const auto leg_half_length = [&](double v0) {
    return 0.5 * (torso_point(-1.0, v0 - 0.2) - torso_point(-1.0, v0 + 0.2)).norm();
  };
  const double left_v = std::numbers::pi - 0.5;
  const double right_v = 0.5;
  const int torso =
      system.add_model(part(ellipsoid(0.3, 0.2, 0.5), {0.1, -0.1, 0.05}, 0.3, {1, 2, 0}));
  const int head =
      system.add_model(part(ellipsoid(0.15, 0.15, 0.15), {0.2, 0.3, 0.9}, 0.8, {0, 1, 1}));
  const int left_arm =
      system.add_model(part(ellipsoid(0.08, 0.08, 0.3), {-0.7, 0.2, 0.2}, 1.0, {1, 0, 0}));
  const int right_arm =
      system.add_model(part(ellipsoid(0.08, 0.08, 0.3), {0.8, -0.3, 0.1}, -0.7, {0, 1, 0}));
  const int left_leg = system.add_model(
      part(ellipsoid(0.05, 0.05, leg_half_length(left_v)), {-0.4, 0.1, -0.8}, 0.5, {1, 1, 1}));
  const int right_leg = system.add_model(
      part(ellipsoid(0.05, 0.05, leg_half_length(right_v)), {0.5, 0.2, -0.9}, -0.4, {1, 0, 1}));
  ConstraintSolver solver;
  BaumgarteParameters parameters;
  parameters.alpha = 5.0;
  solver.add(system, PointToPointConstraint(torso, kTopPole, head, kBottomPole), parameters);
  solver.add(
      system,
      PointToPointConstraint(torso, Eigen::Vector2d(0.8, std::numbers::pi), left_arm, kTopPole),
      parameters);
  solver.add(system, PointToPointConstraint(torso, Eigen::Vector2d(0.8, 0.0), right_arm, kTopPole),
             parameters);
  // Hinges about the y axis: the torso's side points at height u = -1.0 and the leg's poles.
  for (const auto& [leg, v] : {std::pair{left_leg, left_v}, std::pair{right_leg, right_v}}) {
    solver.add(system,
               HingeConstraint(torso, Eigen::Vector2d(-1.0, v - 0.2),
                               Eigen::Vector2d(-1.0, v + 0.2), leg, kTopPole, kBottomPole),
               parameters);
  }
  IntegratorSettings integrator_settings;
  integrator_settings.scheme = IntegratorScheme::kImplicitEuler;
  integrator_settings.newton_iterations = 3;
  Integrator integrator(integrator_settings);
  for (int k = 0; k < 1500; ++k) {
    solver.step(integrator, system, 0.01);
  }
  *violation = solver.max_violation(system);
  *speed = system.velocities().cwiseAbs().maxCoeff();
}

TEST(Multibody, MisplacedRigidFigureAssemblesAndComesToRest) {
  double violation = 0.0;
  double speed = 0.0;
  assemble_figure(DeformableSuperquadricParts::rigid(), &violation, &speed);
  std::cout << "rigid figure: violation " << violation << ", largest speed " << speed << "\n";
  // Parts are about 1 in size: the violation is relative to it.
  EXPECT_LT(violation, 1e-8);
  EXPECT_LT(speed, 1e-4);
}

TEST(Multibody, MisplacedDeformableFigureAssemblesAndComesToRest) {
  double violation = 0.0;
  double speed = 0.0;
  assemble_figure(DeformableSuperquadricParts::global(), &violation, &speed);
  std::cout << "deformable figure: violation " << violation << ", largest speed " << speed << "\n";
  EXPECT_LT(violation, 1e-8);
  EXPECT_LT(speed, 1e-4);
}

}  // namespace
}  // namespace dnurbs
