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
#include "dynamics/deformable_superquadric_model.h"
#include "dynamics/integrator.h"

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
