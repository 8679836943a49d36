#include "dnurbs/dynamics/grid/pde_surface.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/integrator.h"

namespace dnurbs {
namespace {

// A unit square of 25 by 25 nodes (h = 1/24) in the plane z = 0.
Grid square_grid() {
  return Grid(25, 25, 1.0 / 24.0);
}

PdeSurfaceMaterial damped_material() {
  PdeSurfaceMaterial material;
  material.damping_density = 20.0;  // settles within the simulated second
  return material;
}

struct PdeRun {
  NodePositions positions;
  int coordinates = 0;
};

// One second (24 frames of 10 implicit-Euler sub-steps) under a force of 1 (total) on the nodes
// within 0.08 of each centre; regions of the given deformation radius (none: the whole grid).
PdeRun simulate(const std::vector<Eigen::Vector3d>& centres, double deformation_radius,
                const PdeSurfaceMaterial& material = damped_material()) {
  const Grid grid = square_grid();
  const NodePositions rest = flat_grid_positions(grid, Eigen::Vector3d::Zero());
  std::vector<DeformationRegion> regions;
  if (deformation_radius > 0.0) {
    for (const Eigen::Vector3d& centre : centres) {
      regions.push_back({centre, deformation_radius});
    }
  }
  const PdeSurface surface(grid, rest, material, regions);
  System system(surface);
  for (const Eigen::Vector3d& centre : centres) {
    const std::vector<int> nodes = surface.nodes_within(centre, 0.08);
    const Eigen::Vector3d per_node(0, 0, 1.0 / static_cast<double>(nodes.size()));
    system.add_force(0, control_point_force(nodes, [per_node](double) { return per_node; }));
  }
  Integrator integrator(IntegratorSettings{IntegratorScheme::kImplicitEuler});
  for (int frame = 0; frame < 24; ++frame) {
    advance_frame(integrator, system, 1.0 / 240.0);
  }
  EXPECT_EQ(integrator.factorization_count(), 1);  // constant matrices: factored once
  return {surface.positions(system.coordinates(0)), surface.coordinate_count()};
}

TEST(PdeSurface, CurvedRestMeshWithoutForceStaysAtRest) {
  // The PDE acts on the displacement from the rest mesh: any rest mesh is an equilibrium. f_int
  // is exactly zero at rest, so the state does not change at all.
  const Grid grid(9, 7, 0.125);
  NodePositions rest = flat_grid_positions(grid, Eigen::Vector3d::Zero());
  for (int k = 0; k < grid.node_count(); ++k) {
    rest(k, 2) = std::sin(3 * rest(k, 0)) * std::cos(2 * rest(k, 1));
  }
  System system(PdeSurface(grid, rest, damped_material()));
  const Eigen::VectorXd initial = system.coordinates();
  Integrator integrator(IntegratorSettings{IntegratorScheme::kNewmark});
  for (int s = 0; s < 1000; ++s) {
    integrator.step(system, 0.01);
  }
  EXPECT_EQ((system.coordinates() - initial).cwiseAbs().maxCoeff(), 0.0);
}

TEST(PdeSurface, InternalForceIsMinusTheEnergyGradient) {
  // E = (1/2) d^T K d - t . d is quadratic: central differences are exact up to round-off
  // (~1e-16 E / step); 1e-6 relative.
  const Grid grid(7, 6, 0.2);
  PdeSurfaceMaterial material;
  material.b = 0.7;
  material.c = 1.3;
  material.d = 0.4;
  material.tangent_u0 = 0.5;
  material.tangent_v1 = -0.25;
  const PdeSurface surface(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()), material);
  Eigen::VectorXd q = surface.initial_coordinates();
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    q[i] += 0.01 * std::sin(1.7 * static_cast<double>(i));
  }
  Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
  surface.add_internal_force(q, force);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    Eigen::VectorXd plus = q;
    Eigen::VectorXd minus = q;
    plus[i] += 1e-5;
    minus[i] -= 1e-5;
    worst = std::max(
        worst, std::abs(force[i] +
                        (surface.potential_energy(plus) - surface.potential_energy(minus)) / 2e-5));
  }
  EXPECT_LE(worst, 1e-6 * force.cwiseAbs().maxCoeff());
  // K is symmetric: eq 8's central differences with the ghost-node boundary.
  const SparseMatrix& k = surface.constant_matrices()->stiffness;
  EXPECT_EQ((Eigen::MatrixXd(k) - Eigen::MatrixXd(k).transpose()).cwiseAbs().maxCoeff(), 0.0);
}

TEST(PdeSurface, RegionCoveringTheWholeGridAgreesWithTheWholeGrid) {
  // A deformation radius larger than the grid makes the region's box the whole grid: the same
  // active nodes, the same matrices, the same steps. 1e-12 allows for nothing but round-off.
  const Eigen::Vector3d centre(0.5, 0.5, 0.0);
  const PdeRun whole = simulate({centre}, 0.0);
  const PdeRun covering = simulate({centre}, 10.0);
  EXPECT_EQ(whole.coordinates, covering.coordinates);
  EXPECT_LE((whole.positions - covering.positions).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(PdeSurface, DeformationRegionErrorFallsAsItsRadiusGrows) {
  // Simulating only the deformation region clamps the surface at the region's border: the
  // displacement error against the whole grid falls as the radius grows, and the cost (the
  // number of simulated nodes) rises.
  const Eigen::Vector3d centre(0.5, 0.5, 0.0);
  const PdeRun whole = simulate({centre}, 0.0);
  const double peak = whole.positions.col(2).cwiseAbs().maxCoeff();
  double previous_error = std::numeric_limits<double>::infinity();
  for (const double radius : {0.2, 0.3, 0.4, 0.5}) {
    const PdeRun region = simulate({centre}, radius);
    const double error = (region.positions - whole.positions).rowwise().norm().maxCoeff();
    const double cost = static_cast<double>(region.coordinates) / whole.coordinates;
    std::printf(
        "PDE region radius %.2f: displacement error %.3e (relative %.3e), cost ratio "
        "%.3f (%d of %d coordinates)\n",
        radius, error, error / peak, cost, region.coordinates, whole.coordinates);
    ::testing::Test::RecordProperty("relative_error_radius_" + std::to_string(radius),
                                    std::to_string(error / peak));
    EXPECT_LT(error, previous_error) << "radius " << radius;
    EXPECT_LT(cost, 1.0);
    previous_error = error;
  }
}

TEST(PdeSurface, SeveralForcesAtOnceSimulateTheUnionOfTheirRegions) {
  // Two forces with regions of radius 0.15 at opposite corners: two disjoint boxes, each node
  // inside one of them active, the rest fixed and untouched.
  const std::vector<Eigen::Vector3d> centres{{0.25, 0.25, 0.0}, {0.75, 0.75, 0.0}};
  const PdeRun run = simulate(centres, 0.15);
  const Grid grid = square_grid();
  const PdeSurface surface(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()),
                           damped_material(), {{centres[0], 0.15}, {centres[1], 0.15}});
  EXPECT_LT(surface.coordinate_count(), 3 * grid.node_count() / 4);
  EXPECT_GT(run.positions(grid.index(6, 6), 2), 0.0);    // near the first force
  EXPECT_GT(run.positions(grid.index(18, 18), 2), 0.0);  // near the second
  EXPECT_EQ(run.positions(grid.index(18, 6), 2), 0.0);   // outside both regions
}

TEST(PdeSurface, BoundaryTangentsDeformWithoutForce) {
  // Romero 2005, figure 9: su0 != 0 lifts the surface along the rest normal (+z) near u = 0.
  PdeSurfaceMaterial material = damped_material();
  material.tangent_u0 = 1.0;
  const Grid grid = square_grid();
  const PdeSurface surface(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()), material);
  System system(surface);
  Integrator integrator(IntegratorSettings{IntegratorScheme::kImplicitEuler});
  for (int frame = 0; frame < 24; ++frame) {
    EXPECT_EQ(advance_frame(integrator, system, 1.0 / 240.0), 10);
  }
  EXPECT_NEAR(system.time(), 1.0, 1e-12);  // 240 steps of 1/240: round-off only
  const NodePositions r = surface.positions(system.coordinates(0));
  EXPECT_GT(r(grid.index(2, 12), 2), 0.0);
  EXPECT_GT(r(grid.index(2, 12), 2), 10.0 * std::abs(r(grid.index(22, 12), 2)));
}

TEST(PdeSurface, BadInputNamesTheValue) {
  const Grid grid = square_grid();
  const NodePositions rest = flat_grid_positions(grid, Eigen::Vector3d::Zero());
  const auto message = [&](auto&& make) -> std::string {
    try {
      make();
    } catch (const Error& error) {
      return error.what();
    }
    return "no error";
  };
  PdeSurfaceMaterial negative;
  negative.b = -1.5;
  EXPECT_NE(message([&] { PdeSurface(grid, rest, negative); }).find("-1.5"), std::string::npos);
  PdeSurfaceMaterial not_finite;
  not_finite.tangent_u1 = std::nan("");
  EXPECT_NE(message([&] { PdeSurface(grid, rest, not_finite); }).find("su1"), std::string::npos);
  EXPECT_NE(message([&] {
              PdeSurface(grid, rest, {}, {{Eigen::Vector3d(0.5, 0.5, 0), 0.03}});
            }).find("0.03"),
            std::string::npos);
  EXPECT_NE(message([&] {
              const Grid small(25, 2, 0.1);
              PdeSurface(small, flat_grid_positions(small, Eigen::Vector3d::Zero()));
            }).find("25 by 2"),
            std::string::npos);
  System system(PdeSurface(grid, rest));
  Integrator integrator;
  EXPECT_THROW(advance_frame(integrator, system, 0.0), Error);
  EXPECT_THROW(advance_frame(integrator, system, 0.01, -24.0), Error);
}

}  // namespace
}  // namespace dnurbs
