// The yield rule of a rest shape (dynamics/core/plastic_flow.h): elastic up to the yield
// distance, beyond it the excess decays as (1 - rate dt)^n, exactly, on a single node; the rule
// inside a System step, where a held control point's rest position follows the closed form; planar
// nodes (the curves of a swung surface) flow in their plane.

#include "dnurbs/dynamics/core/plastic_flow.h"

#include <cmath>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/nurbs/shape_generators.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

using testing::error_message;
using ::testing::HasSubstr;

TEST(PlasticFlow, ExcessBeyondYieldDecaysGeometricallyOnASingleNode) {
  const PlasticFlow flow{0.25, 3.0};
  const double dt = 0.1;  // c = rate dt = 0.3
  const Eigen::Vector3d direction = Eigen::Vector3d(2.0, -1.0, 2.0) / 3.0;
  const double displacement = 1.0;  // |x - r_0|, held
  Eigen::VectorXd q(3);
  q = displacement * direction;
  Eigen::VectorXd rest = Eigen::VectorXd::Zero(3);
  for (int n = 1; n <= 12; ++n) {
    EXPECT_EQ(flow_rest_positions(flow, dt, 3, q, rest), 1);
    // r_n = (d - yield) (1 - (1 - c)^n) along the strain, the excess (d - yield) (1 - c)^n
    const double moved = (displacement - flow.yield) * (1.0 - std::pow(0.7, n));
    EXPECT_NEAR((rest - moved * direction).norm(), 0.0, 1e-15) << n;
  }
  // Within the yield distance nothing flows
  Eigen::VectorXd inside(3);
  inside << 0.1, 0.1, 0.1;
  Eigen::VectorXd at_rest = Eigen::VectorXd::Zero(3);
  EXPECT_EQ(flow_rest_positions(flow, dt, 3, inside, at_rest), 0);
  EXPECT_EQ(at_rest, Eigen::VectorXd::Zero(3));
}

TEST(PlasticFlow, AFastRateReturnsToTheYieldSurfaceAndWeightsDoNotFlow) {
  // rate dt >= 1: perfect plasticity, |x - r| = yield after one step; a fourth (weight)
  // coordinate per node keeps its rest value
  const PlasticFlow flow{0.5, 100.0};
  Eigen::VectorXd q(8);
  q << 3, 0, 0, 2.0, 0, 0, 0.2, 1.5;
  Eigen::VectorXd rest(8);
  rest << 0, 0, 0, 1.0, 0, 0, 0, 1.0;
  EXPECT_EQ(flow_rest_positions(flow, 0.05, 4, q, rest), 1);
  EXPECT_DOUBLE_EQ(rest[0], 2.5);
  EXPECT_EQ(rest[3], 1.0);
  EXPECT_EQ(rest.segment<4>(4), (Eigen::Vector4d() << 0, 0, 0, 1.0).finished());
}

TEST(PlasticFlow, PlanarNodesFlowInTheirPlaneAndKeepTheirWeight) {
  // Control points of a swung surface's curves: two in-plane coordinates and a weight (stride 3,
  // dimension 2); the distance is measured in the plane, the third entry never flows
  const PlasticFlow flow{0.5, 2.0};
  Eigen::VectorXd q(6);
  q << 3.0, 4.0, 2.0, 0.3, 0.0, 9.0;  // node 0 at distance 5 from its rest, node 1 at 0.3
  Eigen::VectorXd rest(6);
  rest << 0.0, 0.0, 1.0, 0.0, 0.0, 1.0;
  const double dt = 0.1;  // c = 0.2
  EXPECT_EQ(flow_rest_positions(flow, dt, 3, q, rest, 2), 1);
  // r = c (d - yield) s / |s| = 0.2 * 4.5 * (0.6, 0.8)
  EXPECT_DOUBLE_EQ(rest[0], 0.54);
  EXPECT_DOUBLE_EQ(rest[1], 0.72);
  EXPECT_EQ(rest[2], 1.0);
  EXPECT_EQ(rest.tail<3>(), Eigen::Vector3d(0.0, 0.0, 1.0));
  EXPECT_THAT(error_message([&] { flow_rest_positions(flow, dt, 3, q, rest, 4); }),
              HasSubstr("a node position of 4 coordinates (expected 2 or 3)"));
}

TEST(PlasticFlow, BadRulesAndStepsAreRefused) {
  EXPECT_THAT(error_message([] {
                check_plastic_flow({-1.0, 1.0});
              }),
              HasSubstr("plastic yield -1 is not a non-negative finite distance"));
  EXPECT_THAT(error_message([] {
                check_plastic_flow({0.0, 0.0});
              }),
              HasSubstr("plastic rate 0 is not a positive finite number"));
  EXPECT_THAT(error_message([] {
                check_plastic_flow({std::numeric_limits<double>::quiet_NaN(), 1.0});
              }),
              HasSubstr("plastic yield nan"));
  Eigen::VectorXd q = Eigen::VectorXd::Zero(6);
  Eigen::VectorXd rest = Eigen::VectorXd::Zero(6);
  EXPECT_THAT(error_message([&] {
                flow_rest_positions({0.0, 1.0}, 0.0, 3, q, rest);
              }),
              HasSubstr("time step 0 is not positive"));
  EXPECT_THAT(error_message([&] {
                flow_rest_positions({0.0, 1.0}, 0.1, 4, q, rest);
              }),
              HasSubstr("are not nodes of 4"));
}

TEST(PlasticFlow, AHeldControlPointsRestFollowsTheClosedFormThroughSystemSteps) {
  // A rod whose end control point is held 0.8 off its rest position: every committed step of
  // dt lets the rest position yield by the rule, whatever the free middle point does.
  DNurbsCurveMaterial material;
  material.damping_density = 1.0;
  material.tension = 2.0;
  DNurbsSettings settings;
  settings.plastic_flow = PlasticFlow{0.3, 2.0};
  const DNurbsCurve rod(greville_line({0, 0, 0}, {2, 0, 0}, 3, 2), material, settings);
  EXPECT_TRUE(rod.has_rest_shape());
  System system(rod);
  system.fix_point(0, 0);
  system.fix_point(0, 2);
  Eigen::VectorXd q = system.coordinates();
  q[8] += 0.8;  // control point 2, z
  system.set_state(q, Eigen::VectorXd::Zero(q.size()), 0.0);
  IntegratorSettings integrator_settings;
  integrator_settings.scheme = IntegratorScheme::kImplicitEuler;
  Integrator integrator(integrator_settings);
  const double dt = 0.1;  // c = 0.2
  for (int n = 1; n <= 10; ++n) {
    integrator.step(system, dt);
    const Eigen::VectorXd rest = system.flowing_rest_coordinates();
    ASSERT_EQ(rest.size(), 9);
    EXPECT_NEAR(rest[8], (0.8 - 0.3) * (1.0 - std::pow(0.8, n)), 1e-14) << n;
    EXPECT_EQ(rest[0], 0.0);  // the held start never left its rest position
  }
  // The rest shape went back in a checkpoint restores exactly; a wrong size is refused
  const Eigen::VectorXd rest = system.flowing_rest_coordinates();
  System copy(rod);
  copy.restore_flowing_rest_coordinates(rest);
  EXPECT_EQ(copy.flowing_rest_coordinates(), rest);
  EXPECT_THAT(
      error_message([&] { copy.restore_flowing_rest_coordinates(rest.head(3)); }),
      HasSubstr("rest coordinates: expected 9 (the models whose rest shape yields), got 3"));
}

}  // namespace
}  // namespace dnurbs
