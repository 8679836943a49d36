#include "dnurbs/design/energy_minimization.h"

#include <algorithm>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/constraints/point_constraints.h"
#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/integrators/static_equilibrium.h"
#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"
#include "tests/design/design_test_helpers.h"

namespace dnurbs {
namespace {

using test::flat_patch;
using test::plate_material;
using test::point_force;

TEST(EnergyMinimization, FixedWeightsMatchTheDirectLinearSolve) {
  DNurbsSurface model(flat_patch(3, 3), plate_material());
  model.fix_border();
  System system(model);
  system.add_force(0, point_force(Eigen::Vector2d(0.4, 0.55), Eigen::Vector3d(0.1, -0.2, 1.0)));
  System reference = system;
  solve_static_equilibrium(reference);

  for (const auto algorithm :
       {DesignAlgorithm::kSlsqp, DesignAlgorithm::kAugmentedLagrangianLbfgs}) {
    DesignSettings settings;
    settings.algorithm = algorithm;
    std::vector<double> reported;  // the progress callback's energies, one per evaluation
    settings.on_evaluation = [&reported](int evaluations, double energy) {
      EXPECT_EQ(evaluations, static_cast<int>(reported.size()) + 1);
      reported.push_back(energy);
    };
    const DesignResult result = minimize_energy(system, nullptr, settings);
    ASSERT_EQ(reported.size(), static_cast<size_t>(result.iterations));
    // Without constraints the optimum is the lowest energy evaluated (the result's energy is
    // evaluated again there without the gradient, by the same arithmetic)
    EXPECT_EQ(*std::min_element(reported.begin(), reported.end()), result.energy);
    const double error = (result.coordinates - reference.coordinates()).lpNorm<Eigen::Infinity>();
    std::cout << "fixed weights, algorithm " << static_cast<int>(algorithm) << ": "
              << result.iterations << " evaluations, status " << result.status_name << ", energy "
              << result.energy << ", distance to K q = f " << error << "\n";
    EXPECT_TRUE(result.converged()) << result.status_name;
    // Pi is quadratic with minimizer K q = f. SLSQP (the default) stops on the 1e-14 relative
    // variable tolerance: measured 8e-12. LBFGS inside AUGLAG stops on its own test of the
    // change of Pi: measured 5e-9, bounded by 5e-8.
    EXPECT_LT(error, algorithm == DesignAlgorithm::kSlsqp ? 1e-8 : 5e-8);
  }
}

TEST(EnergyMinimization, GradientMatchesFiniteDifferences) {
  DNurbsSettings settings;
  settings.weight_mode = WeightMode::kFree;
  DNurbsSurface model(flat_patch(2, 2), plate_material(), settings);
  System system(model);
  system.add_force(0, point_force(Eigen::Vector2d(0.3, 0.6), Eigen::Vector3d(0.0, 0.5, 1.0)));
  Eigen::VectorXd f = Eigen::VectorXd::Zero(system.velocity_count());
  system.add_applied_forces(0.0, system.coordinates(), f, f);
  Eigen::VectorXd q = system.coordinates();
  q += 0.1 * Eigen::VectorXd::Random(q.size()).cwiseAbs();  // weights stay positive
  Eigen::VectorXd gradient;
  design_energy(system, f, q, &gradient);
  const double h = 1e-6;
  double worst = 0.0;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    Eigen::VectorXd qp = q;
    Eigen::VectorXd qm = q;
    qp[i] += h;
    qm[i] -= h;
    const double difference =
        (design_energy(system, f, qp, nullptr) - design_energy(system, f, qm, nullptr)) / (2 * h);
    worst = std::max(worst, std::abs(difference - gradient[i]));
  }
  // Central differences: h^2 |Pi'''| / 6 ~ 1e-12 plus round-off eps |Pi| / h ~ 1e-10.
  EXPECT_LT(worst, 1e-7 * std::max(1.0, gradient.norm()));
}

TEST(EnergyMinimization, BadSettingsAreRejected) {
  DNurbsSurface model(flat_patch(2, 2), plate_material());
  model.fix_border();
  System system(model);
  DesignSettings settings;
  settings.max_evaluations = 0;
  EXPECT_THROW(minimize_energy(system, nullptr, settings), Error);
  settings = DesignSettings{};
  settings.variable_tolerance = -1.0;
  EXPECT_THROW(minimize_energy(system, nullptr, settings), Error);
}

// A stiff plate whose centre is pulled up by a point constraint: the interior control points
// are expensive to move, so the optimizer also raises the weights of the interior ones.
TEST(EnergyMinimization, FreeWeightsMoveStayAboveTheMinimumAndMeetThePointConstraint) {
  DNurbsSettings settings;
  settings.weight_mode = WeightMode::kFree;
  settings.minimum_weight = 0.5;
  // Exact D-NURBS energy (no weight anchor): the optimum this test describes. With the default
  // weight regularization the anchor (1/2) k_w |w - w_0|^2 is part of the energy too, and LBFGS
  // then ends in NLopt's FAILURE at the same energy 51.6388 as SLSQP.
  settings.weight_inertia = 0.0;
  DNurbsSurfaceMaterial material = test::plate_material();
  material.b20 = 10.0;
  material.b11 = 10.0;
  material.b02 = 10.0;
  DNurbsSurface model(test::flat_patch(2, 3), material, settings);
  model.fix_border();
  System system(model);
  const Eigen::Vector2d uv(0.35, 0.5);
  const Eigen::Vector3d target = system.position(0, uv) + Eigen::Vector3d(0.0, 0.0, 0.3);
  ConstraintSolver constraints;
  constraints.add(system, PointTargetConstraint(0, uv, TargetTrajectory::fixed(target)));

  for (const auto algorithm :
       {DesignAlgorithm::kSlsqp, DesignAlgorithm::kAugmentedLagrangianLbfgs}) {
    DesignSettings design;
    design.algorithm = algorithm;
    if (algorithm == DesignAlgorithm::kAugmentedLagrangianLbfgs) {
      // LBFGS's line search ends in NLopt's generic FAILURE when asked for 1e-14 (round-off);
      // 1e-10 reaches XTOL at the same optimum.
      design.variable_tolerance = 1e-10;
    }
    const DesignResult result = minimize_energy(system, &constraints, design);
    const Eigen::VectorXd weights = model.weights(result.coordinates);
    std::cout << "free weights, algorithm " << static_cast<int>(algorithm) << ": "
              << result.iterations << " evaluations, status " << result.status_name << ", energy "
              << result.energy << ", violation " << result.constraint_violation << ", weights "
              << weights.transpose() << "\n";
    EXPECT_TRUE(result.converged()) << result.status_name;
    // The constraint tolerance handed to NLopt is 1e-12; 1e-8 leaves room for the
    // solvers' final step.
    EXPECT_LT(result.constraint_violation, 1e-8);
    EXPECT_GE(weights.minCoeff(), settings.minimum_weight);
    EXPECT_GT((weights.array() - 1.0).abs().maxCoeff(), 1e-2);  // the weights did move
    // Cheaper than the best fixed-weight shape that meets the same constraint.
    DNurbsSurface fixed_model(test::flat_patch(2, 3), material);
    fixed_model.fix_border();
    System fixed_system(fixed_model);
    ConstraintSolver fixed_constraints;
    fixed_constraints.add(fixed_system,
                          PointTargetConstraint(0, uv, TargetTrajectory::fixed(target)));
    const DesignResult fixed = minimize_energy(fixed_system, &fixed_constraints, design);
    EXPECT_LT(result.energy, fixed.energy);
  }
}

}  // namespace
}  // namespace dnurbs

namespace dnurbs {
namespace {

// Two opposite point forces pull a superquadric apart along z: its q_s (springs of stiffness 1
// to the rest shape) settle where k (q_s - rest) = J^T f, with the orientation held and the
// translation fixed.
TEST(EnergyMinimization, SuperquadricShapeParametersBalanceTheForces) {
  DeformableSuperquadricSettings settings;
  settings.parts = DeformableSuperquadricParts::global();
  SuperquadricShapeParameters shape = DeformableSuperquadricShape::sphere(1.0).parameters();
  shape[SuperquadricShapeParameter::kBendFrequency] = 0.5;
  DeformableSuperquadricModel model(shape, Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(),
                                    settings);
  for (int k = 0; k < 3; ++k) {
    model.fix_coordinate(model.translation_velocity_offset() + k);
  }
  System system(model);
  const Eigen::Vector2d top(1.2, 0.3);
  const Eigen::Vector2d bottom(-1.2, 0.3);
  system.add_force(0, test::point_force(top, Eigen::Vector3d(0.0, 0.0, 0.2)));
  system.add_force(0, test::point_force(bottom, Eigen::Vector3d(0.0, 0.0, -0.2)));
  const DesignResult result = minimize_energy(system, nullptr);
  std::cout << "superquadric q_s: " << result.iterations << " evaluations, status "
            << result.status_name << ", energy " << result.energy << "\n";
  EXPECT_TRUE(result.converged()) << result.status_name;

  // Stationarity on the free q_s: f_int(q) + f = 0, f the generalized force at the start (the
  // work of the forces is linearized there, as in solve_static_equilibrium).
  const Eigen::VectorXd& q = result.coordinates;
  Eigen::VectorXd residual = Eigen::VectorXd::Zero(model.velocity_count());
  system.add_applied_forces(0.0, system.coordinates(), residual, residual);
  model.add_internal_force(q, residual);
  const int first = model.shape_velocity_offset();
  const double stationarity = residual.tail(model.velocity_count() - first).norm();
  std::cout << "  stationarity |f_int + f| on q_s " << stationarity << "\n";
  // The energy is quadratic in q_s (diagonal springs): SLSQP stops at the 1e-14 variable
  // tolerance, far inside 1e-8.
  EXPECT_LT(stationarity, 1e-8);
  const SuperquadricShapeParameters fitted = model.shape_parameters(q);
  EXPECT_GT(fitted[SuperquadricShapeParameter::kAspect3], 1.0);  // pulled apart along z
}

}  // namespace
}  // namespace dnurbs
