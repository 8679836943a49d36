#include "dnurbs/dynamics/grid/pde_surface.h"

#include <cmath>
#include <cstdint>
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

// Keyable material (Romero 2005, section 5.2.1.2): a 13 by 13 grid (h = 1/12) pushed by 1 per
// node within 0.2 of its centre, stepped by `scheme` in steps of 1/200.
struct MaterialRun {
  explicit MaterialRun(const PdeSurface& surface, IntegratorScheme scheme)
      : system(surface), integrator(IntegratorSettings{scheme}) {
    system.add_force(0, control_point_force(surface.nodes_within(Eigen::Vector3d(0.5, 0.5, 0), 0.2),
                                            [](double) { return Eigen::Vector3d(0, 0, 1); }));
  }
  void steps(int count) {
    for (int s = 0; s < count; ++s) {
      integrator.step(system, 1.0 / 200.0);
    }
  }
  System system;
  Integrator integrator;
};

Grid small_grid() {
  return Grid(13, 13, 1.0 / 12.0);
}

PdeSurface small_surface(const PdeSurfaceMaterial& material) {
  return PdeSurface(small_grid(), flat_grid_positions(small_grid(), Eigen::Vector3d::Zero()),
                    material);
}

// Every coefficient changes: stiffer along u, softer along v, lighter, damped, tangents set.
PdeSurfaceMaterial jumped_material() {
  PdeSurfaceMaterial m;
  m.b = 4.0;
  m.c = 1.0;
  m.d = 0.5;
  m.mass_density = 0.5;
  m.damping_density = 3.0;
  m.tangent_u0 = 0.3;
  m.tangent_v1 = -0.2;
  return m;
}

TEST(PdeSurfaceMaterial, JumpEqualsARestartWithTheNewMaterial) {
  // A run whose material jumps after 40 steps (System::set_material_parameters) against one that
  // stops there and continues as a new System of a new surface with the new material, from the
  // same positions, velocities and time. A factorization kept from before the jump would step
  // the old material on; the two runs must instead agree to round-off.
  for (const IntegratorScheme scheme :
       {IntegratorScheme::kCentral, IntegratorScheme::kImplicitEuler, IntegratorScheme::kNewmark}) {
    SCOPED_TRACE(std::string(to_string(scheme)));
    const PdeSurface before = small_surface(PdeSurfaceMaterial{});
    MaterialRun jumped(before, scheme);
    jumped.steps(40);
    ASSERT_TRUE(
        jumped.system.set_material_parameters(0, pde_material_parameters(jumped_material())));
    jumped.steps(40);
    EXPECT_EQ(jumped.integrator.factorization_count(), 2);  // once per material

    MaterialRun first(before, scheme);
    first.steps(40);
    MaterialRun restarted(small_surface(jumped_material()), scheme);
    restarted.system.set_state(first.system.coordinates(), first.system.velocities(),
                               first.system.time());
    restarted.steps(40);
    MaterialRun unchanged(before, scheme);
    unchanged.steps(80);

    const Eigen::VectorXd rest = before.initial_coordinates();
    const Eigen::VectorXd q = jumped.system.coordinates() - rest;
    const Eigen::VectorXd q_restarted = restarted.system.coordinates() - rest;
    ASSERT_GT(q_restarted.norm(), 1e-3);
    // The same matrices (set_material and the constructor combine the same unit matrices) and
    // the same state: round-off only
    EXPECT_LE((q - q_restarted).norm(), 1e-12 * q_restarted.norm());
    EXPECT_LE((jumped.system.velocities() - restarted.system.velocities()).norm(),
              1e-12 * restarted.system.velocities().norm());
    // ... and the jump matters: the old material would be far off
    EXPECT_GT((unchanged.system.coordinates() - rest - q_restarted).norm(),
              0.1 * q_restarted.norm());
  }
}

TEST(PdeSurfaceMaterial, TangentsAloneKeepTheFactorization) {
  // Keyed tangents change the force t, not M, D or K: the run keeps its factorization and still
  // equals a restart with the new tangents
  PdeSurfaceMaterial tangents;
  tangents.tangent_u0 = 0.5;
  tangents.tangent_v1 = -0.25;
  const PdeSurface before = small_surface(PdeSurfaceMaterial{});
  MaterialRun jumped(before, IntegratorScheme::kNewmark);
  jumped.steps(40);
  const std::uint64_t revision = jumped.system.revision();
  ASSERT_TRUE(jumped.system.set_material_parameters(0, pde_material_parameters(tangents)));
  EXPECT_EQ(jumped.system.revision(), revision);
  jumped.steps(40);
  EXPECT_EQ(jumped.integrator.factorization_count(), 1);
  MaterialRun first(before, IntegratorScheme::kNewmark);
  first.steps(40);
  MaterialRun restarted(small_surface(tangents), IntegratorScheme::kNewmark);
  restarted.system.set_state(first.system.coordinates(), first.system.velocities(),
                             first.system.time());
  restarted.steps(40);
  const Eigen::VectorXd q = restarted.system.coordinates() - before.initial_coordinates();
  EXPECT_LE((jumped.system.coordinates() - restarted.system.coordinates()).norm(),
            1e-12 * q.norm());
}

TEST(PdeSurfaceMaterial, SetMaterialGivesTheFreshSurfaceAndRefusesBadValues) {
  PdeSurface surface = small_surface(PdeSurfaceMaterial{});
  surface.set_material(jumped_material());
  const PdeSurface fresh = small_surface(jumped_material());
  const auto same = [](const SparseMatrix& a, const SparseMatrix& b) {
    return a.nonZeros() == b.nonZeros() && SparseMatrix(a - b).norm() == 0.0;
  };
  EXPECT_TRUE(same(surface.constant_matrices()->stiffness, fresh.constant_matrices()->stiffness));
  EXPECT_TRUE(same(surface.constant_matrices()->mass, fresh.constant_matrices()->mass));
  EXPECT_TRUE(same(surface.constant_matrices()->damping, fresh.constant_matrices()->damping));
  EXPECT_EQ(surface.tangent_force(), fresh.tangent_force());
  EXPECT_EQ(surface.material_parameters(), pde_material_parameters(jumped_material()));
  // K is linear in (b, c, d): b = c = d = 0 leaves no stiffness, and the tangents no force
  PdeSurfaceMaterial loose = jumped_material();
  loose.b = loose.c = loose.d = 0.0;
  surface.set_material(loose);
  EXPECT_EQ(surface.constant_matrices()->stiffness.nonZeros(), 0);
  EXPECT_EQ(surface.tangent_force().norm(), 0.0);

  // A bad value is named and changes nothing
  PdeSurfaceMaterial bad = jumped_material();
  bad.mass_density = -0.25;
  try {
    surface.set_material(bad);
    ADD_FAILURE() << "a negative density was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("-0.25"), std::string::npos);
  }
  EXPECT_EQ(surface.material_parameters(), pde_material_parameters(loose));
  EXPECT_THROW(surface.set_material_parameters(Eigen::VectorXd::Ones(8)), Error);

  // Through a System: equal values change nothing (no refactorization), bad ones throw and
  // leave the model as it was; an index out of range is refused
  MaterialRun run(small_surface(PdeSurfaceMaterial{}), IntegratorScheme::kImplicitEuler);
  run.steps(2);
  const std::uint64_t revision = run.system.revision();
  EXPECT_FALSE(run.system.set_material_parameters(0, pde_material_parameters({})));
  run.steps(2);
  EXPECT_EQ(run.system.revision(), revision);
  EXPECT_EQ(run.integrator.factorization_count(), 1);
  Eigen::VectorXd nan = pde_material_parameters({});
  nan(2) = std::nan("");
  EXPECT_THROW(run.system.set_material_parameters(0, nan), Error);
  EXPECT_EQ(run.system.revision(), revision);
  EXPECT_THROW(run.system.set_material_parameters(1, nan), Error);
}

}  // namespace
}  // namespace dnurbs
