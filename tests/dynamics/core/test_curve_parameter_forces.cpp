// Tests of the curve-parameter and constant-vector overloads of dynamics/core/forces.h and
// dynamics/core/spring.h: point_force(u, f), spring_force(u, ...) and mouse_spring(u, ...) on a
// curve are the (u, 0) forms exactly, and control_point_force(points, f) is the constant force
// f on each listed control point.

#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/spring.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "tests/common/dynamics_test_helpers.h"

namespace dnurbs {
namespace {

Eigen::VectorXd applied(const Force& force, const Model& model, const Eigen::VectorXd& q) {
  Eigen::VectorXd generalized = Eigen::VectorXd::Zero(model.velocity_count());
  force(model, 0.25, q, Eigen::VectorXd::Zero(model.velocity_count()), generalized);
  return generalized;
}

TEST(CurveParameterForces, EqualTheForcesAtUAndZero) {
  const DNurbsCurve curve(test::straight_curve(3, 5));
  Eigen::VectorXd q = curve.initial_coordinates();
  q += 0.1 * Eigen::VectorXd::LinSpaced(q.size(), -1.0, 1.0).array().cos().matrix();
  const Eigen::Vector3d f(0.3, -1.2, 2.5);
  const auto target = [](double t) { return Eigen::Vector3d(t, 1.0, -0.5); };
  const Eigen::VectorXd at_point = applied(point_force(Eigen::Vector2d(0.37, 0.0), f), curve, q);
  EXPECT_GT(at_point.norm(), 1.0);  // a real force, so that equality means something
  EXPECT_EQ(applied(point_force(0.37, f), curve, q), at_point);
  EXPECT_EQ(applied(point_force(0.37, [f](double) { return f; }), curve, q), at_point);
  EXPECT_EQ(applied(spring_force(0.37, target, 40.0), curve, q),
            applied(spring_force(Eigen::Vector2d(0.37, 0.0), target, 40.0), curve, q));
  const SpringState by_parameter = mouse_spring(0.37, target, 40.0)(0.5);
  const SpringState by_point = mouse_spring(Eigen::Vector2d(0.37, 0.0), target, 40.0)(0.5);
  EXPECT_EQ(by_parameter.parameter, by_point.parameter);
  EXPECT_EQ(by_parameter.parameter, Eigen::Vector2d(0.37, 0.0));
  EXPECT_EQ(by_parameter.target, by_point.target);
  EXPECT_EQ(by_parameter.stiffness, 40.0);
}

TEST(ConstantControlPointForce, AddsTheVectorToEachListedControlPoint) {
  const DNurbsCurve curve(test::straight_curve(3, 6));
  const Eigen::Vector3d f(1.5, 0.0, -2.0);
  const std::vector<int> points = {1, 4};
  const Eigen::VectorXd generalized =
      applied(control_point_force(points, f), curve, curve.initial_coordinates());
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(curve.velocity_count());
  for (const int i : points) {
    expected.segment<3>(curve.control_point_offset(i)) = f;
  }
  EXPECT_EQ(generalized, expected);
}

}  // namespace
}  // namespace dnurbs
