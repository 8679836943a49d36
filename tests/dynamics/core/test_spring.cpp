// Tests of dynamics/core/spring.h and the springs of System (dynamics/core/system.h): the spring
// force is minus the gradient of the spring energy (finite differences), windows and drags give
// the states they promise, ids stay stable when springs are removed, bad input throws.

#include "dnurbs/dynamics/core/spring.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "tests/common/dynamics_test_helpers.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

Eigen::Vector3d constant(double x, double y, double z) {
  return Eigen::Vector3d(x, y, z);
}

TEST(SpringForce, IsMinusTheGradientOfTheSpringEnergy) {
  // f = L^T k (target - x) = -dE/dq for E = (1/2) k |x(q, u) - target|^2, on a free-weight curve
  // (x rational in q, L depends on q) and a fixed-weight sheet. Central differences with h = 1e-6
  // have error O(h^2 E''') ~ 1e-12 and rounding 1e-16 E / h ~ 1e-10: tolerance 1e-7 relative.
  DNurbsSettings free_weights;
  free_weights.weight_mode = WeightMode::kFree;
  const DNurbsCurve curve(test::straight_curve(3, 4), {}, free_weights);
  const DNurbsSurface sheet(test::flat_patch(3, 2, 3, 2));
  for (const Model* model :
       {static_cast<const Model*>(&curve), static_cast<const Model*>(&sheet)}) {
    System system(*model);
    system.add_spring(0, mouse_spring(
                             {0.37, 0.61}, [](double) { return constant(0.2, 0.5, 0.7); }, 30.0));
    Eigen::VectorXd q = system.coordinates();
    q += 0.05 * Eigen::VectorXd::LinSpaced(q.size(), -1.0, 1.0).array().sin().matrix();
    Eigen::VectorXd force = Eigen::VectorXd::Zero(system.velocity_count());
    system.add_spring_forces(0.0, q, force);
    const double h = 1e-6;
    Eigen::VectorXd gradient(q.size());
    for (Eigen::Index i = 0; i < q.size(); ++i) {
      Eigen::VectorXd plus = q;
      Eigen::VectorXd minus = q;
      plus[i] += h;
      minus[i] -= h;
      gradient[i] = (system.spring_energy(0.0, plus) - system.spring_energy(0.0, minus)) / (2 * h);
    }
    EXPECT_LT((force + gradient).norm(), 1e-7 * force.norm());
    EXPECT_GT(force.norm(), 1.0);  // the spring pulls: the test compares something
  }
}

TEST(SpringForce, AppliedForcesIncludeSpringsUnlessAsked) {
  System system(DNurbsSurface(test::flat_patch(2, 2, 2, 2)));
  system.add_spring(0, mouse_spring(
                           {0.5, 0.5}, [](double) { return constant(0.5, 0.5, 1.0); }, 4.0));
  const Eigen::VectorXd q = system.coordinates();
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(q.size());
  Eigen::VectorXd with = Eigen::VectorXd::Zero(q.size());
  Eigen::VectorXd without = Eigen::VectorXd::Zero(q.size());
  system.add_applied_forces(0.0, q, v, with);
  system.add_applied_forces(0.0, q, v, without, /*include_springs=*/false);
  EXPECT_EQ(without.norm(), 0.0);
  // The pull on the flat sheet is straight up: z components sum to k * 1 (partition of unity)
  double z = 0.0;
  for (Eigen::Index i = 2; i < with.size(); i += 3) {
    z += with[i];
  }
  EXPECT_NEAR(z, 4.0, 1e-14);  // sum of N_j(u) = 1 to rounding
  EXPECT_NEAR(system.spring_energy(), 0.5 * 4.0 * 1.0, 1e-14);
}

TEST(SpringState, WindowsAndDragsGiveTheirStates) {
  const Spring window =
      windowed_spring(mouse_spring(
                          {0.1, 0.2}, [](double t) { return constant(t, 0, 0); }, 7.0),
                      1.0, 2.0);
  EXPECT_EQ(window(0.5).stiffness, 0.0);
  EXPECT_EQ(window(1.0).stiffness, 7.0);
  EXPECT_EQ(window(2.0).stiffness, 0.0);
  EXPECT_EQ(window(1.5).target.x(), 1.5);
  const Spring drag = dragged_spring([](double t) { return Eigen::Vector2d(t, 2 * t); },
                                     [](double t) { return constant(0, 0, t); }, 3.0);
  EXPECT_EQ(drag(0.25).parameter, Eigen::Vector2d(0.25, 0.5));
  EXPECT_EQ(drag(0.25).target.z(), 0.25);
}

TEST(SpringIds, StayStableWhenSpringsAreRemoved) {
  System system(DNurbsCurve(test::straight_curve(3, 4)));
  const auto at = [](double) { return constant(0, 1, 0); };
  const int a = system.add_spring(0, mouse_spring({0.2, 0}, at, 1.0));
  const int b = system.add_spring(0, mouse_spring({0.8, 0}, at, 2.0));
  system.remove_spring(a);
  EXPECT_FALSE(system.has_spring(a));
  EXPECT_TRUE(system.has_spring(b));
  EXPECT_EQ(system.spring_state(b, 0.0).stiffness, 2.0);
  const int c = system.add_spring(0, mouse_spring({0.5, 0}, at, 3.0));
  EXPECT_EQ(c, 2);  // removed ids are not reused
  system.set_spring(b, mouse_spring({0.6, 0}, at, 5.0));
  EXPECT_EQ(system.spring_state(b, 0.0).parameter.x(), 0.6);
  const System copy = system;
  EXPECT_EQ(copy.spring_state(c, 0.0).stiffness, 3.0);
  EXPECT_NE(testing::error_message([&] { system.remove_spring(a); }).find("no spring 0"),
            std::string::npos);
}

TEST(SpringErrors, BadValuesThrowNamingThem) {
  const auto at = [](double) { return constant(0, 0, 0); };
  EXPECT_NE(testing::error_message([&] {
              mouse_spring({0.5, 0.5}, at, -2.0);
            }).find("-2"),
            std::string::npos);
  EXPECT_THROW(mouse_spring({std::nan(""), 0.5}, at, 1.0), Error);
  EXPECT_THROW(mouse_spring({0.5, 0.5}, VectorOfTime(), 1.0), Error);
  EXPECT_THROW(dragged_spring(ParameterOfTime(), at, 1.0), Error);
  System system(DNurbsCurve(test::straight_curve(3, 4)));
  EXPECT_THROW(system.add_spring(3, mouse_spring({0.5, 0}, at, 1.0)), Error);
  EXPECT_THROW(system.add_spring(0, Spring()), Error);
  system.add_spring(0, [](double t) {
    return SpringState{{0.5, 0}, {0, 0, 0}, t > 1 ? -1.0 : 1.0};
  });
  EXPECT_NO_THROW(system.spring_state(0, 0.5));
  const std::string message = testing::error_message([&] { system.spring_state(0, 2.0); });
  EXPECT_NE(message.find("spring 0 at t = 2"), std::string::npos) << message;
}

}  // namespace
}  // namespace dnurbs
