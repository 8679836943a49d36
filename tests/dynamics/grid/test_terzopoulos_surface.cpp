#include "dnurbs/dynamics/grid/terzopoulos_surface.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/line_force.h"
#include "dnurbs/dynamics/core/obstacles.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/integrators/semi_implicit_step.h"
#include "dnurbs/surface/triangle_mesh.h"
#include "tests/common/grid_scenes.h"

namespace dnurbs {
namespace {

using test::asymmetry;
using test::max_curvature;
using test::sheet_material;
using test::tangential_drift;
using test::unit_square_grid;

constexpr std::array<NormalApproximation, 3> kApproximations{
    NormalApproximation::kClassic, NormalApproximation::kChristoffel,
    NormalApproximation::kChristoffelUnnormalized};

struct PaperResult {
  double asymmetry = 0.0;
  test::Drift drift;
  double max_curvature = 0.0;
  double max_deflection = 0.0;
};

// The paper scene of Wu & de Melo, figures 5 and 7 on a 17 by 17 unit sheet: border clamped, eta_ii
// = 0.1 (paper hardly stretches), gamma = 0.5, a normal force of 0.01 pressed on the 3 by 3 nodes
// at the centre, stepped 400 times with dt = 0.005 semi-implicitly as in the seed (matrix from
// the current tensors).
PaperResult run_paper_scene(NormalApproximation normal, double xi) {
  const Grid grid = unit_square_grid(17);
  TerzopoulosSettings settings;
  settings.normal = normal;
  TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()),
                           sheet_material(0.1, 0.0, xi, 0.5), settings);
  sheet.fix_border();
  System system(sheet);
  const double force = 0.01;
  for (int j = 7; j <= 9; ++j) {
    for (int i = 7; i <= 9; ++i) {
      system.add_force(0, point_force(grid.parameter(i, j), Eigen::Vector3d(0, 0, -force / 9)));
    }
  }
  SemiImplicitStepper stepper;
  for (int s = 0; s < 400; ++s) {
    stepper.step(system, 0.005);
  }
  const NodePositions d = sheet.positions(system.coordinates(0)) - sheet.rest_positions();
  PaperResult result;
  result.asymmetry = asymmetry(grid, d);
  result.drift = tangential_drift(sheet.rest_positions(), d);
  result.max_curvature = max_curvature(sheet, system.coordinates(0));
  result.max_deflection = d.col(2).cwiseAbs().maxCoeff();
  std::printf(
      "paper xi = %g %-11s asymmetry %.3e tangential %.3e rotation %.3e max |B| %.4e "
      "max deflection %.4e\n",
      xi, to_string(normal), result.asymmetry, result.drift.tangential, result.drift.rotation,
      result.max_curvature, result.max_deflection);
  return result;
}

// Each scene is run once per test program (two tests share xi = 1e-4).
PaperResult paper_scene(NormalApproximation normal, double xi) {
  static std::map<std::pair<int, double>, PaperResult> results;
  const auto key = std::make_pair(static_cast<int>(normal), xi);
  const auto found = results.find(key);
  if (found != results.end()) {
    return found->second;
  }
  return results[key] = run_paper_scene(normal, xi);
}

TEST(TerzopoulosSurface, FlatSheetAtRestStaysAtRestFor10000Steps) {
  // A 7 by 7 sheet with every weight non-zero and no force: G = G0 and B = B0 = 0 exactly, so
  // alpha = beta = 0 and nothing moves; 1e-12 bounds any round-off (there is none to expect).
  const Grid grid(7, 7, 1.0 / 6.0);
  for (const NormalApproximation normal : kApproximations) {
    TerzopoulosSettings settings;
    settings.normal = normal;
    TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d(0.3, -0.2, 1.0)),
                             sheet_material(0.01, 0.006, 1e-4, 0.1), settings);
    sheet.fix_point(0);
    System seed_system(sheet);
    System common_system(sheet);
    SemiImplicitStepper stepper;
    Integrator integrator(IntegratorSettings{IntegratorScheme::kCentral});
    for (int s = 0; s < 10000; ++s) {
      stepper.step(seed_system, 0.01);
      integrator.step(common_system, 0.01);
    }
    const Eigen::VectorXd rest = sheet.initial_coordinates();
    EXPECT_LE((seed_system.coordinates() - rest).cwiseAbs().maxCoeff(), 1e-12) << to_string(normal);
    EXPECT_LE((common_system.coordinates() - rest).cwiseAbs().maxCoeff(), 1e-12)
        << to_string(normal);
  }
}

TEST(TerzopoulosSurface, StretchingForceIsMinusTheEnergyGradient) {
  // xi = 0: the model's force -h^2 sum_ij (D+_i)^T alpha_ij D+_j r is exactly -dE/dr of
  // E = (h^2/4) sum eta_ij (G_ij - G0_ij)^2. Central differences of E with step 1e-6 have
  // truncation error ~1e-12 times E''' and round-off ~1e-16 E / 1e-6; 1e-7 relative covers both.
  const Grid grid(5, 6, 0.25);
  NodePositions rest = flat_grid_positions(grid, Eigen::Vector3d::Zero());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  TerzopoulosSurface surface(grid, rest, sheet_material(0.3, 0.1, 0.0));
  for (int k = 0; k < grid.node_count(); ++k) {
    Eigen::Matrix2d eta;
    const double off = 0.05 + 0.01 * (k % 3);
    eta << 0.2 + 0.01 * k, off, off, 0.4 - 0.005 * k;
    surface.set_node_elasticity(k, eta, Eigen::Matrix2d::Zero());
  }
  Eigen::VectorXd q = surface.initial_coordinates();
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    q[i] += jitter(random);
  }
  Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
  surface.add_internal_force(q, force);
  const double step = 1e-6;
  double worst = 0.0;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    Eigen::VectorXd plus = q;
    Eigen::VectorXd minus = q;
    plus[i] += step;
    minus[i] -= step;
    const double gradient =
        (surface.potential_energy(plus) - surface.potential_energy(minus)) / (2 * step);
    worst = std::max(worst, std::abs(force[i] + gradient));
  }
  EXPECT_LE(worst, 1e-7 * force.cwiseAbs().maxCoeff());
  EXPECT_GT(force.cwiseAbs().maxCoeff(), 1e-3);  // the test is not vacuous
}

// A paraboloid z = a (u^2 + v^2) over a 9 by 9 grid (h = 0.1): B_11 = B_22 = 2a / |r_u x r_v|
// (to the differences' error), B_12 = 0.
NodePositions paraboloid(const Grid& grid, double a) {
  NodePositions r = flat_grid_positions(grid, Eigen::Vector3d(-0.4, -0.4, 0.0));
  for (int k = 0; k < grid.node_count(); ++k) {
    r(k, 2) = a * (r(k, 0) * r(k, 0) + r(k, 1) * r(k, 1));
  }
  return r;
}

TEST(TerzopoulosSurface, ChristoffelNormalIsTheUnitNormalAboveDelta) {
  // Wu & de Melo, eqs. 23-24: with |B| > delta (a = 2: B ~ 4) the Gauss formula gives the unit
  // normal at the coefficients' own state; eqs 25-26: below delta (a = -0.05: B ~ -0.1) it is
  // -[r_ij - Gamma r_k] = -B n. Exact identities of the discrete quantities: 1e-12 (round-off).
  const Grid grid(9, 9, 0.1);
  for (const double a : {2.0, -0.05}) {
    const TerzopoulosSurface surface(grid, paraboloid(grid, a));
    const Eigen::VectorXd q = surface.initial_coordinates();
    const auto normals = surface.approximate_normals(q, q);
    const SurfaceTensors tensors = surface.tensors(q);
    const TriangleMesh mesh = grid_triangle_mesh(grid, surface.positions(q));
    for (int k = 0; k < grid.node_count(); ++k) {
      const auto [i, j] = grid.node(k);
      if (i == 0 || i == 8) {
        EXPECT_EQ(normals[0].row(k).norm(), 0.0);  // D+_11 not computable: no normal
        continue;
      }
      const Eigen::RowVector3d n = mesh.normals.row(k);  // the unit normal of the tangents
      const double b = tensors.curvature(k, 0);
      const Eigen::RowVector3d expected = std::abs(b) > 0.5 ? n : Eigen::RowVector3d(-b * n);
      EXPECT_LE((normals[0].row(k) - expected).norm(), 1e-12) << "a " << a << " node " << k;
      EXPECT_GT(std::abs(b), a > 0 ? 1.0 : 0.01);
      EXPECT_LT(std::abs(b), a > 0 ? 10.0 : 0.5);
    }
  }
}

// Coordinates q (3 per node) of node positions.
Eigen::VectorXd coordinates_of(const NodePositions& r) {
  Eigen::VectorXd q(3 * r.rows());
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(q.data(), r.rows(), 3) = r;
  return q;
}

TerzopoulosSurface surface_with(const Grid& grid, const NodePositions& rest,
                                NormalApproximation normal, double xi = 0.0) {
  TerzopoulosSettings settings;
  settings.normal = normal;
  return {grid, rest, sheet_material(0.0, 0.0, xi), settings};
}

TEST(TerzopoulosSurface, UnnormalizedNormalIsBTimesTheUnitNormal) {
  // Wu & de Melo, section 4, first attempt (|B_ij| = 1, figure 6): the Gauss formula's bracket
  // is B_ij n at the coefficients' own state, so the unnormalized estimate is |B_ij| n at every
  // node, the normalized one (eqs 24-26, delta = 0.5) n above delta and the same |B_ij| n below
  // it. On the paraboloid a = 2 (B_11 = 4 / |r_u x r_v|, about 1.8 to 4.0) the unnormalized normal
  // is up to 4 times as long, and its bending force (flat rest shape, xi = 1e-3) is 2.08 times the
  // normalized one's (the Weingarten terms of eq 22 do not depend on n); at a = -0.05 (|B| < 0.1 <
  // delta) the two are the same operator, bit for bit. Identities of the discrete quantities:
  // 1e-12.
  const Grid grid(9, 9, 0.1);
  for (const double a : {2.0, -0.05}) {
    const NodePositions shape = paraboloid(grid, a);
    const Eigen::VectorXd q = coordinates_of(shape);
    const TerzopoulosSurface unnormalized =
        surface_with(grid, shape, NormalApproximation::kChristoffelUnnormalized);
    const TerzopoulosSurface normalized =
        surface_with(grid, shape, NormalApproximation::kChristoffel);
    const auto long_normals = unnormalized.approximate_normals(q, q);
    const auto unit_normals = normalized.approximate_normals(q, q);
    const SurfaceTensors tensors = unnormalized.tensors(q);
    const TriangleMesh mesh = grid_triangle_mesh(grid, shape);
    double longest = 0.0;
    for (int k = 0; k < grid.node_count(); ++k) {
      const auto [i, j] = grid.node(k);
      if (i == 0 || i == 8) {
        continue;  // D+_11 not computable: no normal (ChristoffelNormalIsTheUnitNormalAboveDelta)
      }
      const Eigen::RowVector3d n = mesh.normals.row(k);
      const double b = tensors.curvature(k, 0);
      EXPECT_LE((long_normals[0].row(k) - std::abs(b) * n).norm(), 1e-12) << "a " << a;
      longest = std::max(longest, long_normals[0].row(k).norm());
      if (std::abs(b) <= 0.5) {
        EXPECT_EQ(long_normals[0].row(k), unit_normals[0].row(k)) << "a " << a;
      }
    }
    const NodePositions flat = flat_grid_positions(grid, Eigen::Vector3d(-0.4, -0.4, 0.0));
    Eigen::VectorXd long_force = Eigen::VectorXd::Zero(q.size());
    Eigen::VectorXd unit_force = Eigen::VectorXd::Zero(q.size());
    surface_with(grid, flat, NormalApproximation::kChristoffelUnnormalized, 1e-3)
        .add_internal_force(q, long_force);
    surface_with(grid, flat, NormalApproximation::kChristoffel, 1e-3)
        .add_internal_force(q, unit_force);
    const double ratio = long_force.norm() / unit_force.norm();
    std::printf("paraboloid a = %g: longest unnormalized normal %.4f, force ratio %.4f\n", a,
                longest, ratio);
    if (a > 0) {
      EXPECT_GT(longest, 3.9);
      EXPECT_LT(longest, 4.1);
      EXPECT_NEAR(ratio, 2.08, 0.01);
    } else {
      EXPECT_LT(longest, 0.1);
      EXPECT_EQ(ratio, 1.0);
    }
  }
}

TEST(TerzopoulosSurface, LaggedNormalsConvergeAtFirstOrderInTheStep) {
  // Wu & de Melo, section 4: n_k uses B and Gamma of the state k-1, so it is linear in r_k. Its
  // error against the estimate built at state k itself (the unit normal for the normalized
  // variant above delta, |B| n for the unnormalized one) is O(|r_k - r_(k-1)|): halving the
  // step from the paraboloid a = 2 to a = 2 + eps halves the error (finite differences of the
  // coefficients, measured orders 1.00).
  const Grid grid(9, 9, 0.1);
  const Eigen::VectorXd previous = coordinates_of(paraboloid(grid, 2.0));
  for (const auto normal :
       {NormalApproximation::kChristoffel, NormalApproximation::kChristoffelUnnormalized}) {
    const TerzopoulosSurface surface = surface_with(grid, paraboloid(grid, 2.0), normal);
    std::array<double, 2> error{};
    for (size_t halving = 0; halving < 2; ++halving) {
      const double eps = 1e-3 / static_cast<double>(1 + halving);
      const Eigen::VectorXd q = coordinates_of(paraboloid(grid, 2.0 + eps));
      const auto lagged = surface.approximate_normals(previous, q);
      const auto exact = surface.approximate_normals(q, q);
      for (size_t c = 0; c < 3; ++c) {
        error[halving] = std::max(error[halving], (lagged[c] - exact[c]).cwiseAbs().maxCoeff());
      }
    }
    const double order = std::log2(error[0] / error[1]);
    std::printf("%s lagged normal: error %.3e at eps 1e-3, order %.3f\n", to_string(normal),
                error[0], order);
    EXPECT_GT(error[1], 1e-8);  // not vacuous
    EXPECT_NEAR(order, 1.0, 0.02);
  }
}

TEST(TerzopoulosSurface, ClassicStiffnessIsSymmetricAndGivesTheForce) {
  // The classic K(q) is symmetric (adjoint differences); f_int = -K(q) q to round-off.
  const Grid grid(6, 5, 0.2);
  TerzopoulosSurface surface(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()),
                             sheet_material(0.2, 0.05, 0.01));
  Eigen::VectorXd q = surface.initial_coordinates();
  std::mt19937 random(3);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    q[i] += jitter(random);
  }
  const SparseMatrix k = surface.linearized_stiffness(q);
  EXPECT_LE((Eigen::MatrixXd(k) - Eigen::MatrixXd(k).transpose()).cwiseAbs().maxCoeff(),
            1e-12 * Eigen::MatrixXd(k).cwiseAbs().maxCoeff());  // round-off of the products
  ModelMatrices matrices;
  surface.assemble_matrices(q, matrices);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
  surface.add_internal_force(q, force);
  EXPECT_LE((force + matrices.stiffness * q).cwiseAbs().maxCoeff(),
            1e-12 * force.cwiseAbs().maxCoeff() + 1e-15);
}

TEST(PaperScene, ChristoffelKeepsFourFoldSymmetryAndDriftsLessThanClassic) {
  // Wu & de Melo, figures 5-8: with the largest curving resistance of figure 7 (xi = 1e-4) the
  // classic normal (r_ij) folds and rotates the pressed sheet; the Christoffel normal keeps it
  // nearly four-fold symmetric without rotation. Forward differences are not mirror-symmetric,
  // so neither is exact; the in-plane displacement includes the physical pull toward the load.
  // Measured: christoffel asymmetry 5.4e-2, in-plane 0.10, rotation ~1e-16; classic (folded,
  // chaotic: its digits change with round-off) ~1.2, ~1.2, ~2e-2. The bounds leave margins of
  // 4x and more.
  const PaperResult classic = paper_scene(NormalApproximation::kClassic, 1e-4);
  const PaperResult christoffel = paper_scene(NormalApproximation::kChristoffel, 1e-4);
  EXPECT_LT(christoffel.asymmetry, 0.2 * classic.asymmetry);
  EXPECT_LT(christoffel.drift.tangential, 0.5 * classic.drift.tangential);
  EXPECT_LT(christoffel.drift.rotation, classic.drift.rotation);
  EXPECT_LT(christoffel.asymmetry, 0.1);
  // Figure 5's largest value (xi = 7e-7): both stay near-symmetric, christoffel more so
  // (measured 2.9e-3 against 2.9e-2).
  const PaperResult classic_small = paper_scene(NormalApproximation::kClassic, 7e-7);
  const PaperResult christoffel_small = paper_scene(NormalApproximation::kChristoffel, 7e-7);
  EXPECT_LT(christoffel_small.asymmetry, classic_small.asymmetry);
}

TEST(PaperScene, IncreasingXiMakesTheSheetFlatterWithChristoffel) {
  // Wu & de Melo, figure 7 (xi = 0, 5e-6, 3e-5, 1e-4): with the Christoffel normal the maximum
  // curvature falls as xi grows (measured 11.0, 10.1, 9.5, 7.3). The classic normal is recorded:
  // it folds instead (figure 5's behavior; measured 11.0, 49, 164, 651).
  double previous = std::numeric_limits<double>::infinity();
  std::vector<double> classic;
  for (const double xi : {0.0, 5e-6, 3e-5, 1e-4}) {
    const PaperResult result = paper_scene(NormalApproximation::kChristoffel, xi);
    EXPECT_LT(result.max_curvature, previous) << "xi = " << xi;
    previous = result.max_curvature;
    classic.push_back(paper_scene(NormalApproximation::kClassic, xi).max_curvature);
  }
  ::testing::Test::RecordProperty("classic_max_curvature_xi_1e-4", std::to_string(classic.back()));
  EXPECT_GT(classic.back(), classic.front());  // what classic does: it curves more, not less
}

TEST(RubberSheet, LargerEtaSagsLess) {
  // Wu & de Melo, figure 3: a rubber sheet with fixed border under gravity (xi = 0) stays flatter
  // as eta grows (7e-7, 4e-6, 3e-5, 1e-2). 9 by 9 nodes in grid units, gravity 1e-5, t = 20000:
  // measured sags 8.9, 5.3, 2.7, 0.39, close to the membrane scaling (g L^4 / eta)^(1/3).
  const Grid grid(9, 9, 1.0);
  double previous = std::numeric_limits<double>::infinity();
  for (const double eta : {7e-7, 4e-6, 3e-5, 1e-2}) {
    TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()),
                             sheet_material(eta, eta, 0.0, 0.02));
    sheet.fix_border();
    System system(sheet);
    system.add_force(0, gravity(Eigen::Vector3d(0, 0, -1e-5)));
    SemiImplicitStepper stepper;
    for (int s = 0; s < 4000; ++s) {
      stepper.step(system, 5.0);
    }
    const double sag = -system.coordinates()[3 * grid.index(4, 4) + 2];
    std::printf("rubber sheet eta = %g: sag %.4f\n", eta, sag);
    EXPECT_LT(sag, previous) << "eta = " << eta;
    EXPECT_GT(sag, 0.0);
    previous = sag;
  }
}

TEST(TerzopoulosSurface, ClampedNodesNeverMove) {
  // Melting cheese (Wu & de Melo, figure 1): eta = xi = 0, border fixed, gravity. The border nodes
  // are eliminated from every solve, so they keep their exact values.
  const Grid grid = unit_square_grid(9);
  for (const NormalApproximation normal : kApproximations) {
    TerzopoulosSettings settings;
    settings.normal = normal;
    TerzopoulosSurface cheese(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()),
                              sheet_material(0.0, 0.0, 0.0, 0.1), settings);
    cheese.fix_border();
    System seed_system(cheese);
    seed_system.add_force(0, gravity(Eigen::Vector3d(0, 0, -9.81)));
    System common_system = seed_system;
    SemiImplicitStepper stepper;
    Integrator integrator(IntegratorSettings{IntegratorScheme::kNewmark});
    for (int s = 0; s < 50; ++s) {
      stepper.step(seed_system, 0.01);
      integrator.step(common_system, 0.01);
    }
    const Eigen::VectorXd rest = cheese.initial_coordinates();
    for (const System* system : {&seed_system, &common_system}) {
      for (const int index : cheese.fixed_coordinates()) {
        EXPECT_EQ(system->coordinates()[index], rest[index]);
      }
      // The interior falls freely (no resistance): 1/2 g t^2 to the schemes' O(dt) error.
      const int centre = grid.index(4, 4);
      EXPECT_NEAR(system->coordinates()[3 * centre + 2], -0.5 * 9.81 * 0.25, 0.1);
    }
  }
}

TEST(TerzopoulosSurface, BadInputNamesTheValue) {
  const Grid grid = unit_square_grid(5);
  const NodePositions rest = flat_grid_positions(grid, Eigen::Vector3d::Zero());
  const auto message = [&](auto&& make) -> std::string {
    try {
      make();
    } catch (const Error& error) {
      return error.what();
    }
    return "no error";
  };
  EXPECT_NE(
      message([&] { TerzopoulosSurface(grid, rest, sheet_material(-0.5, 0.0, 0.0)); }).find("-0.5"),
      std::string::npos);
  EXPECT_NE(
      message([&] { TerzopoulosSurface(grid, rest, sheet_material(0.1, 0.0, -2e-6)); }).find("xi"),
      std::string::npos);
  EXPECT_NE(message([&] {
              const Grid small(2, 5, 0.1);
              TerzopoulosSurface(small, flat_grid_positions(small, Eigen::Vector3d::Zero()));
            }).find("2 by 5"),
            std::string::npos);
  NodePositions bad = rest;
  bad(7, 1) = std::nan("");
  EXPECT_NE(message([&] { TerzopoulosSurface(grid, bad); }).find("nan"), std::string::npos);
  TerzopoulosSettings settings;
  settings.delta = 0.0;
  EXPECT_NE(message([&] { TerzopoulosSurface(grid, rest, {}, settings); }).find("delta"),
            std::string::npos);
  TerzopoulosSurface surface(grid, rest);
  EXPECT_THROW(surface.fix_point(25), Error);
}

TEST(TerzopoulosSurface, SeedStepAndCommonIntegratorsReachTheSameEquilibrium) {
  // A clamped 9 by 9 membrane (eta = 0.1, xi = 0) under a centred load, heavily damped: the
  // seed's semi-implicit step, implicit Euler and Newmark (both with Newton iterations through
  // the Model contract) all settle on the static equilibrium f_int(q) + f = 0, independent of the
  // scheme. After t = 20 the slowest mode is still settling (the membrane's stiffness vanishes
  // at zero strain): measured differences ~3e-5 for a deflection of 0.21, so 1e-3 relative.
  for (const NormalApproximation normal : kApproximations) {
    const Grid grid = unit_square_grid(9);
    TerzopoulosSettings settings;
    settings.normal = normal;
    TerzopoulosSurface sheet(
        grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()),
        sheet_material(0.1, 0.02, normal == NormalApproximation::kClassic ? 0.0 : 1e-5, 5.0),
        settings);
    sheet.fix_border();
    System seed_system(sheet);
    seed_system.add_force(0, point_force(Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d(0, 0, -0.01)));
    System euler_system = seed_system;
    System newmark_system = seed_system;
    SemiImplicitStepper stepper;
    IntegratorSettings euler_settings{IntegratorScheme::kImplicitEuler};
    euler_settings.newton_iterations = 1;
    IntegratorSettings newmark_settings{IntegratorScheme::kNewmark};
    newmark_settings.newton_iterations = 1;
    Integrator euler(euler_settings);
    Integrator newmark(newmark_settings);
    for (int s = 0; s < 400; ++s) {
      stepper.step(seed_system, 0.05);
      euler.step(euler_system, 0.05);
      newmark.step(newmark_system, 0.05);
    }
    const double euler_difference =
        (euler_system.coordinates() - seed_system.coordinates()).cwiseAbs().maxCoeff();
    const double newmark_difference =
        (newmark_system.coordinates() - seed_system.coordinates()).cwiseAbs().maxCoeff();
    std::printf(
        "%s equilibrium: deflection %.4e, implicit Euler differs by %.3e, Newmark by "
        "%.3e\n",
        to_string(normal), -seed_system.coordinates()[3 * grid.index(4, 4) + 2], euler_difference,
        newmark_difference);
    const double deflection = std::abs(seed_system.coordinates()[3 * grid.index(4, 4) + 2]);
    EXPECT_GT(deflection, 0.1);
    EXPECT_LE(euler_difference, 1e-3 * deflection);
    EXPECT_LE(newmark_difference, 1e-3 * deflection);
  }
}

// ----------------------------------------------------------------------------------------------
// The remaining scenes of Wu & de Melo on small grids: cardboard pressed at its centre (figure 4),
// lifting a cardboard by its middle point (figure 9) and opening curtains (figures 10, 11).

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

TEST(Curtains, TheUpperLineOpensTheCurtainAndSilkFoldsMoreThanWool) {
  // Woollen (xi = 2e-6) and silk (xi = 0) curtains of 9 by 7 nodes hang pleated from a rail; the
  // same force along the upper line draws them toward the fixed first hook. The hooks' heights
  // are fixed coordinates: exactly unchanged.
  const Grid grid(9, 7, 1.0);
  struct Drape {
    double sharpest_fold = 0.0;        // largest |B_ij|
    double pleat_depth = 0.0;          // spread of y over the curtain
    double change_of_curvature = 0.0;  // largest |B_ij - B0_ij|
  };
  std::vector<Drape> drapes;
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
    Drape drape;
    drape.sharpest_fold = test::max_curvature(curtain, system.coordinates(0));
    drape.pleat_depth = r.col(1).maxCoeff() - r.col(1).minCoeff();
    drape.change_of_curvature = (curtain.tensors(system.coordinates(0)).curvature -
                                 curtain.tensors(curtain.initial_coordinates()).curvature)
                                    .cwiseAbs()
                                    .maxCoeff();
    drapes.push_back(drape);
    std::printf(
        "curtain xi = %g: last hook at x = %.3f (from 8), sharpest fold |B| %.4f, pleat depth "
        "%.4f, largest |B - B0| %.4f\n",
        xi, r(grid.nu() - 1, 0), drape.sharpest_fold, drape.pleat_depth, drape.change_of_curvature);
    EXPECT_LT(r(grid.nu() - 1, 0), 7.0);
    EXPECT_GT(r(grid.nu() - 1, 0), 0.0);  // it does not pass the fixed hook
    for (int i = 0; i < grid.nu(); ++i) {
      EXPECT_EQ(r(grid.index(i, 0), 2), 0.0);
    }
  }
  // Wool resists curving, silk does not (Wu & de Melo, figures 10 and 11): the silk curtain's
  // folds change their curvature more and fold more sharply. Measured: largest |B - B0| 2.39
  // (wool) and 2.54 (silk), sharpest |B| 1.936 and 1.952; the pleat depths agree (1.643, 1.638).
  const Drape& wool = drapes[0];
  const Drape& silk = drapes[1];
  EXPECT_GT(silk.change_of_curvature, 1.03 * wool.change_of_curvature);
  EXPECT_GT(silk.sharpest_fold, wool.sharpest_fold);
  EXPECT_NEAR(silk.pleat_depth, wool.pleat_depth, 0.01 * wool.pleat_depth);
}

// ----------------------------------------------------------------------------------------------
// A large reaction force (Wu & de Melo, figures 6 and 8) and the threshold delta (eqs 24-26).

struct ReactionResult {
  double pressed_deflection = 0.0;  // largest |z| at the end of the press
  double pressed_asymmetry = 0.0;   // test::asymmetry at the end of the press
  double release_asymmetry = 0.0;   // largest test::asymmetry while springing back
  double release_rotation = 0.0;    // largest rotation angle about the centre while springing back
  double release_curvature = 0.0;   // max |B| at the end
};

// The paper scene (run_paper_scene, xi = 1e-4) pressed by `load` for `press` steps of 0.005,
// then released for `release` steps: the sheet springs back under its own reaction force, with
// only normal forces ever applied.
ReactionResult run_reaction_scene(const TerzopoulosSettings& settings, double load, int press,
                                  int release) {
  const Grid grid = unit_square_grid(17);
  TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()),
                           sheet_material(0.1, 0.0, 1e-4, 0.5), settings);
  sheet.fix_border();
  System system(sheet);
  for (int j = 7; j <= 9; ++j) {
    for (int i = 7; i <= 9; ++i) {
      system.add_force(0, point_force(grid.parameter(i, j), Eigen::Vector3d(0, 0, -load / 9)));
    }
  }
  SemiImplicitStepper stepper;
  for (int s = 0; s < press; ++s) {
    stepper.step(system, 0.005);
  }
  ReactionResult result;
  const NodePositions pressed = sheet.positions(system.coordinates(0)) - sheet.rest_positions();
  result.pressed_deflection = pressed.col(2).cwiseAbs().maxCoeff();
  result.pressed_asymmetry = asymmetry(grid, pressed);
  system.clear_forces();
  for (int s = 0; s < release; ++s) {
    stepper.step(system, 0.005);
    const NodePositions d = sheet.positions(system.coordinates(0)) - sheet.rest_positions();
    result.release_asymmetry = std::max(result.release_asymmetry, asymmetry(grid, d));
    result.release_rotation =
        std::max(result.release_rotation, tangential_drift(sheet.rest_positions(), d).rotation *
                                              d.col(2).cwiseAbs().maxCoeff());
  }
  result.release_curvature = max_curvature(sheet, system.coordinates(0));
  return result;
}

ReactionResult reaction_scene(NormalApproximation normal, double load) {
  TerzopoulosSettings settings;
  settings.normal = normal;
  const ReactionResult result = run_reaction_scene(settings, load, 400, 400);
  std::printf(
      "reaction load %g %-12s pressed %.4f (asymmetry %.3f), spring-back asymmetry %.3f "
      "rotation %.3e, max |B| %.2f\n",
      load, to_string(normal), result.pressed_deflection, result.pressed_asymmetry,
      result.release_asymmetry, result.release_rotation, result.release_curvature);
  return result;
}

TEST(ReactionScene, UnnormalizedNormalsDistortTheSpringBackMore) {
  // Wu & de Melo, figure 6 against figure 8: after a large reaction force the unnormalized
  // normals (|B| = 1) move the sheet sideways although only normal forces act. Ten times the
  // paper scene's load (0.1), released after 2 s: the spring-back's mirror asymmetry peaks at
  // 0.607 unnormalized against 0.351 normalized (at 0.05 and 0.2: 0.334 vs 0.099, 0.375 vs
  // 0.289). Neither rotates (the scene is symmetric about the diagonals; 1e-16).
  const ReactionResult normalized = reaction_scene(NormalApproximation::kChristoffel, 0.1);
  const ReactionResult unnormalized =
      reaction_scene(NormalApproximation::kChristoffelUnnormalized, 0.1);
  EXPECT_GT(unnormalized.release_asymmetry, 1.5 * normalized.release_asymmetry);
  EXPECT_NEAR(normalized.pressed_deflection, 0.501, 0.005);
  EXPECT_NEAR(unnormalized.pressed_deflection, 0.468, 0.005);
  EXPECT_LT(normalized.release_rotation, 1e-12);
  EXPECT_LT(unnormalized.release_rotation, 1e-12);
}

TEST(ReactionScene, AtThirtyTimesTheLoadTheNormalizedSheetRotates) {
  // Not the paper's finding, recorded: at 30 times the paper scene's load (0.3; max |B| ~ 7
  // pressed, h = 1/16) the normalized normal with delta = 0.5 is the one that rotates on release
  // (angle 0.109 rad, max |B| 122 after it) while the unnormalized spring-back stays
  // symmetric about the diagonals (1e-16 rad, max |B| 6.8). So does delta >= 4 (DeltaSweep).
  const ReactionResult normalized = reaction_scene(NormalApproximation::kChristoffel, 0.3);
  const ReactionResult unnormalized =
      reaction_scene(NormalApproximation::kChristoffelUnnormalized, 0.3);
  EXPECT_GT(normalized.release_rotation, 1e-2);
  EXPECT_GT(normalized.release_curvature, 50.0);
  EXPECT_LT(unnormalized.release_rotation, 1e-12);
  EXPECT_LT(unnormalized.release_curvature, 10.0);
}

TEST(DeltaSweep, DeflectionHoldsBelowTheCurvaturesAndTurnsUnnormalizedAbove) {
  // Wu & de Melo, eqs 24-26: delta decides where n is the unit normal (|B| > delta) and where
  // +-B n. The paper scene (load 0.01, xi = 1e-4, 400 steps) for delta from 0.05 to 1e300:
  //   delta       0.05    0.25    0.5     1       2       4       8       1e300
  //   deflection  0.1410  0.1424  0.1440  0.1431  0.1462  0.0956  0.0779  0.0779
  // Below the curvatures the load makes (|B| up to ~2 in the dimple) the result hardly depends
  // on delta (2.4% spread, the "almost planar cells" regime of the seed's 0.5); once delta
  // exceeds them the normal has length |B| > 1 in the dimple, bending is stiffer and the sheet
  // deflects about half as much; delta above every |B| is the unnormalized variant exactly.
  std::vector<double> deflections;
  for (const double delta : {0.05, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 1e300}) {
    TerzopoulosSettings settings;
    settings.normal = NormalApproximation::kChristoffel;
    settings.delta = delta;
    const ReactionResult result = run_reaction_scene(settings, 0.01, 400, 0);
    std::printf("delta %-6g deflection %.4f asymmetry %.3f\n", delta, result.pressed_deflection,
                result.pressed_asymmetry);
    deflections.push_back(result.pressed_deflection);
  }
  TerzopoulosSettings unnormalized;
  unnormalized.normal = NormalApproximation::kChristoffelUnnormalized;
  const double reference = run_reaction_scene(unnormalized, 0.01, 400, 0).pressed_deflection;
  for (size_t k = 0; k < 5; ++k) {
    EXPECT_NEAR(deflections[k], 0.1435, 0.003) << "delta index " << k;
  }
  EXPECT_LT(deflections[5], 0.7 * deflections[4]);
  EXPECT_EQ(deflections[6], reference);
  EXPECT_EQ(deflections[7], reference);
  EXPECT_NEAR(reference, 0.0779, 0.001);
}

}  // namespace
}  // namespace dnurbs
