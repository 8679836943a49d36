// The remaining scenes of seed 000 on small grids: cardboard pressed at its centre (figure 4),
// lifting a cardboard by its middle point (figure 9) and opening curtains (figures 10, 11).

#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "dynamics/core/forces.h"
#include "dynamics/core/line_force.h"
#include "dynamics/core/obstacles.h"
#include "dynamics/integrators/semi_implicit_step.h"
#include "dynamics/core/system.h"
#include "dynamics/grid/terzopoulos_surface.h"
#include "tests/common/grid_scenes.h"

namespace dnurbs {
namespace {

TEST(CardboardPress, BothNormalsAgreeForSmallCurvingResistance) {
  // eta = 0.01, xi = 1e-8: bending is negligible next to stretching, so the two normal
  // approximations give the same press to 1% (measured: they differ by ~1e-3 relative).
  const Grid grid = test::unit_square_grid(13);
  double deflection[2] = {0.0, 0.0};
  for (const auto normal : {NormalApproximation::kClassic, NormalApproximation::kChristoffel}) {
    TerzopoulosSettings settings;
    settings.normal = normal;
    TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()),
                             test::sheet_material(0.01, 0.0, 1e-8, 0.5), settings);
    sheet.fix_border();
    System system(sheet);
    system.add_force(0, point_force(Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d(0, 0, -0.002)));
    SemiImplicitStepper stepper;
    for (int s = 0; s < 300; ++s) {
      stepper.step(system, 0.01);
    }
    const NodePositions d = sheet.positions(system.coordinates(0)) - sheet.rest_positions();
    deflection[static_cast<int>(normal)] = -d(grid.index(6, 6), 2);
    // Forward differences are not mirror-symmetric: measured asymmetry ~1.3e-3.
    EXPECT_LT(test::asymmetry(grid, d), 1e-2);
  }
  std::printf("cardboard press: centre deflection classic %.5f, christoffel %.5f\n", deflection[0],
              deflection[1]);
  EXPECT_GT(deflection[0], 0.05);
  EXPECT_NEAR(deflection[1], deflection[0], 0.01 * deflection[0]);
}

TEST(LiftingCardboard, MiddleRisesCornersStayOnTheGround) {
  // eta = 1e-2, xi = 2e-6, Christoffel normal; a lift of twice the weight on the middle 3 by 3
  // nodes, the ground met by projection: the middle rises, the corners stay on the ground and
  // no node is ever below it (1e-12: round-off of the projection).
  const Grid grid = test::unit_square_grid(13);
  TerzopoulosSettings settings;
  settings.normal = NormalApproximation::kChristoffel;
  TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()),
                           test::sheet_material(1e-2, 0.0, 2e-6, 0.5), settings);
  System system(sheet);
  system.add_force(0, gravity(Eigen::Vector3d(0, 0, -0.002)));
  for (int j = 5; j <= 7; ++j) {
    for (int i = 5; i <= 7; ++i) {
      system.add_force(0, point_force(grid.parameter(i, j), Eigen::Vector3d(0, 0, 0.004 / 9)));
    }
  }
  const std::vector<Obstacle> ground{GroundPlane{}};
  const std::vector<Eigen::Vector2d> points = grid.node_parameters();
  ContactSettings contact;
  contact.friction = 0.3;
  SemiImplicitStepper stepper;
  for (int s = 0; s < 400; ++s) {
    stepper.step(system, 0.005);
    project_contacts(system, 0, ground, points, contact);
    ASSERT_LE(max_penetration(system, 0, ground, points), 1e-12);
  }
  const NodePositions r = sheet.positions(system.coordinates(0));
  std::printf("lifting cardboard: middle z %.4f, corner z %.2e\n", r(grid.index(6, 6), 2), r(0, 2));
  EXPECT_GT(r(grid.index(6, 6), 2), 0.05);
  EXPECT_LT(r(0, 2), 1e-3);
}

TEST(Curtains, TheUpperLineOpensTheCurtainAndKeepsItsHeight) {
  // Woollen (xi = 2e-6) and silk (xi = 0) curtains of 9 by 7 nodes hang pleated from a rail; the
  // same force along the upper line draws them toward the fixed first hook. The hooks' heights
  // are fixed coordinates: exactly unchanged.
  const Grid grid(9, 7, 1.0);
  for (const double xi : {2e-6, 0.0}) {
    NodePositions rest(grid.node_count(), 3);
    for (int k = 0; k < grid.node_count(); ++k) {
      const auto [i, j] = grid.node(k);
      rest.row(k) << i, 0.4 * std::sin(std::numbers::pi * i / 2.0), -j;
    }
    TerzopoulosSettings settings;
    settings.normal = NormalApproximation::kChristoffel;
    TerzopoulosMaterial cloth = test::sheet_material(1e-3, 1e-6, xi, 0.002);
    TerzopoulosSurface curtain(grid, rest, cloth, settings);
    curtain.fix_point(0);
    for (int i = 1; i < grid.nu(); ++i) {
      curtain.fix_coordinate(3 * grid.index(i, 0) + 2);
    }
    System system(curtain);
    system.add_force(0, gravity(Eigen::Vector3d(0, 0, -1e-4)));
    std::vector<Eigen::Vector2d> hooks = grid.row_parameters(0);
    hooks.erase(hooks.begin());
    system.add_force(0, line_force(hooks, [](double) { return Eigen::Vector3d(-5e-4, 0, 0); }));
    SemiImplicitStepper stepper;
    for (int s = 0; s < 300; ++s) {
      stepper.step(system, 1.0);
    }
    const NodePositions r = curtain.positions(system.coordinates(0));
    std::printf("curtain xi = %g: last hook at x = %.3f (from 8)\n", xi, r(grid.nu() - 1, 0));
    EXPECT_LT(r(grid.nu() - 1, 0), 7.0);
    EXPECT_GT(r(grid.nu() - 1, 0), 0.0);  // it does not pass the fixed hook
    for (int i = 0; i < grid.nu(); ++i) {
      EXPECT_EQ(r(grid.index(i, 0), 2), 0.0);
    }
  }
}

}  // namespace
}  // namespace dnurbs
