#include "dnurbs/dynamics/core/obstacles.h"

#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/dynamics/integrators/semi_implicit_step.h"
#include "tests/common/grid_scenes.h"

namespace dnurbs {
namespace {

TEST(Obstacles, SignedDistancesAndNormals) {
  Eigen::Vector3d normal;
  const GroundPlane ground{Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, 2)};
  EXPECT_DOUBLE_EQ(signed_distance(ground, Eigen::Vector3d(5, 3, 0.5), &normal), -0.5);
  EXPECT_EQ(normal, Eigen::Vector3d::UnitZ());
  const BoxObstacle table{Eigen::Vector3d(-1, -1, -2), Eigen::Vector3d(1, 1, 0)};
  EXPECT_DOUBLE_EQ(signed_distance(table, Eigen::Vector3d(0.2, 0.1, -0.1), &normal), -0.1);
  EXPECT_EQ(normal, Eigen::Vector3d::UnitZ());
  EXPECT_DOUBLE_EQ(signed_distance(table, Eigen::Vector3d(4, 5, 0), &normal), 5.0);
  EXPECT_NEAR((normal - Eigen::Vector3d(0.6, 0.8, 0)).norm(), 0.0, 1e-15);
  const SphereObstacle ball{Eigen::Vector3d(1, 0, 0), 0.5};
  EXPECT_DOUBLE_EQ(signed_distance(ball, Eigen::Vector3d(1, 0, 0.25), &normal), -0.25);
  EXPECT_EQ(normal, Eigen::Vector3d::UnitZ());
  EXPECT_DOUBLE_EQ(penetration_depth({ground, ball}, Eigen::Vector3d(1, 0, 0.1)), 0.9);
  EXPECT_THROW(check_obstacle(SphereObstacle{Eigen::Vector3d::Zero(), -1.0}), Error);
  EXPECT_THROW(check_obstacle(BoxObstacle{Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero()}),
               Error);
  EXPECT_THROW(check_obstacle(GroundPlane{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}),
               Error);
  ContactSettings negative;
  negative.friction = -0.5;
  EXPECT_THROW(penalty_contact({ground}, {Eigen::Vector2d::Zero()}, negative), Error);
  System empty;
  SemiImplicitStepper stepper;
  EXPECT_THROW(stepper.step(empty, 0.0), Error);  // dt must be positive
}

struct ClothResult {
  double max_penetration = 0.0;    // over the whole fall, after each step
  double before_projection = 0.0;  // projection: deepest penetration a step produced
  double lowest_on_table = 0.0;    // z of the lowest node above the table top
  double hanging = 0.0;            // z of a corner (it hangs over the edge)
};

// Wu & de Melo, figure 2: a 16 by 16 table cloth (17 by 17 nodes, h = 1, grid units) with eta_ii =
// 0.001, eta_12 = 0.0006, xi = 0 falls from 1 above a table top of 8 by 8 under gravity 1e-4.
ClothResult table_cloth(bool projection, double friction) {
  const Grid grid(17, 17, 1.0);
  TerzopoulosSurface cloth(grid, flat_grid_positions(grid, Eigen::Vector3d(-8, -8, 1)),
                           test::sheet_material(0.001, 0.0006, 0.0, 0.01));
  System system(cloth);
  system.add_force(0, gravity(Eigen::Vector3d(0, 0, -1e-4)));
  const std::vector<Obstacle> table{
      BoxObstacle{Eigen::Vector3d(-4, -4, -20), Eigen::Vector3d(4, 4, 0)}};
  const std::vector<Eigen::Vector2d> points = grid.node_parameters();
  ContactSettings contact;
  contact.stiffness = 0.05;
  contact.damping = 0.05;
  contact.friction = friction;
  if (!projection) {
    system.add_force(0, penalty_contact(table, points, contact));
  }
  SemiImplicitStepper stepper;
  ClothResult result;
  for (int s = 0; s < 600; ++s) {
    stepper.step(system, 1.0);
    if (projection) {
      result.before_projection =
          std::max(result.before_projection, project_contacts(system, 0, table, points, contact));
    }
    result.max_penetration =
        std::max(result.max_penetration, max_penetration(system, 0, table, points));
  }
  const NodePositions r = cloth.positions(system.coordinates(0));
  result.lowest_on_table = 1e300;
  for (int k = 0; k < grid.node_count(); ++k) {
    if (std::abs(r(k, 0)) < 3.5 && std::abs(r(k, 1)) < 3.5) {
      result.lowest_on_table = std::min(result.lowest_on_table, r(k, 2));
    }
  }
  result.hanging = r(0, 2);
  std::printf(
      "table cloth %s friction %.1f: max penetration %.3e (before projection %.3e), "
      "lowest on table %.3e, corner z %.3f\n",
      projection ? "projection" : "penalty", friction, result.max_penetration,
      result.before_projection, result.lowest_on_table, result.hanging);
  return result;
}

TEST(TableCloth, NeverPassesThroughTheTable) {
  for (const double friction : {0.0, 0.5}) {
    const ClothResult penalty = table_cloth(false, friction);
    const ClothResult projected = table_cloth(true, friction);
    EXPECT_LT(penalty.max_penetration, 0.05);
    // Projection puts the nodes on the top face; only the round-off of z + depth remains.
    EXPECT_LE(projected.max_penetration, 1e-12);
    EXPECT_LT(projected.before_projection, 0.05);
    EXPECT_GT(penalty.lowest_on_table, -0.05);
    EXPECT_LT(penalty.hanging, -1.0);  // the cloth drapes over the edges
    EXPECT_LT(projected.hanging, -1.0);
  }
}

TEST(Obstacles, SheetDrapesOverASphereByProjection) {
  // A 9 by 9 unit sheet (eta = 0.05) falls on a sphere of radius 0.3: after every projection no
  // node is inside (1e-12: round-off of x + depth n), and the free corners fall below the top.
  const Grid grid(9, 9, 0.125);
  TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d(-0.5, -0.5, 0.35)),
                           test::sheet_material(0.05, 0.0, 0.0, 0.2));
  System system(sheet);
  system.add_force(0, gravity(Eigen::Vector3d(0, 0, -1.0)));
  const std::vector<Obstacle> ball{SphereObstacle{Eigen::Vector3d::Zero(), 0.3}};
  const std::vector<Eigen::Vector2d> points = grid.node_parameters();
  SemiImplicitStepper stepper;
  for (int s = 0; s < 300; ++s) {
    stepper.step(system, 0.01);
    project_contacts(system, 0, ball, points, ContactSettings{});
    ASSERT_LE(max_penetration(system, 0, ball, points), 1e-12) << "step " << s;
  }
  const NodePositions r = sheet.positions(system.coordinates(0));
  EXPECT_NEAR(r(grid.index(4, 4), 2), 0.3, 0.01);  // the centre rests on the top
  EXPECT_LT(r(0, 2), 0.0);                         // the corners hang down
}

// A 5 by 5 sheet (h = 0.25, eta = 0.01) on the ground, sliding at 1 along x under gravity 9.81:
// the distance it slides in one second.
double slide(bool projection, double friction) {
  const Grid grid(5, 5, 0.25);
  TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()),
                           test::sheet_material(0.01, 0.0, 0.0));
  System system(sheet);
  Eigen::VectorXd velocity = Eigen::VectorXd::Zero(sheet.coordinate_count());
  for (int k = 0; k < grid.node_count(); ++k) {
    velocity[3 * k] = 1.0;
  }
  system.set_velocities(0, velocity);
  system.add_force(0, gravity(Eigen::Vector3d(0, 0, -9.81)));
  const std::vector<Obstacle> ground{GroundPlane{}};
  const std::vector<Eigen::Vector2d> points = grid.node_parameters();
  ContactSettings contact;
  contact.stiffness = 1000.0;
  contact.damping = 5.0;
  contact.friction = friction;
  if (!projection) {
    system.add_force(0, penalty_contact(ground, points, contact));
  }
  SemiImplicitStepper stepper;
  for (int s = 0; s < 500; ++s) {
    stepper.step(system, 0.002);
    if (projection) {
      project_contacts(system, 0, ground, points, contact);
    }
  }
  return sheet.positions(system.coordinates(0)).col(0).mean() -
         sheet.rest_positions().col(0).mean();
}

TEST(Obstacles, FrictionStopsASlidingSheet) {
  // Without friction the sheet slides 1 in one second (to the O(dt) error of the contact);
  // with Coulomb friction 0.5 it stops after v / (mu g) = 0.2 s, having slid v^2 / (2 mu g) =
  // 0.1 (within 0.05: the penalty's regularization and the projection's impulse per step).
  for (const bool projection : {false, true}) {
    EXPECT_NEAR(slide(projection, 0.0), 1.0, 0.01) << projection;
    EXPECT_NEAR(slide(projection, 0.5), 0.1, 0.05) << projection;
    std::printf("slide %s: friction off %.4f, friction 0.5 %.4f\n",
                projection ? "projection" : "penalty", slide(projection, 0.0),
                slide(projection, 0.5));
  }
}

}  // namespace
}  // namespace dnurbs
