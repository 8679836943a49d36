// Every constraint's C_q, Cdot and sigma against finite differences of C along the coordinates
// and along the motion q(t) = q + t qd (coordinates are a vector space for D-NURBS models).

#include "dnurbs/constraints/constraint.h"

#include <random>

#include <gtest/gtest.h>

#include "dnurbs/constraints/constraint_solver.h"
#include "dnurbs/constraints/point_constraints.h"
#include "dnurbs/constraints/surface_constraints.h"
#include "dnurbs/core/error.h"
#include "tests/common/constraint_test_scenes.h"

namespace dnurbs {
namespace {

void expect_derivatives_match_differences(const System& system, const Constraint& constraint) {
  ConstraintSolver solver;
  solver.add(system, constraint);
  std::mt19937 generator(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  const int n = system.velocity_count();
  Eigen::VectorXd q = system.coordinates();
  Eigen::VectorXd qd(n);
  for (int i = 0; i < n; ++i) {
    qd[i] = 0.3 * normal(generator);
  }
  const double time = 0.7;
  ConstraintSolver::Evaluation at;
  solver.evaluate(system, q, qd, time, at);
  const Eigen::MatrixXd jacobian = Eigen::MatrixXd(at.jacobian);
  const int rows = solver.row_count();
  const auto value = [&](const Eigen::VectorXd& coordinates, double t) {
    ConstraintSolver::Evaluation e;
    solver.evaluate(system, coordinates, qd, t, e);
    return Eigen::VectorXd(e.value);
  };
  // C_q column by column: central differences, error h^2 |C'''| (~1e-12 here) plus rounding
  // eps |C| / h.
  const double h = 1e-6;
  Eigen::MatrixXd numeric(rows, n);
  for (int k = 0; k < n; ++k) {
    Eigen::VectorXd plus = q;
    Eigen::VectorXd minus = q;
    plus[k] += h;
    minus[k] -= h;
    numeric.col(k) = (value(plus, time) - value(minus, time)) / (2.0 * h);
  }
  EXPECT_LT((jacobian - numeric).cwiseAbs().maxCoeff(), 1e-7 * (1.0 + jacobian.norm()))
      << constraint.description();
  // Cdot = d/dt C(q + t qd, t0 + t) and -sigma = d^2/dt^2 C(q + t qd, t0 + t) (with qdd = 0):
  // second differences with step 1e-4 have error h^2 |C''''| / 12 + eps |C| / h^2 ~ 1e-8.
  const double s = 1e-4;
  const Eigen::VectorXd forward = value(q + s * qd, time + s);
  const Eigen::VectorXd backward = value(q - s * qd, time - s);
  const Eigen::VectorXd middle = value(q, time);
  const Eigen::VectorXd rate = (forward - backward) / (2.0 * s);
  const Eigen::VectorXd second = (forward - 2.0 * middle + backward) / (s * s);
  EXPECT_LT((at.rate - rate).norm(), 1e-7 * (1.0 + rate.norm())) << constraint.description();
  EXPECT_LT((at.sigma + second).norm(), 1e-5 * (1.0 + second.norm())) << constraint.description();
}

class ConstraintJacobian : public ::testing::TestWithParam<WeightMode> {};

TEST_P(ConstraintJacobian, PointTargetMatchesDifferences) {
  const System system = testing::surface_and_curve(GetParam());
  // A moving target given by keyframes: its velocity and acceleration enter Cdot and sigma.
  const TargetTrajectory target = TargetTrajectory::keyframes(
      {0.0, 0.5, 1.0, 2.0}, {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.2, 0.1, 0.3),
                             Eigen::Vector3d(0.5, 0.4, 0.1), Eigen::Vector3d(1, 1, 1)});
  expect_derivatives_match_differences(
      system, PointTargetConstraint(0, Eigen::Vector2d(0.35, 0.62), target));
  const TargetTrajectory circling = TargetTrajectory::function(
      [](double t) { return Eigen::Vector3d(std::cos(t), std::sin(t), 0.1 * t * t); });
  expect_derivatives_match_differences(
      system, PointTargetConstraint(1, Eigen::Vector2d(0.4, 0.0), circling));
}

TEST_P(ConstraintJacobian, BallJointAndHingeMatchDifferences) {
  const System system = testing::surface_and_curve(GetParam());
  expect_derivatives_match_differences(
      system, PointToPointConstraint(1, Eigen::Vector2d(0.3, 0.0), 0, Eigen::Vector2d(0.5, 0.5)));
  expect_derivatives_match_differences(
      system, HingeConstraint(1, Eigen::Vector2d(0.2, 0.0), Eigen::Vector2d(0.8, 0.0), 0,
                              Eigen::Vector2d(0.3, 0.3), Eigen::Vector2d(0.7, 0.6)));
}

TEST_P(ConstraintJacobian, SurfaceNormalMatchesDifferences) {
  const System system = testing::surface_and_curve(GetParam());
  expect_derivatives_match_differences(
      system,
      SurfaceNormalConstraint(0, Eigen::Vector2d(0.45, 0.3), Eigen::Vector3d(0.1, -0.2, 1.0)));
}

TEST_P(ConstraintJacobian, ControlPointMatchesDifferences) {
  const System system = testing::surface_and_curve(GetParam());
  expect_derivatives_match_differences(
      system, ControlPointConstraint(1, 3, Eigen::Vector3d(0.5, 0.5, 0.5)));
}

TEST_P(ConstraintJacobian, CurveOnSurfaceSamplesMatchDifferences) {
  const System system = testing::surface_and_curve(GetParam());
  const auto constraints = curve_on_surface_constraints(system, 1, 0, 4);
  ASSERT_EQ(constraints.size(), 4u);
  for (const auto& constraint : constraints) {
    expect_derivatives_match_differences(system, *constraint);
  }
}

INSTANTIATE_TEST_SUITE_P(FixedAndFreeWeights, ConstraintJacobian,
                         ::testing::Values(WeightMode::kFixed, WeightMode::kFree),
                         [](const auto& info) {
                           return info.param == WeightMode::kFixed ? std::string("FixedWeights")
                                                                   : std::string("FreeWeights");
                         });

TEST(ConstraintChecks, BadModelsAndParametersAreRejected) {
  const System system = testing::surface_and_curve(WeightMode::kFixed);
  ConstraintSolver solver;
  EXPECT_THROW(
      solver.add(system, PointTargetConstraint(5, Eigen::Vector2d(0.5, 0.5),
                                               TargetTrajectory::fixed(Eigen::Vector3d::Zero()))),
      Error);
  EXPECT_THROW(
      solver.add(system, PointTargetConstraint(0, Eigen::Vector2d(1.5, 0.5),
                                               TargetTrajectory::fixed(Eigen::Vector3d::Zero()))),
      Error);
  EXPECT_THROW(solver.add(system, SurfaceNormalConstraint(1, Eigen::Vector2d(0.5, 0.0),
                                                          Eigen::Vector3d::UnitZ())),
               Error);  // model 1 is a curve
  EXPECT_THROW(SurfaceNormalConstraint(0, Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d::Zero()),
               Error);
  EXPECT_THROW(solver.add(system, ControlPointConstraint(0, 36, Eigen::Vector3d::Zero())), Error);
  EXPECT_THROW(
      TargetTrajectory::keyframes({0.0, 0.0}, {Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()}),
      Error);
  BaumgarteParameters negative;
  negative.alpha = -1.0;
  EXPECT_THROW(solver.add(system,
                          PointTargetConstraint(0, Eigen::Vector2d(0.5, 0.5),
                                                TargetTrajectory::fixed(Eigen::Vector3d::Zero())),
                          negative),
               Error);
  EXPECT_EQ(solver.constraint_count(), 0);
}

}  // namespace
}  // namespace dnurbs
