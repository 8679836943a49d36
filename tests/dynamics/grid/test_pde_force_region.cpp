// Tests of dynamics/grid/pde_force_region.h and the box region of dynamics/grid/pde_surface.h
// (Romero 2005, section 5 and figures 11 and 12): the box region simulates the nodes inside the
// box, the force region pushes each node within the force radius, and a moving force's swept
// region gives a node entering the moving region the velocity of the whole-surface solve, where
// rebuilding the region around the centre at every step (the thesis' way) starts it from rest.

#include "dnurbs/dynamics/grid/pde_force_region.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/integrator.h"

namespace dnurbs {
namespace {

// A unit square of 25 by 25 nodes (h = 1/24) in the plane z = 0.
Grid square_grid() {
  return Grid(25, 25, 1.0 / 24.0);
}

NodePositions flat_rest() {
  return flat_grid_positions(square_grid(), Eigen::Vector3d::Zero());
}

TEST(PdeBoxRegion, SimulatesTheNodesStrictlyInsideTheBoxOfNodes) {
  // Nodes with x, y in [0.25, 0.75] are i, j = 6..18: the box border, so 7..17 are active
  DeformationRegion region;
  region.box = Eigen::AlignedBox3d(Eigen::Vector3d(0.25, 0.25, -1), Eigen::Vector3d(0.75, 0.75, 1));
  const PdeSurface surface(square_grid(), flat_rest(), {}, {region});
  ASSERT_EQ(surface.coordinate_count(), 3 * 11 * 11);
  EXPECT_EQ(surface.active_nodes().front(), square_grid().index(7, 7));
  EXPECT_EQ(surface.active_nodes().back(), square_grid().index(17, 17));
}

TEST(PdeBoxRegion, EmptyOrThinBoxesNameTheBox) {
  DeformationRegion empty;
  empty.box = Eigen::AlignedBox3d(Eigen::Vector3d(0.5, 0, 0), Eigen::Vector3d(0.4, 1, 0));
  EXPECT_THROW(
      {
        try {
          const PdeSurface surface(square_grid(), flat_rest(), {}, {empty});
        } catch (const Error& error) {
          EXPECT_NE(std::string(error.what()).find("box region from (0.5, 0, 0)"),
                    std::string::npos);
          throw;
        }
      },
      Error);
  DeformationRegion thin;  // two node columns: no interior node
  thin.box = Eigen::AlignedBox3d(Eigen::Vector3d(0.5, 0, -1), Eigen::Vector3d(0.55, 1, 1));
  EXPECT_THROW(PdeSurface(square_grid(), flat_rest(), {}, {thin}), Error);
}

TEST(PdeForceRegion, PushesEachActiveNodeWithinTheForceRadius) {
  const PdeSurface surface(square_grid(), flat_rest());
  System system(surface);
  const Eigen::Vector3d centre(0.5, 0.5, 0.0);
  system.add_force(0, pde_force_region(
                          surface, [](double) { return Eigen::Vector3d(0.5, 0.5, 0.0); }, 0.1,
                          [](double t) { return Eigen::Vector3d(0, 0, 300.0 * t); }));
  Eigen::VectorXd f = Eigen::VectorXd::Zero(surface.coordinate_count());
  system.add_applied_forces(0.5, system.coordinates(), system.velocities(), f);
  const std::vector<int> nodes = surface.nodes_within(centre, 0.1);
  ASSERT_EQ(nodes.size(), 21U);  // the lattice points within 2.4 spacings of a node
  for (const int slot : nodes) {
    EXPECT_EQ(f(3 * slot + 2), 150.0);
  }
  EXPECT_EQ(f.sum(), 150.0 * 21);
  EXPECT_THROW(pde_force_region(
                   surface, [](double) { return Eigen::Vector3d::Zero(); }, -1.0,
                   [](double) { return Eigen::Vector3d::Zero(); }),
               Error);
}

TEST(PdeForceRegion, ActsOnTheNodesOfTheSurfaceItWasFoundOn) {
  // The rest positions are read from the surface when the force is made: a force made on a
  // region's surface acts on that surface's active nodes, and refuses a model of another size
  DeformationRegion box;
  box.box = Eigen::AlignedBox3d(Eigen::Vector3d(0.25, 0.25, -1), Eigen::Vector3d(0.75, 0.75, 1));
  const PdeSurface region(square_grid(), flat_rest(), {}, {box});
  const Force push = pde_force_region(
      region, [](double) { return Eigen::Vector3d(0.5, 0.5, 0.0); }, 0.1,
      [](double) { return Eigen::Vector3d(0, 0, 1); });
  const Eigen::VectorXd rest = region.initial_coordinates();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(region.velocity_count());
  push(region, 0.0, rest, Eigen::VectorXd::Zero(rest.size()), f);
  const std::vector<int> nodes = region.nodes_within(Eigen::Vector3d(0.5, 0.5, 0.0), 0.1);
  ASSERT_EQ(nodes.size(), 21U);
  EXPECT_EQ(f.sum(), 21.0);
  for (const int slot : nodes) {
    EXPECT_EQ(f(region.control_point_offset(slot) + 2), 1.0);
  }
  const PdeSurface whole(square_grid(), flat_rest());
  const Eigen::VectorXd whole_rest = whole.initial_coordinates();
  Eigen::VectorXd g = Eigen::VectorXd::Zero(whole_rest.size());
  EXPECT_THROW(push(whole, 0.0, whole_rest, Eigen::VectorXd::Zero(whole_rest.size()), g), Error);
}

// A force of 1 per node within 0.08 of a centre that moves from (0.3, 0.5) to (0.7, 0.5) in one
// second.
Eigen::Vector3d moving_centre(double t) {
  return {0.3 + 0.4 * std::clamp(t, 0.0, 1.0), 0.5, 0.0};
}

PdeSurfaceMaterial moving_material() {
  PdeSurfaceMaterial material;
  material.damping_density = 2.0;
  return material;
}

constexpr double kDt = 0.01;
constexpr int kSteps = 100;

// The z velocity of grid node `node` after each step (0 while it is fixed).
std::vector<double> node_velocities(const PdeSurface& surface, int node) {
  System system(surface);
  system.add_force(0, pde_force_region(surface, moving_centre, 0.08,
                                       [](double) { return Eigen::Vector3d(0, 0, 1); }));
  Integrator integrator(IntegratorSettings{IntegratorScheme::kImplicitEuler});
  std::vector<double> v;
  for (int s = 0; s < kSteps; ++s) {
    integrator.step(system, kDt);
    const int slot = surface.active_slot(node);
    v.push_back(slot >= 0 ? system.velocities(0)(3 * slot + 2) : 0.0);
  }
  return v;
}

// The thesis' way: the region is rebuilt around the centre at every step; nodes that stay keep
// their state, nodes that enter start from rest (Romero 2005, section 5: velocity 0 "if the node
// is newly deformed"), nodes that leave are fixed at rest.
std::vector<double> rebuilt_region_velocities(int node, double radius) {
  const NodePositions rest = flat_rest();
  NodePositions positions = rest;
  NodePositions velocities = NodePositions::Zero(square_grid().node_count(), 3);
  std::vector<double> v;
  for (int s = 0; s < kSteps; ++s) {
    const double t = s * kDt;
    const PdeSurface surface(square_grid(), rest, moving_material(), {{moving_centre(t), radius}});
    const int count = static_cast<int>(surface.active_nodes().size());
    Eigen::VectorXd q(3 * count);
    Eigen::VectorXd qd(3 * count);
    for (int a = 0; a < count; ++a) {
      q.segment<3>(3 * a) = positions.row(surface.active_nodes()[a]).transpose();
      qd.segment<3>(3 * a) = velocities.row(surface.active_nodes()[a]).transpose();
    }
    System system(surface);
    system.set_state(q, qd, t);
    system.add_force(0, pde_force_region(surface, moving_centre, 0.08,
                                         [](double) { return Eigen::Vector3d(0, 0, 1); }));
    Integrator integrator(IntegratorSettings{IntegratorScheme::kImplicitEuler});
    integrator.step(system, kDt);
    positions = rest;
    velocities.setZero();
    for (int a = 0; a < count; ++a) {
      positions.row(surface.active_nodes()[a]) = system.coordinates(0).segment<3>(3 * a);
      velocities.row(surface.active_nodes()[a]) = system.velocities(0).segment<3>(3 * a);
    }
    v.push_back(velocities(node, 2));
  }
  return v;
}

struct EntryVelocities {
  int entry = 0;                    // the first step whose region around the centre holds the node
  double whole = 0.0;               // the node's velocity after that step: whole-surface solve
  double swept = 0.0;               // the moving region of swept_deformation_regions
  double rebuilt = 0.0;             // the region rebuilt at every step, entering nodes from rest
  double largest_change = 0.0;      // of the whole-surface velocity in one step: O(dt)
  double largest_jump = 0.0;        // of the swept region's velocity in one step
  double largest_difference = 0.0;  // swept against whole over the run
};

// Grid node (i, 12) under the moving force with deformation radius `radius`.
EntryVelocities entry_velocities(double radius, int i) {
  const int node = square_grid().index(i, 12);
  const PdeSurface whole_surface(square_grid(), flat_rest(), moving_material());
  const PdeSurface swept_surface(
      square_grid(), flat_rest(), moving_material(),
      swept_deformation_regions(moving_centre, radius, 0.0, 1.0, 0.5 * square_grid().spacing()));
  const std::vector<double> whole = node_velocities(whole_surface, node);
  const std::vector<double> swept = node_velocities(swept_surface, node);
  const std::vector<double> rebuilt = rebuilt_region_velocities(node, radius);
  EntryVelocities result;
  while (result.entry < kSteps &&
         PdeSurface(square_grid(), flat_rest(), {}, {{moving_centre(result.entry * kDt), radius}})
                 .active_slot(node) < 0) {
    ++result.entry;
  }
  const auto e = static_cast<size_t>(std::min(result.entry, kSteps - 1));
  result.whole = whole[e];
  result.swept = swept[e];
  result.rebuilt = rebuilt[e];
  for (size_t s = 1; s < whole.size(); ++s) {
    result.largest_change = std::max(result.largest_change, std::abs(whole[s] - whole[s - 1]));
    result.largest_jump = std::max(result.largest_jump, std::abs(swept[s] - swept[s - 1]));
    result.largest_difference = std::max(result.largest_difference, std::abs(swept[s] - whole[s]));
  }
  std::printf(
      "radius %.2f node (%d, 12) enters at step %d: v = %.6g whole, %.6g swept, %.6g "
      "rebuilt; largest step change %.4g whole, %.4g swept\n",
      radius, i, result.entry, result.whole, result.swept, result.rebuilt, result.largest_change,
      result.largest_jump);
  return result;
}

TEST(PdeMovingForce, SweptRegionCoveringTheGridIsTheWholeSurfaceSolve) {
  // Radius 0.5 around a centre moving from x = 0.3 to 0.7 sweeps every interior node; node
  // (19, 12) enters the region around the centre at step 9 (x = 0.3333 + 0.5 > 20/24)
  const EntryVelocities v = entry_velocities(0.5, 19);
  ASSERT_EQ(v.entry, 9);
  ASSERT_GT(std::abs(v.whole), 1e-4);
  EXPECT_LE(v.largest_difference, 1e-12);  // the same equations, round-off only
  EXPECT_LE(v.largest_jump, v.largest_change + 1e-12);
  // Starting it from rest misses its velocity by more than half
  EXPECT_GT(std::abs(v.rebuilt - v.whole), 0.5 * std::abs(v.whole));
}

TEST(PdeMovingForce, NodeEnteringTheMovingRegionKeepsTheWholeSurfaceVelocity) {
  // Radius 0.3: node (21, 12) enters the region around the centre at step 80; the swept region is
  // a band about y = 0.5, so it differs from the whole grid by its border's truncation
  // (PdeSurface.DeformationRegionErrorFallsAsItsRadiusGrows), measured 6 % of the velocity
  const EntryVelocities v = entry_velocities(0.3, 21);
  ASSERT_EQ(v.entry, 80);
  ASSERT_GT(std::abs(v.whole), 1e-3);
  // Continuous: no step changes the swept region's velocity more than the whole surface's
  EXPECT_LE(v.largest_jump, v.largest_change);
  EXPECT_NEAR(v.swept, v.whole, 0.1 * std::abs(v.whole));
  // The region rebuilt around the centre (from rest) fails the same check
  EXPECT_GT(std::abs(v.rebuilt - v.whole), 0.1 * std::abs(v.whole));
}

TEST(PdeMovingForce, SweptRegionsFollowThePathAndNameBadValues) {
  const std::vector<DeformationRegion> still = swept_deformation_regions(
      [](double) { return Eigen::Vector3d(0.5, 0.5, 0); }, 0.2, 0.0, 1.0, 0.02);
  ASSERT_EQ(still.size(), 1U);
  EXPECT_EQ(still[0].deformation_radius, 0.22);
  const std::vector<DeformationRegion> moving =
      swept_deformation_regions(moving_centre, 0.2, 0.0, 1.0, 0.02);
  ASSERT_EQ(moving.size(), 33U);  // 0.4 over 32 samples: 0.0125 < 0.02 (16 gave 0.025)
  EXPECT_EQ(moving.back().centre.x(), 0.7);
  EXPECT_THROW(swept_deformation_regions(moving_centre, 0.0, 0.0, 1.0, 0.02), Error);
  EXPECT_THROW(swept_deformation_regions(moving_centre, 0.2, 1.0, 0.0, 0.02), Error);
  EXPECT_THROW(swept_deformation_regions(moving_centre, 0.2, 0.0, 1.0, 0.0), Error);
}

}  // namespace
}  // namespace dnurbs
