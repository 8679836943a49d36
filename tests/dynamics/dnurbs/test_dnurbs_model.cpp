// Tests of dynamics/dnurbs/dnurbs_model.h with free weights (Terzopoulos 2003, eqs. 1.22-1.25): the
// rational Jacobian, Jdot qd and the generalized inertial force g against finite differences, the
// re-assembled matrices against an independent quadrature, energy conservation of free motion
// and the minimum-weight projection.

#include "dnurbs/dynamics/dnurbs/dnurbs_model.h"

#include <algorithm>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/nurbs/gauss_legendre.h"
#include "tests/common/dynamics_test_helpers.h"

namespace dnurbs {
namespace {

// Exact D-NURBS free weights (weight inertia 0 and no weight stiffness): these tests check the
// identities of the exact model (M = integral mu J^T J, f_int = -K q); the default weight
// regularization is tested in test_rational_control_net_model.cpp.
DNurbsSettings free_weights() {
  DNurbsSettings settings;
  settings.weight_mode = WeightMode::kFree;
  settings.weight_inertia = 0.0;
  return settings;
}

// A rational cubic curve with non-uniform weights and a wiggly control polygon.
NurbsCurve rational_curve() {
  KnotVector knots = KnotVector::clamped_from_breakpoints(3, {0.0, 0.3, 0.55, 1.0});
  Eigen::MatrixX3d points(6, 3);
  points << 0.0, 0.0, 0.0, 0.3, 0.5, 0.1, 0.6, -0.2, 0.3, 1.0, 0.4, -0.1, 1.3, 0.1, 0.2, 1.6, 0.3,
      0.0;
  Eigen::VectorXd weights(6);
  weights << 1.0, 0.7, 1.6, 0.9, 1.3, 1.0;
  return NurbsCurve(knots, points, weights);
}

NurbsSurface rational_surface() {
  NurbsSurface flat = test::flat_patch(2, 3, 2, 2);
  Eigen::MatrixX3d points = flat.control_points();
  Eigen::VectorXd weights(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    points(i, 2) = 0.2 * std::sin(3.0 * static_cast<double>(i));
    weights[i] = 1.0 + 0.4 * std::cos(2.0 * static_cast<double>(i));
  }
  return NurbsSurface(flat.knots_u(), flat.knots_v(), points, weights);
}

Eigen::VectorXd random_velocity(int size, unsigned seed) {
  std::srand(seed);
  return Eigen::VectorXd::Random(size);
}

TEST(FreeWeightJacobian, JacobianMatchesFiniteDifferencesOfPosition) {
  const DNurbsCurve model(rational_curve(), {}, free_weights());
  const Eigen::VectorXd q = model.initial_coordinates();
  const double h = 1e-6;
  for (const double u : {0.05, 0.4, 0.8}) {
    const Eigen::Vector2d parameter(u, 0.0);
    const Eigen::MatrixXd L(model.position_jacobian(q, parameter));
    for (int k = 0; k < q.size(); ++k) {
      Eigen::VectorXd plus = q;
      Eigen::VectorXd minus = q;
      plus[k] += h;
      minus[k] -= h;
      const Eigen::Vector3d fd =
          (model.position(plus, parameter) - model.position(minus, parameter)) / (2.0 * h);
      // Central difference: O(h^2) truncation (~1e-12) + O(1e-16 / h) round-off (~1e-10).
      EXPECT_LT((L.col(k) - fd).norm(), 1e-9) << "u " << u << " coordinate " << k;
    }
  }
}

TEST(FreeWeightJacobian, JdotTimesVelocityMatchesFiniteDifferencesOfJacobian) {
  const DNurbsCurve curve(rational_curve(), {}, free_weights());
  const DNurbsSurface surface(rational_surface(), {}, free_weights());
  for (const DNurbsModel* model :
       {static_cast<const DNurbsModel*>(&curve), static_cast<const DNurbsModel*>(&surface)}) {
    const Eigen::VectorXd q = model->initial_coordinates();
    const Eigen::VectorXd qd = random_velocity(model->coordinate_count(), 7);
    const double h = 1e-5;
    for (const Eigen::Vector2d& parameter :
         {Eigen::Vector2d(0.1, 0.2), Eigen::Vector2d(0.45, 0.9), Eigen::Vector2d(0.8, 0.5)}) {
      // Jdot qd = d/ds [L(q + s qd)] qd at s = 0.
      const Eigen::Vector3d fd = (model->position_jacobian(q + h * qd, parameter) * qd -
                                  model->position_jacobian(q - h * qd, parameter) * qd) /
                                 (2.0 * h);
      const Eigen::Vector3d analytic = model->jacobian_rate_times_velocity(q, qd, parameter);
      // O(h^2) truncation with third derivatives of size ~10 (~1e-9) + round-off ~1e-11.
      EXPECT_LT((analytic - fd).norm(), 1e-7 * std::max(1.0, fd.norm()))
          << model->parametric_dimension() << "-D, u " << parameter.transpose();
    }
  }
}

// Lagrange: d/dt (M qd) - dT/dq = M qdd - g, so g = dT/dq - Mdot qd with T = qd^T M(q) qd / 2.
TEST(FreeWeightInertialForce, MatchesLagrangianFiniteDifferences) {
  const DNurbsCurve curve(rational_curve(), {}, free_weights());
  const DNurbsSurface surface(rational_surface(), {}, free_weights());
  for (const DNurbsModel* model :
       {static_cast<const DNurbsModel*>(&curve), static_cast<const DNurbsModel*>(&surface)}) {
    const Eigen::VectorXd q = model->initial_coordinates();
    const Eigen::VectorXd qd = random_velocity(model->coordinate_count(), 11);
    const double h = 1e-5;
    ModelMatrices plus;
    ModelMatrices minus;
    auto kinetic = [&](const Eigen::VectorXd& at) {
      ModelMatrices m;
      model->assemble_matrices(at, m);
      return 0.5 * qd.dot(m.mass * qd);
    };
    model->assemble_matrices(q + h * qd, plus);
    model->assemble_matrices(q - h * qd, minus);
    Eigen::VectorXd expected = -((plus.mass - minus.mass) * qd) / (2.0 * h);
    for (int k = 0; k < q.size(); ++k) {
      Eigen::VectorXd qp = q;
      Eigen::VectorXd qm = q;
      qp[k] += h;
      qm[k] -= h;
      expected[k] += (kinetic(qp) - kinetic(qm)) / (2.0 * h);
    }
    Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
    model->add_inertial_force(q, qd, g);
    // O(h^2) truncation + O(1e-16 |T| / h) round-off; relative to |g| ~ 1.
    EXPECT_LT((g - expected).norm(), 1e-7 * std::max(1.0, expected.norm()))
        << model->parametric_dimension() << "-D: |g| = " << g.norm();
  }
}

TEST(FreeWeightMatrices, MassMatchesIndependentQuadratureOfJacobians) {
  DNurbsCurveMaterial material;
  material.mass_density = 1.7;
  const DNurbsCurve model(rational_curve(), material, free_weights());
  const Eigen::VectorXd q = model.initial_coordinates();
  ModelMatrices matrices;
  model.assemble_matrices(q, matrices);
  // integral mu L^T L with L from position_jacobian, by 4 Gauss points per span as the model.
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(q.size(), q.size());
  const std::vector<double> breaks = {0.0, 0.3, 0.55, 1.0};
  for (size_t s = 0; s + 1 < breaks.size(); ++s) {
    const GaussLegendreRule rule = gauss_legendre_rule_on(4, breaks[s], breaks[s + 1]);
    for (int g = 0; g < 4; ++g) {
      const Eigen::MatrixXd L(model.position_jacobian(q, Eigen::Vector2d(rule.nodes[g], 0.0)));
      expected += 1.7 * rule.weights[g] * L.transpose() * L;
    }
  }
  const Eigen::MatrixXd M(matrices.mass);
  EXPECT_LT((M - expected).norm(), 1e-13 * expected.norm());  // same sums, round-off
  EXPECT_LT((M - M.transpose()).norm(), 1e-15);               // symmetric by construction
}

TEST(FreeWeightKineticEnergy, IsHalfTheMassQuadraticFormAtTheState) {
  // Model::kinetic_energy of a state-dependent model: (1/2) qd^T M(q) qd with M assembled at q,
  // not at the initial state (the moved weights change M); fixed weights: the scalar pass.
  const DNurbsSurface model(rational_surface(), DNurbsSurfaceMaterial{}, free_weights());
  Eigen::VectorXd q = model.initial_coordinates();
  for (int i = 0; i < model.control_point_count(); ++i) {
    q[4 * i + 3] *= 1.0 + 0.3 * std::sin(static_cast<double>(i));
  }
  const Eigen::VectorXd qd = random_velocity(model.velocity_count(), 11);
  ModelMatrices moved;
  model.assemble_matrices(q, moved);
  ModelMatrices initial;
  model.assemble_matrices(model.initial_coordinates(), initial);
  const double expected = 0.5 * qd.dot(moved.mass * qd);
  EXPECT_NEAR(model.kinetic_energy(q, qd), expected, 1e-14 * expected);
  EXPECT_GT(std::abs(0.5 * qd.dot(initial.mass * qd) - expected), 1e-6 * expected);
  const DNurbsSurface fixed(rational_surface(), DNurbsSurfaceMaterial{}, DNurbsSettings{});
  const Eigen::VectorXd fixed_qd = random_velocity(fixed.velocity_count(), 12);
  ModelMatrices constant;
  fixed.assemble_matrices(fixed.initial_coordinates(), constant);
  const double fixed_expected = 0.5 * fixed_qd.dot(constant.mass * fixed_qd);
  EXPECT_NEAR(fixed.kinetic_energy(fixed.initial_coordinates(), fixed_qd), fixed_expected,
              1e-14 * fixed_expected);
  // Sizes are checked
  EXPECT_THROW(static_cast<void>(model.kinetic_energy(q, qd.head(3))), Error);
}

TEST(FreeWeightStiffness, InternalForceIsMinusGradientOfEnergyAndEqualsMinusKq) {
  DNurbsSurfaceMaterial material;
  material.a10 = 1.0;
  material.a01 = 0.5;
  material.b20 = 0.1;
  material.b11 = 0.05;
  material.b02 = 0.2;
  const DNurbsSurface model(rational_surface(), material, free_weights());
  const Eigen::VectorXd q = model.initial_coordinates();
  Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
  model.add_internal_force(q, force);
  ModelMatrices matrices;
  model.assemble_matrices(q, matrices);
  // x^alpha = J^alpha q (homogeneity), so K(q) q = dE/dq exactly up to round-off.
  EXPECT_LT((force + matrices.stiffness * q).norm(), 1e-12 * force.norm());
  const double h = 1e-6;
  for (int k = 0; k < q.size(); ++k) {
    Eigen::VectorXd plus = q;
    Eigen::VectorXd minus = q;
    plus[k] += h;
    minus[k] -= h;
    const double fd = -(model.potential_energy(plus) - model.potential_energy(minus)) / (2 * h);
    // O(h^2) truncation + O(1e-16 E / h) round-off, E ~ 1.
    EXPECT_NEAR(force[k], fd, 1e-8) << "coordinate " << k;
  }
}

// Model::assemble_step, the one pass of free weights (M, D, K, f_int and g from one rational
// Jacobian per Gauss point), against the separate calls, its force against finite differences
// of the energy, and Model::add_step_residual against the assembled matrices; with the default
// weight regularization (its anchor force and energy included) at a state away from the initial
// one.
TEST(FreeWeightAssembleStep, OnePassEqualsSeparateCallsAndItsForceIsMinusGradientOfEnergy) {
  DNurbsCurveMaterial curve_material;
  curve_material.damping_density = 0.3;
  curve_material.tension = 1.0;
  curve_material.rigidity = 0.05;
  DNurbsSurfaceMaterial surface_material;
  surface_material.damping_density = 0.3;
  surface_material.a10 = 1.0;
  surface_material.a01 = 0.5;
  surface_material.b20 = surface_material.b11 = surface_material.b02 = 0.1;
  DNurbsSettings settings;
  settings.weight_mode = WeightMode::kFree;  // default regularization: inertia and anchor
  const DNurbsCurve curve(rational_curve(), curve_material, settings);
  const DNurbsSurface surface(rational_surface(), surface_material, settings);
  for (const DNurbsModel* model :
       {static_cast<const DNurbsModel*>(&curve), static_cast<const DNurbsModel*>(&surface)}) {
    ASSERT_GT(model->weight_stiffness(), 0.0);
    const Eigen::VectorXd q =
        model->initial_coordinates() + 0.05 * random_velocity(model->coordinate_count(), 5);
    const Eigen::VectorXd qd = random_velocity(model->coordinate_count(), 7);
    ModelMatrices separate;
    model->assemble_matrices(q, separate);
    Eigen::VectorXd expected = Eigen::VectorXd::Zero(q.size());
    model->add_internal_force(q, expected);
    model->add_inertial_force(q, qd, expected);
    ModelMatrices fused;
    Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
    model->assemble_step(q, qd, true, fused, force);
    // The same products summed in the same order: the matrices agree to the last bit; the force
    // sums f_int and g per point instead of per pass, rounding only (1e-14 relative).
    EXPECT_EQ(Eigen::MatrixXd(fused.mass - separate.mass).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(Eigen::MatrixXd(fused.damping - separate.damping).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(Eigen::MatrixXd(fused.stiffness - separate.stiffness).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_LT((force - expected).norm(), 1e-14 * expected.norm());
    // Without the inertial force: f_int = -dE/dq (E with the weight anchor) by central differences
    Eigen::VectorXd internal = Eigen::VectorXd::Zero(q.size());
    model->assemble_step(q, qd, false, fused, internal);
    const double h = 1e-6;
    for (int k = 0; k < q.size(); ++k) {
      Eigen::VectorXd plus = q;
      Eigen::VectorXd minus = q;
      plus[k] += h;
      minus[k] -= h;
      const double fd = -(model->potential_energy(plus) - model->potential_energy(minus)) / (2 * h);
      // O(h^2) truncation + O(1e-16 E / h) round-off, E ~ 1.
      EXPECT_NEAR(internal[k], fd, 1e-8) << model->parametric_dimension() << "-D, coordinate " << k;
    }
    EXPECT_GT((force - internal).norm(), 1e-3);  // g is not zero at this velocity
    // The matrix-free residual of modified Newton: f_int + g - D qd - M a without assembling
    const Eigen::VectorXd a = random_velocity(model->coordinate_count(), 13);
    Eigen::VectorXd residual = Eigen::VectorXd::Zero(q.size());
    model->add_step_residual(q, qd, a, true, residual);
    const Eigen::VectorXd assembled = expected - separate.damping * qd - separate.mass * a;
    // Per-point products J^T (J a) against the sums of the assembled entries: rounding, 1e-13
    // relative
    EXPECT_LT((residual - assembled).norm(), 1e-13 * assembled.norm());
  }
}

// Largest |E(t) - E(0)| of a free, undamped rational curve over t in [0, 0.02] (Newmark). The
// weights are light coordinates (their mass entries are ~1e-5 against ~0.1 for positions) that
// the tension drives fast, so the run is short and the steps resolve them.
double free_motion_energy_error(int steps, int newton_iterations) {
  DNurbsCurveMaterial material;
  material.tension = 1.0;
  material.rigidity = 0.01;
  const DNurbsCurve model(rational_curve(), material, free_weights());
  System system(model);
  system.set_velocities(0, 0.5 * random_velocity(model.velocity_count(), 3));
  IntegratorSettings settings;
  settings.newton_iterations = newton_iterations;
  Integrator integrator(settings);
  const double initial = system.kinetic_energy() + system.potential_energy();
  double worst = 0.0;
  const double dt = 0.02 / steps;
  for (int k = 0; k < steps; ++k) {
    integrator.step(system, dt);
    worst =
        std::max(worst, std::abs(system.kinetic_energy() + system.potential_energy() - initial));
  }
  return worst;
}

TEST(FreeWeightDynamics, FreeMotionConservesEnergyToSecondOrderInTimeStep) {
  const double coarse = free_motion_energy_error(40, 3);
  const double fine = free_motion_energy_error(80, 3);
  const double finer = free_motion_energy_error(160, 3);
  std::cout << "free weights, Newmark + 3 Newton iterations: energy error " << coarse << " -> "
            << fine << " -> " << finer << ", ratios " << coarse / fine << ", " << fine / finer
            << "\n";
  // O(dt^2) energy error of the second-order scheme: ratio 4 when dt halves; the band allows
  // the O(dt^3) terms at these step sizes (measured 4.09 and 4.03).
  EXPECT_GT(coarse / fine, 3.7);
  EXPECT_LT(coarse / fine, 4.4);
  EXPECT_GT(fine / finer, 3.7);
  EXPECT_LT(fine / finer, 4.4);
  EXPECT_LT(finer, 1e-3 * (0.5 + 3.8));  // small against the energy (about 3.8)
}

TEST(FreeWeightDynamics, WeightPulledTowardZeroStopsAtTheMinimumAndPointsStayFinite) {
  // No stiffness: the force and damping alone move the weight (with tension the light weights
  // also follow the parametrization forces, a separate matter).
  DNurbsCurveMaterial material;
  material.damping_density = 1.0;
  const DNurbsCurve model(rational_curve(), material, free_weights());
  System system(model);
  system.add_force(0, coordinate_force({model.weight_offset(2)}, [](double) { return -0.01; }));
  for (const auto scheme : {IntegratorScheme::kNewmark, IntegratorScheme::kImplicitEuler}) {
    System run = system;
    IntegratorSettings settings;
    settings.scheme = scheme;
    settings.newton_iterations = 3;
    Integrator integrator(settings);
    for (int k = 0; k < 500; ++k) {
      integrator.step(run, 0.002);
      ASSERT_GE(run.coordinates()[model.weight_offset(2)], model.minimum_weight())
          << to_string(scheme) << " step " << k;
    }
    // The force keeps pushing, so the projection holds the weight exactly at the minimum.
    EXPECT_EQ(run.coordinates()[model.weight_offset(2)], model.minimum_weight())
        << to_string(scheme);
    EXPECT_GE(run.velocities()[model.weight_offset(2)], 0.0);
    for (int i = 0; i <= 200; ++i) {
      const Eigen::Vector2d u(i / 200.0, 0.0);
      EXPECT_TRUE(run.position(0, u).allFinite()) << to_string(scheme) << " u " << u.x();
    }
  }
}

TEST(FreeWeightDynamics, ProjectionClampsWeightAndItsDownwardVelocity) {
  const DNurbsCurve model(rational_curve(), {}, free_weights());
  Eigen::VectorXd q = model.initial_coordinates();
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(q.size());
  q[model.weight_offset(1)] = -0.5;
  qd[model.weight_offset(1)] = -2.0;
  q[model.weight_offset(3)] = 2e-4;
  qd[model.weight_offset(3)] = 1.0;  // already moving up: kept
  model.project_state(q, qd);
  EXPECT_EQ(q[model.weight_offset(1)], 1e-3);
  EXPECT_EQ(qd[model.weight_offset(1)], 0.0);
  EXPECT_EQ(q[model.weight_offset(3)], 1e-3);
  EXPECT_EQ(qd[model.weight_offset(3)], 1.0);
}

TEST(FreeWeightModel, WeightGaugeFixesWeightZeroOnly) {
  const DNurbsCurve model(rational_curve(), {}, free_weights());
  EXPECT_EQ(model.fixed_coordinates(), (std::vector<int>{3}));
  DNurbsSettings settings = free_weights();
  settings.fix_weight_gauge = false;
  const DNurbsCurve ungauged(rational_curve(), {}, settings);
  EXPECT_TRUE(ungauged.fixed_coordinates().empty());
  // The gauge direction [0, w_0, 0, w_1, ...] moves no point: J q_gauge = 0.
  const Eigen::VectorXd q = model.initial_coordinates();
  Eigen::VectorXd gauge = Eigen::VectorXd::Zero(q.size());
  for (int i = 0; i < model.control_point_count(); ++i) {
    gauge[model.weight_offset(i)] = q[model.weight_offset(i)];
  }
  EXPECT_LT((model.position_jacobian(q, Eigen::Vector2d(0.37, 0.0)) * gauge).norm(), 1e-15);
}

// Beyond the gauge, a straight line keeps its parametrized points under a weight change, so M
// restricted to the free coordinates is singular; weight_inertia removes that.
TEST(FreeWeightModel, WeightInertiaRegularizesTheSingularMassOfAStraightLine) {
  auto smallest_free_mass_eigenvalue = [](double inertia) {
    DNurbsSettings settings = free_weights();
    settings.weight_inertia = inertia;
    DNurbsCurve model(test::straight_curve(3, 10), {}, settings);
    model.fix_control_point(0);
    model.fix_control_point(model.control_point_count() - 1);
    ModelMatrices matrices;
    model.assemble_matrices(model.initial_coordinates(), matrices);
    const Eigen::MatrixXd M(matrices.mass);
    std::vector<int> free;
    const auto& fixed = model.fixed_coordinates();
    for (int i = 0; i < M.rows(); ++i) {
      if (!std::binary_search(fixed.begin(), fixed.end(), i)) {
        free.push_back(i);
      }
    }
    Eigen::MatrixXd reduced(free.size(), free.size());
    for (size_t i = 0; i < free.size(); ++i) {
      for (size_t j = 0; j < free.size(); ++j) {
        reduced(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = M(free[i], free[j]);
      }
    }
    return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(reduced).eigenvalues().minCoeff();
  };
  // Round-off level against entries of size ~0.1.
  EXPECT_LT(std::abs(smallest_free_mass_eigenvalue(0.0)), 1e-15);
  // The added diagonal 1e-4 on the weights bounds the weight block from below.
  EXPECT_GT(smallest_free_mass_eigenvalue(1e-4), 0.5e-4);
  DNurbsSettings bad = free_weights();
  bad.weight_inertia = -1.0;
  EXPECT_THROW(DNurbsCurve(test::straight_curve(3, 4), {}, bad), Error);
}

}  // namespace
}  // namespace dnurbs
