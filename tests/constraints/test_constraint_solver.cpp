// Baumgarte stabilization (Terzopoulos 2003, eq. 1.40) inside the integrators, and the redundant
// and conflicting cases.

#include "dnurbs/constraints/constraint_solver.h"

#include <cmath>
#include <iostream>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "dnurbs/constraints/point_constraints.h"
#include "dnurbs/constraints/surface_constraints.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"
#include "dnurbs/nurbs/knot_vector.h"
#include "tests/common/constraint_test_scenes.h"

namespace dnurbs {
namespace {

// A free D-NURBS curve (no forces, no damping) whose point at u = 0.5 is held at a target
// `offset` away from where it is: the violation obeys Cddot + 2 alpha Cdot + alpha^2 C = 0, so
// C(t) = C0 (1 + alpha t) exp(-alpha t). Returns the largest error of |C| against the formula
// at t = 0.05, 0.1, 0.2, 0.4.
double baumgarte_error(double alpha, double dt, IntegratorScheme scheme) {
  DNurbsCurveMaterial material;
  material.tension = 1.0;
  System system(DNurbsCurve(testing::curve_over_patch(false), material));
  const Eigen::Vector2d u(0.5, 0.0);
  const Eigen::Vector3d offset(0.03, -0.02, 0.04);
  const TargetTrajectory target = TargetTrajectory::fixed(system.position(0, u) + offset);
  ConstraintSolver solver;
  BaumgarteParameters parameters;
  parameters.alpha = alpha;
  solver.add(system, PointTargetConstraint(0, u, target), parameters);
  IntegratorSettings settings;
  settings.scheme = scheme;
  Integrator integrator(settings);
  double worst = 0.0;
  const double initial = offset.norm();
  int checkpoint = 0;
  const std::array<double, 4> times = {0.05, 0.1, 0.2, 0.4};
  const int steps = static_cast<int>(std::lround(0.4 / dt));
  for (int k = 1; k <= steps; ++k) {
    solver.step(integrator, system, dt);
    if (std::abs(system.time() - times[static_cast<size_t>(checkpoint)]) < 0.5 * dt) {
      const double t = system.time();
      const double expected = initial * (1.0 + alpha * t) * std::exp(-alpha * t);
      worst = std::max(worst, std::abs(solver.max_violation(system) - expected));
      ++checkpoint;
    }
  }
  EXPECT_EQ(checkpoint, 4);
  return worst;
}

TEST(Baumgarte, CriticallyDampedViolationFollowsTheClosedForm) {
  for (double alpha : {10.0, 30.0}) {
    for (IntegratorScheme scheme : {IntegratorScheme::kImplicitEuler, IntegratorScheme::kNewmark}) {
      const double coarse = baumgarte_error(alpha, 2e-3, scheme);
      const double fine = baumgarte_error(alpha, 1e-3, scheme);
      // The end-of-step condition discretizes the violation ODE with the scheme's own accuracy:
      // first order at least, so halving dt at least nearly halves the error ...
      EXPECT_LT(fine, 0.6 * coarse) << "alpha " << alpha;
      // ... and at dt = 1e-3 the error is a small fraction of C0 = 0.054 (alpha dt <= 0.03).
      EXPECT_LT(fine, 0.02 * 0.054) << "alpha " << alpha << " scheme " << to_string(scheme);
    }
  }
}

TEST(Baumgarte, SculptedSurfaceKeepsPointsAndNormalConstrained) {
  // A D-NURBS surface pulled by a moving mouse spring while 3 surface points are pinned and one
  // normal is held where it was. Point constraints of a fixed-weight surface are linear in q, so
  // the end-of-step condition holds them to rounding; the normal is quadratic in q, and two
  // Newton iterations per step remove its linearization error.
  DNurbsSurfaceMaterial material;
  material.a10 = material.a01 = 1.0;
  material.b20 = material.b02 = 0.1;
  material.damping_density = 0.5;
  // The border control points are clamped (eliminated), as in sculpting: without them the
  // membrane energy, which has no rest shape, would shrink the patch to a degenerate one.
  DNurbsSurface surface(testing::curved_patch(false), material);
  surface.fix_border();
  System system(surface);
  const std::array<Eigen::Vector2d, 3> pinned = {
      Eigen::Vector2d(0.25, 0.3), Eigen::Vector2d(0.75, 0.25), Eigen::Vector2d(0.5, 0.8)};
  ConstraintSolver solver;
  for (const auto& uv : pinned) {
    solver.add(system,
               PointTargetConstraint(0, uv, TargetTrajectory::fixed(system.position(0, uv))));
  }
  const Eigen::Vector2d normal_at(0.3, 0.6);
  const NurbsSurface initial = testing::curved_patch(false);
  solver.add(system, SurfaceNormalConstraint(0, normal_at, initial.unit_normal(0.3, 0.6)));
  system.add_force(
      0, spring_force(
             Eigen::Vector2d(0.6, 0.45),
             [](double t) { return Eigen::Vector3d(0.6 + 0.2 * t, 0.45, 0.5 * t); }, 20.0));
  IntegratorSettings settings;
  settings.newton_iterations = 2;
  Integrator integrator(settings);
  const Eigen::Vector3d start = system.position(0, Eigen::Vector2d(0.6, 0.45));
  double worst = 0.0;
  for (int k = 0; k < 200; ++k) {
    solver.step(integrator, system, 0.01);
    worst = std::max(worst, solver.max_violation(system));
  }
  EXPECT_LT(worst, 1e-8);
  // The surface did move where the spring pulls it.
  EXPECT_GT((system.position(0, Eigen::Vector2d(0.6, 0.45)) - start).norm(), 0.05);
  EXPECT_FALSE(solver.last_report().rank_deficient);
}

TEST(Baumgarte, ConstraintAddedTwiceIsReportedAndStepsStayFinite) {
  DNurbsCurveMaterial material;
  material.tension = 1.0;
  System system(DNurbsCurve(testing::curve_over_patch(false), material));
  const Eigen::Vector2d u(0.5, 0.0);
  const PointTargetConstraint pin(
      0, u, TargetTrajectory::fixed(system.position(0, u) + Eigen::Vector3d(0.02, 0, 0)));
  ConstraintSolver solver;
  solver.add(system, pin);
  solver.add(system, pin);
  Integrator integrator;
  for (int k = 0; k < 300; ++k) {
    solver.step(integrator, system, 1e-2);
  }
  EXPECT_TRUE(solver.last_report().rank_deficient);
  EXPECT_EQ(solver.last_report().rank, 3);
  EXPECT_EQ(solver.last_report().involved, (std::vector<int>{0, 1}));
  EXPECT_NE(solver.last_report().message.find("rank deficient"), std::string::npos);
  EXPECT_TRUE(system.coordinates().allFinite());
  EXPECT_TRUE(solver.multipliers().allFinite());
  // Redundant but consistent: the point still reaches its target.
  EXPECT_LT(solver.max_violation(system), 1e-6);
}

TEST(Baumgarte, ConflictingTargetsGiveAFiniteLeastSquaresMotion) {
  DNurbsCurveMaterial material;
  material.tension = 1.0;
  System system(DNurbsCurve(testing::curve_over_patch(false), material));
  const Eigen::Vector2d u(0.5, 0.0);
  const Eigen::Vector3d here = system.position(0, u);
  ConstraintSolver solver;
  solver.add(system, PointTargetConstraint(
                         0, u, TargetTrajectory::fixed(here + Eigen::Vector3d(0.1, 0, 0))));
  solver.add(system, PointTargetConstraint(
                         0, u, TargetTrajectory::fixed(here - Eigen::Vector3d(0.1, 0, 0))));
  Integrator integrator;
  for (int k = 0; k < 300; ++k) {
    solver.step(integrator, system, 1e-2);
  }
  EXPECT_TRUE(solver.last_report().rank_deficient);
  EXPECT_EQ(solver.last_report().involved, (std::vector<int>{0, 1}));
  EXPECT_TRUE(system.coordinates().allFinite());
  // The least-squares compromise is the midpoint: both violations equal 0.1.
  const Eigen::VectorXd violations = solver.violations(system);
  EXPECT_NEAR(violations[0], 0.1, 1e-6);
  EXPECT_NEAR(violations[1], 0.1, 1e-6);
  EXPECT_GT(solver.rank_deficient_steps(), 0);
}

// ----------------------------------------------------------------------------------------------
// A point-to-point constraint couples a constant D-NURBS sheet and a state-dependent deformable
// superquadric that the integrator factors block by block: the constraint solver's Schur
// complement goes through the per-block solve hook, the joint holds, the sheet's block is still
// factored once and the sheet carries the superquadric's weight through the joint alone.

// A flat bicubic 6 x 6 patch over [0, 1]^2 at z = 0.
NurbsSurface flat_sheet() {
  const KnotVector knots = KnotVector::clamped_uniform(3, 6);
  Eigen::MatrixX3d points(36, 3);
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      points.row(i * 6 + j) << i / 5.0, j / 5.0, 0.0;
    }
  }
  return NurbsSurface(knots, knots, points);
}

TEST(BlockConstraintCoupling, SuperquadricHangsFromAClampedSheetByABallJoint) {
  DNurbsSurfaceMaterial material;
  material.damping_density = 0.5;
  material.a10 = 2.0;
  material.a01 = 2.0;
  DNurbsSurface sheet(flat_sheet(), material);
  sheet.fix_border();
  // An ellipsoid (global deformations free) whose north pole sits at the sheet's centre.
  SuperquadricShapeParameters shape = SuperquadricShapeParameters::Zero();
  shape << 1.0, 0.15, 0.15, 0.25, 1.0, 1.0, 0, 0, 0, 0, 0, 0, 0, 0;
  DeformableSuperquadricSettings settings;
  settings.parts = DeformableSuperquadricParts::global();
  settings.mass_density = 0.5;
  const Eigen::Vector2d pole(1.5707963267948966, 0.0);
  const Eigen::Vector2d middle(0.5, 0.5);
  const Eigen::Vector3d anchor = sheet.position(sheet.initial_coordinates(), middle);
  const DeformableSuperquadricModel probe(shape, Eigen::Vector3d::Zero(),
                                          Eigen::Quaterniond::Identity(), settings);
  const Eigen::Vector3d centre = anchor - probe.position(probe.initial_coordinates(), pole);
  const DeformableSuperquadricModel body(shape, centre, Eigen::Quaterniond::Identity(), settings);

  System system;
  system.add_model(sheet);
  system.add_model(body);
  system.add_force(1, gravity(Eigen::Vector3d(0.0, 0.0, -9.81)));  // the sheet has no load
  ConstraintSolver solver;
  solver.add(system, PointToPointConstraint(0, middle, 1, pole));
  ASSERT_LT(solver.max_violation(system), 1e-14);
  IntegratorSettings integrator_settings;  // newmark
  integrator_settings.newton_iterations = 2;
  Integrator integrator(integrator_settings);
  double largest_violation = 0.0;
  const int steps = 100;
  for (int k = 0; k < steps; ++k) {
    solver.step(integrator, system, 0.005);
    largest_violation = std::max(largest_violation, solver.max_violation(system));
  }
  const double sag = system.position(0, middle).z();
  std::cout << "superquadric on a sheet, 0.5 s: largest joint violation " << largest_violation
            << ", sheet centre at z = " << sag << "\n";
  // Baumgarte-stabilized acceleration-level rows with Newton iterations at the end-of-step
  // state: what is left is the unconverged non-linear part (the pole moves with the rotation and
  // shape) and round-off; 6e-16 measured.
  EXPECT_LT(largest_violation, 1e-8);
  // Only the joint pulls the sheet down (it has no load of its own).
  EXPECT_LT(sag, -1e-2);
  EXPECT_EQ(integrator.block_factorization_count(0), 1);
  EXPECT_GE(integrator.block_factorization_count(1), steps);
  EXPECT_TRUE(system.coordinates().allFinite());
}

// ----------------------------------------------------------------------------------------------
// Multibody assembly with superquadric parts (Terzopoulos 2003, eqs. 1.39-1.40): an articulated
// figure assembled from misplaced, rotated (and, with global deformations on, misshaped) parts.

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
