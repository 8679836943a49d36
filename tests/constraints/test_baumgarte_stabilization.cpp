// Baumgarte stabilisation (seed 001 eq 1.40) inside the integrators, and the redundant and
// conflicting cases.
#include <cmath>

#include <gtest/gtest.h>

#include "tests/common/constraint_test_scenes.h"
#include "constraints/constraint_solver.h"
#include "constraints/point_constraints.h"
#include "constraints/surface_constraints.h"
#include "dynamics/core/forces.h"
#include "dynamics/integrators/integrator.h"

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
      // The end-of-step condition discretises the violation ODE with the scheme's own accuracy:
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
  // Newton iterations per step remove its linearisation error.
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

}  // namespace
}  // namespace dnurbs
