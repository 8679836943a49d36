// Hard cases, constraints: redundant and conflicting constraints on one D-NURBS curve, and a
// pendulum chain of 50 rigid superquadric parts joined by ball joints.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "dnurbs/constraints/constraint_solver.h"
#include "dnurbs/constraints/point_constraints.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"
#include "hardcase_helpers.h"

namespace dnurbs {
namespace {

using hardcase::record_result;

const Eigen::Vector2d kMiddle(0.5, 0.0);

// A damped straight cubic (8 spans, w1 = 1, gamma = 4) whose midpoint is pulled by the given
// targets, stepped 2 s at dt = 0.01 by newmark.
struct PulledCurve {
  System system;
  ConstraintSolver solver;
  Integrator integrator;

  explicit PulledCurve(const std::vector<Eigen::Vector3d>& targets) {
    DNurbsCurveMaterial material;
    material.tension = 1.0;
    material.damping_density = 4.0;
    system.add_model(DNurbsCurve(hardcase::straight_cubic(8), material));
    for (const Eigen::Vector3d& target : targets) {
      solver.add(system, PointTargetConstraint(0, kMiddle, TargetTrajectory::fixed(target)));
    }
  }

  void run() {
    for (int k = 0; k < 200; ++k) {
      solver.step(integrator, system, 0.01);
    }
  }

  Eigen::Vector3d midpoint() const { return system.position(0, kMiddle); }
};

TEST(ConstraintExtremes, RedundantConstraintsAreReportedAndStillSatisfied) {
  // The midpoint (0.5, 0, 0) pinned three times to (0.5, 0.2, 0): 9 rows of rank 3. Stable, in
  // numbers: every step rank deficient and reported (rank 3 of 9), the least-squares step
  // still moves the point onto the target (Baumgarte alpha = 20 over 2 s: decay
  // (1 + alpha t) e^{-alpha t} ~ 1e-16 of the initial 0.2) to |x - target| <= 1e-9, and the
  // three multipliers share the one constraint force equally (minimum-norm lambda) to 1e-9.
  const Eigen::Vector3d target(0.5, 0.2, 0.0);
  PulledCurve curve({target, target, target});
  curve.run();
  const ConstraintReport& report = curve.solver.last_report();
  const double error = (curve.midpoint() - target).norm();
  const Eigen::VectorXd& lambda = curve.solver.multipliers();
  const double split = std::max((lambda.segment<3>(0) - lambda.segment<3>(3)).norm(),
                                (lambda.segment<3>(0) - lambda.segment<3>(6)).norm());
  std::printf("redundant: rank %d of %d, |x - target| %.3e, multiplier split %.3e, '%s'\n",
              report.rank, report.row_count, error, split, report.message.c_str());
  EXPECT_TRUE(report.rank_deficient);
  EXPECT_EQ(report.rank, 3);
  EXPECT_EQ(report.row_count, 9);
  EXPECT_FALSE(report.message.empty());
  EXPECT_EQ(curve.solver.rank_deficient_steps(), 200);
  EXPECT_LE(error, 1e-9);
  EXPECT_LE(split, 1e-9);
  record_result("|x - target| after 2 s, point pinned three times (rank 3 of 9)", error, "<= 1e-9");
}

TEST(ConstraintExtremes, ConflictingConstraintsSettleOnTheLeastSquaresPoint) {
  // The midpoint pinned to (0.5, 0.2, 0) and to (0.5, -0.1, 0) at once: no state satisfies both.
  // The least-squares answer is the average target (0.5, 0.05, 0), where the two violations
  // are equal and opposite (0.15 each). Stable, in numbers: every step finite and reported
  // rank deficient, and after 2 s the point within 1e-9 of the average target.
  const Eigen::Vector3d first(0.5, 0.2, 0.0);
  const Eigen::Vector3d second(0.5, -0.1, 0.0);
  PulledCurve curve({first, second});
  curve.run();
  const Eigen::Vector3d average = 0.5 * (first + second);
  const double error = (curve.midpoint() - average).norm();
  const ConstraintReport& report = curve.solver.last_report();
  std::printf("conflicting: rank %d of %d, |x - average target| %.3e, '%s'\n", report.rank,
              report.row_count, error, report.message.c_str());
  EXPECT_TRUE(report.rank_deficient);
  EXPECT_EQ(report.rank, 3);
  EXPECT_TRUE(curve.system.coordinates().allFinite());
  EXPECT_LE(error, 1e-9);
  record_result("|x - mean target| after 2 s, point pinned to two targets 0.3 apart", error,
                "<= 1e-9");
}

const Eigen::Vector2d kTopPole(0.5 * std::numbers::pi, 0.0);      // body point (0, 0, a a3)
const Eigen::Vector2d kBottomPole(-0.5 * std::numbers::pi, 0.0);  // body point (0, 0, -a a3)

TEST(ConstraintExtremes, PendulumChainOfFiftyPartsKeepsJointsAndEnergy) {
  // Fifty slender rigid ellipsoids (half length 0.05, so the chain is 5 long) hanging from a
  // pivot, released from 40 degrees off the vertical as one straight rod, ball joints from each
  // bottom pole to the next top pole, undamped, projection after each step (as the 10-part
  // chain of tests/constraints). Stable, in numbers: over 0.5 s (200 steps of 2.5e-3) the
  // largest joint violation stays <= 1e-12 (the projection tolerance) and the total energy
  // (kinetic + m g z) within 1e-5 relative of its start (newmark with Newton conserves it up to
  // its O(dt^2) truncation: 2.4e-7 measured).
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  const double angle = 40.0 * std::numbers::pi / 180.0;
  const Eigen::Vector3d down(std::sin(angle), 0.0, -std::cos(angle));
  const Eigen::Quaterniond orientation =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), -down);
  constexpr int kParts = 50;
  SuperquadricShapeParameters shape = SuperquadricShapeParameters::Zero();
  shape << 1.0, 0.02, 0.02, 0.05, 1.0, 1.0, 0, 0, 0, 0, 0, 0, 0, 0;
  System system;
  for (int i = 0; i < kParts; ++i) {
    const DeformableSuperquadricModel part(shape, (0.1 * i + 0.05) * down, orientation);
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
  for (int i = 0; i + 1 < kParts; ++i) {
    solver.add(system, PointToPointConstraint(i, kBottomPole, i + 1, kTopPole), parameters);
  }
  solver.set_projection(true, 1e-12);
  IntegratorSettings settings;
  settings.newton_iterations = 4;
  settings.newton_tolerance = 1e-12;
  Integrator integrator(settings);
  const auto energy = [&] {
    double total = system.kinetic_energy();
    for (int i = 0; i < kParts; ++i) {
      const auto& part = dynamic_cast<const DeformableSuperquadricModel&>(system.model(i));
      total -= part.reference_mass_properties().mass * g.dot(system.coordinates(i).head<3>());
    }
    return total;
  };
  const double initial = energy();
  double drift = 0.0;
  double violation = 0.0;
  for (int k = 0; k < 200; ++k) {
    solver.step(integrator, system, 2.5e-3);
    drift = std::max(drift, std::abs(energy() - initial) / std::abs(initial));
    violation = std::max(violation, solver.max_violation(system));
  }
  const double fall = (system.coordinates(kParts - 1).head<3>() - 4.95 * down).norm();
  std::printf("chain of %d: energy drift %.3e, violation %.3e, lowest part moved %.3e\n", kParts,
              drift, violation, fall);
  EXPECT_LE(violation, 1e-12);
  EXPECT_LE(drift, 1e-5);
  EXPECT_GT(fall, 0.1);  // the chain did swing
  record_result("max joint violation over 0.5 s, 50-part pendulum chain", violation, "<= 1e-12");
}

}  // namespace
}  // namespace dnurbs
