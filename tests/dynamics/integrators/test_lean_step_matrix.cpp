// Tests of dynamics/integrators/lean_step_matrix.h and of the lean step it serves
// (IntegratorSettings::lean_step): the factorization against a dense solve, one symbolic analysis
// over many factorizations, errors, and free-weight trajectories of the lean step against the
// reference path (separate assembly and force calls, SparseCholesky at every iterate).

#include "dnurbs/dynamics/integrators/lean_step_matrix.h"

#include <cmath>
#include <iostream>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"

namespace dnurbs {
namespace {

// A symmetric positive definite n by n matrix with the pattern of a 1D chain coupled to its
// second neighbours (both triangles stored), values from `seed`; M, D and K share the pattern.
ModelMatrices chain_matrices(int n, double seed) {
  std::vector<Eigen::Triplet<double>> mass;
  std::vector<Eigen::Triplet<double>> stiffness;
  std::vector<Eigen::Triplet<double>> damping;
  for (int i = 0; i < n; ++i) {
    for (int j = std::max(0, i - 2); j <= std::min(n - 1, i + 2); ++j) {
      const double coupling = i == j ? 0.0 : 0.1 * std::sin(seed + i + j);
      mass.emplace_back(i, j, i == j ? 2.0 + std::cos(seed * i) : coupling);
      stiffness.emplace_back(i, j, i == j ? 4.0 : -1.0 + coupling);
      damping.emplace_back(i, j, i == j ? 1.0 : 0.3 * coupling);
    }
  }
  ModelMatrices m;
  for (auto [matrix, triplets] : {std::pair{&m.mass, &mass}, std::pair{&m.stiffness, &stiffness},
                                  std::pair{&m.damping, &damping}}) {
    *matrix = SparseMatrix(n, n);
    matrix->setFromTriplets(triplets->begin(), triplets->end());
    matrix->makeCompressed();
  }
  return m;
}

class LeanStepMatrixModes : public ::testing::TestWithParam<bool> {};

TEST_P(LeanStepMatrixModes, SolvesTheFreeBlockLikeADenseFactorization) {
  const bool supernodal = GetParam();
  const int n = 40;
  const std::vector<int> fixed{0, 1, 17, 39};
  const FreeCoordinates free(n, fixed);
  LeanStepMatrix lean;
  for (const double seed : {0.3, 1.7, 4.2}) {
    const ModelMatrices m = chain_matrices(n, seed);
    if (!lean.fits(m, supernodal)) {
      ASSERT_TRUE(lean.analyze(m, free, supernodal));
    }
    EXPECT_EQ(lean.is_supernodal(), supernodal);
    const double c_d = 0.05;
    const double c_k = 0.0025;
    lean.factorize(m, c_d, c_k);
    const Eigen::VectorXd r = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0).array().sin();
    Eigen::VectorXd x = Eigen::VectorXd::Constant(n, 7.0);
    lean.solve(r.data(), x.data());
    // The dense reference on the free rows and columns
    const Eigen::MatrixXd a = Eigen::MatrixXd(m.mass) + c_d * Eigen::MatrixXd(m.damping) +
                              c_k * Eigen::MatrixXd(m.stiffness);
    Eigen::MatrixXd a_free(free.free_count(), free.free_count());
    Eigen::VectorXd r_free(free.free_count());
    for (int i = 0; i < free.free_count(); ++i) {
      r_free[i] = r[free.free_unknown(i)];
      for (int j = 0; j < free.free_count(); ++j) {
        a_free(i, j) = a(free.free_unknown(i), free.free_unknown(j));
      }
    }
    const Eigen::VectorXd expected = a_free.ldlt().solve(r_free);
    for (int i = 0; i < free.free_count(); ++i) {
      // Two backward-stable solves of a matrix with condition number below 10: rounding, 1e-14
      EXPECT_NEAR(x[free.free_unknown(i)], expected[i], 1e-14) << i;
    }
    for (const int index : fixed) {
      EXPECT_EQ(x[index], 7.0);  // fixed entries untouched
    }
  }
  // Three factorizations, one analysis: the pattern stayed.
  EXPECT_EQ(lean.analysis_count(), 1);
  EXPECT_EQ(lean.factorization_count(), 3);
  // The other mode asks for a new analysis
  EXPECT_FALSE(lean.fits(chain_matrices(n, 0.3), !supernodal));
}

TEST_P(LeanStepMatrixModes, RefusesPatternsItCannotTakeAndIndefiniteMatrices) {
  const bool supernodal = GetParam();
  const int n = 12;
  const FreeCoordinates free(n, {});
  ModelMatrices m = chain_matrices(n, 0.5);
  LeanStepMatrix lean;
  // A stiffness with another pattern (diagonal): not analyzed, the caller takes another path
  ModelMatrices other = m;
  other.stiffness = SparseMatrix(n, n);
  other.stiffness.setIdentity();
  EXPECT_FALSE(lean.analyze(other, free, supernodal));
  EXPECT_FALSE(lean.fits(m, supernodal));
  EXPECT_THROW(lean.factorize(m, 0.0, 0.0), Error);
  // An indefinite matrix: mass diagonal entry 5 made -3
  ASSERT_TRUE(lean.analyze(m, free, supernodal));
  m.mass.coeffRef(5, 5) = -3.0;
  try {
    lean.factorize(m, 0.0, 0.0);
    FAIL() << "an indefinite matrix was factored";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("not positive definite"), std::string::npos)
        << error.what();
  }
  EXPECT_FALSE(lean.is_factored());
  Eigen::VectorXd x(n);
  const Eigen::VectorXd r = Eigen::VectorXd::Ones(n);
  EXPECT_THROW(lean.solve(r.data(), x.data()), Error);
}

INSTANTIATE_TEST_SUITE_P(SimplicialAndSupernodal, LeanStepMatrixModes, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? std::string("Supernodal")
                                             : std::string("Simplicial");
                         });

DNurbsSettings free_weights() {
  DNurbsSettings settings;
  settings.weight_mode = WeightMode::kFree;
  return settings;
}

// A curved cubic rod (ends fixed) and a curved bicubic 6 x 6 sheet (border fixed) with free
// weights under a point load, moving from their initial shape.
System free_curve() {
  const KnotVector knots = KnotVector::clamped_uniform(3, 9);
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(9, 3);
  for (int i = 0; i < 9; ++i) {
    points(i, 0) = i / 8.0;
    points(i, 2) = 0.3 * std::sin(M_PI * i / 8.0);
  }
  DNurbsCurveMaterial material;
  material.damping_density = 0.5;
  material.tension = 1.0;
  material.rigidity = 0.01;
  DNurbsCurve model(NurbsCurve(knots, points), material, free_weights());
  model.fix_control_point(0);
  model.fix_control_point(8);
  System system(model);
  system.add_force(0, point_force(Eigen::Vector2d(0.4, 0.0), Eigen::Vector3d(0.0, 0.0, -1.0)));
  return system;
}

System free_sheet() {
  const KnotVector knots = KnotVector::clamped_uniform(3, 6);
  Eigen::MatrixX3d points(36, 3);
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      points.row(i * 6 + j) << i / 5.0, j / 5.0,
          0.2 * std::sin(M_PI * i / 5.0) * std::sin(M_PI * j / 5.0);
    }
  }
  DNurbsSurfaceMaterial material;
  material.damping_density = 0.5;
  material.a10 = material.a01 = 1.0;
  material.b20 = material.b02 = 0.01;
  DNurbsSurface model(NurbsSurface(knots, knots, points), material, free_weights());
  model.fix_border();
  System system(model);
  system.add_force(0, point_force(Eigen::Vector2d(0.4, 0.6), Eigen::Vector3d(0.0, 0.0, -1.0)));
  return system;
}

struct Trajectory {
  Eigen::VectorXd q;
  Eigen::VectorXd v;
  int factorizations = 0;
};

// keep: IntegratorSettings::keep_factor_across_steps (off by default here: the comparisons of
// single steps below are of the factor at each step's predictor, as the reference path takes).
Trajectory run(System system, IntegratorScheme scheme, bool lean, int newton, int steps,
               CholeskyBackend backend = CholeskyBackend::kAutomatic, bool keep = false) {
  IntegratorSettings settings;
  settings.keep_factor_across_steps = keep;
  settings.cholesky.backend = backend;
  settings.scheme = scheme;
  settings.lean_step = lean;
  settings.newton_iterations = newton;
  settings.automatic_newton = false;  // newton = 0: the linearly implicit step of both paths
  settings.newton_tolerance = 1e-12;
  Integrator integrator(settings);
  for (int k = 0; k < steps; ++k) {
    integrator.step(system, 0.01);
  }
  return {system.coordinates(), system.velocities(), integrator.factorization_count()};
}

double relative(const Eigen::VectorXd& value, const Eigen::VectorXd& reference) {
  return (value - reference).norm() / reference.norm();
}

TEST(LeanStep, FreeWeightTrajectoryEqualsTheReferencePath) {
  // Linearly implicit steps (no Newton): the lean step computes the same M, D, K, f_int, g and
  // the same factorization (same AMD ordering, the same up-looking algorithm); only the order of
  // a few sums differs (f_int and g summed per point, not per pass; 1 / d_i multiplied), so the
  // states differ by rounding, about 1e-16 relative per step, grown by the dynamics over 200
  // steps: 1e-12 relative bounds it.
  for (const bool sheet : {false, true}) {
    for (const IntegratorScheme scheme :
         {IntegratorScheme::kNewmark, IntegratorScheme::kImplicitEuler,
          IntegratorScheme::kCentral}) {
      const int steps = scheme == IntegratorScheme::kCentral ? 50 : 200;
      const System system = sheet ? free_sheet() : free_curve();
      const Trajectory reference = run(system, scheme, false, 0, steps);
      const Trajectory lean = run(system, scheme, true, 0, steps);
      const double q_error = relative(lean.q, reference.q);
      const double v_error = relative(lean.v, reference.v);
      std::cout << (sheet ? "sheet " : "curve ") << to_string(scheme) << ": lean against reference "
                << q_error << " (q), " << v_error << " (v)\n";
      EXPECT_LT(q_error, 1e-12);
      EXPECT_LT(v_error, 1e-12);
      // The shape moved (not a comparison of two rest states)
      EXPECT_GT((reference.q - system.coordinates()).norm(), 1e-3);
      EXPECT_EQ(lean.factorizations, reference.factorizations);  // one per step either way
    }
  }
}

TEST(LeanStep, SupernodalLeanStepEqualsTheReferencePath) {
  // Both paths factored by CHOLMOD (same ordering, same supernodal algorithm): the lean step's
  // lower triangle holds the same values as the reference's reduced matrix, so the states differ
  // by the rounding of the sums' order, as in the simplicial comparison: 1e-12 relative.
  const System system = free_sheet();
  const Trajectory reference =
      run(system, IntegratorScheme::kNewmark, false, 0, 200, CholeskyBackend::kCholmodSupernodal);
  const Trajectory lean =
      run(system, IntegratorScheme::kNewmark, true, 0, 200, CholeskyBackend::kCholmodSupernodal);
  EXPECT_LT(relative(lean.q, reference.q), 1e-12);
  EXPECT_LT(relative(lean.v, reference.v), 1e-12);
  EXPECT_GT((reference.q - system.coordinates()).norm(), 1e-3);
  // The modified Newton of the lean step on CHOLMOD: the same converged steps, fewer
  // factorizations (bound as in ModifiedNewtonConvergesToTheSameStepWithFewerFactorizations)
  const Trajectory newton_reference =
      run(system, IntegratorScheme::kNewmark, false, 30, 100, CholeskyBackend::kCholmodSupernodal);
  const Trajectory newton_lean =
      run(system, IntegratorScheme::kNewmark, true, 30, 100, CholeskyBackend::kCholmodSupernodal);
  EXPECT_LT(relative(newton_lean.q, newton_reference.q), 1e-10);
  EXPECT_LT(newton_lean.factorizations, newton_reference.factorizations);
}

TEST(LeanStep, ModifiedNewtonConvergesToTheSameStepWithFewerFactorizations) {
  // Newton to 1e-12 with up to 30 iterations (both converge: the reference takes about 7.7
  // iterates per step on the curve, its A leaving out d(M a)/dq and dg/dq, so it contracts
  // linearly too): the reference refactors at every iterate, the lean step keeps the factor
  // while the corrections contract (modified Newton). Both stop within the tolerance of the
  // same implicit solution; the per-step difference, ~1e-12 of |a| dt^2 in q, adds up over 100
  // steps: 1e-10 relative bounds it (measured 8e-15 and 1.3e-15).
  for (const bool sheet : {false, true}) {
    const System system = sheet ? free_sheet() : free_curve();
    const int steps = 100;
    const Trajectory reference = run(system, IntegratorScheme::kNewmark, false, 30, steps);
    const Trajectory lean = run(system, IntegratorScheme::kNewmark, true, 30, steps);
    const double q_error = relative(lean.q, reference.q);
    std::cout << (sheet ? "sheet" : "curve") << ": modified Newton against Newton " << q_error
              << ", factorizations " << lean.factorizations << " against "
              << reference.factorizations << "\n";
    EXPECT_LT(q_error, 1e-10);
    EXPECT_LT(relative(lean.v, reference.v), 1e-10);
    EXPECT_LT(lean.factorizations, reference.factorizations);
    EXPECT_GE(lean.factorizations, steps);  // at least the predictor's factorization per step
  }
}

TEST(LeanStep, FactorKeptAcrossStepsLandsOnTheSameStepsWithFewerFactorizations) {
  // The automatic Newton of free weights (to 1e-8 of |a|) with each step starting from the
  // factor the last one ended with (keep_factor_across_steps) against a factor at every
  // predictor: both converge to the same implicit solution within the tolerance. Each step's a
  // differs by at most about 1e-8 |a|, q by beta dt^2 times that; summed over 100 steps and grown
  // by the dynamics, 1e-7 relative bounds the difference of the states.
  for (const bool sheet : {false, true}) {
    for (const IntegratorScheme scheme :
         {IntegratorScheme::kNewmark, IntegratorScheme::kImplicitEuler}) {
      const int steps = 100;
      Trajectory result[2];
      for (const bool keep : {false, true}) {
        System system = sheet ? free_sheet() : free_curve();
        IntegratorSettings settings;
        settings.scheme = scheme;
        settings.keep_factor_across_steps = keep;
        Integrator integrator(settings);
        for (int k = 0; k < steps; ++k) {
          integrator.step(system, 0.01);
        }
        EXPECT_GT(
            (system.coordinates() - (sheet ? free_sheet() : free_curve()).coordinates()).norm(),
            1e-3);  // the shape moved
        result[keep ? 1 : 0] = {system.coordinates(), system.velocities(),
                                integrator.factorization_count()};
      }
      const Trajectory& fresh = result[0];
      const Trajectory& kept = result[1];
      const double q_error = relative(kept.q, fresh.q);
      std::cout << (sheet ? "sheet " : "curve ") << to_string(scheme)
                << ": factor kept across steps against a factor per step " << q_error << " (q), "
                << relative(kept.v, fresh.v) << " (v), factorizations " << kept.factorizations
                << " against " << fresh.factorizations << "\n";
      EXPECT_LT(q_error, 1e-7);
      EXPECT_LT(relative(kept.v, fresh.v), 1e-6);
      // One factorization per step without the setting; with it, refactorizations where a
      // correction stalls or a step falls back to its predictor (these small sheets under a unit
      // point load: 24 to 61 in 100 steps; 15 in 55 on bench/free_weights' 20 x 20 sheet)
      EXPECT_GE(fresh.factorizations, steps);
      EXPECT_LT(kept.factorizations, fresh.factorizations);
    }
  }
}

TEST(LeanStep, KeptFactorIsReplacedWhenTheStepCoefficientsChange) {
  // The automatic Newton of free weights (IntegratorSettings{}): a new dt changes the step
  // matrix's coefficients, so the first step at it factors at its predictor; a linearly implicit
  // integrator (no iterations) factors at every predictor whatever keep_factor_across_steps says.
  System system = free_sheet();
  Integrator integrator;
  for (int k = 0; k < 10; ++k) {
    integrator.step(system, 0.01);
  }
  const int before = integrator.factorization_count();
  integrator.step(system, 0.005);
  EXPECT_GE(integrator.factorization_count(), before + 1);
  EXPECT_LT(before, 10);  // ten steps at one dt kept their factor at least once
  IntegratorSettings linear;
  linear.automatic_newton = false;
  Integrator linear_integrator(linear);
  System linear_system = free_sheet();
  for (int k = 0; k < 10; ++k) {
    linear_integrator.step(linear_system, 0.01);
  }
  EXPECT_EQ(linear_integrator.factorization_count(), 10);
}

}  // namespace
}  // namespace dnurbs
