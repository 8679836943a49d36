// The rest shape and plastic flow of swung D-NURBS surfaces (dynamics/swung/dnurbs_swung_surface.h,
// file comment): at the rest shape the internal force is exactly zero; the force is -dE/dq of
// E = 1/2 integral sum_Q k_Q |S^Q(q) - S^Q(q_r)|^2 (central differences) and equals the
// tensor-product twin's with the twin's rest shape; E is the quadratic form of the rest stiffness
// exactly when one curve moves, to third order otherwise; the yield rule moves a held control
// point's rest position by its closed form; and a pushed sphere keeps a dent where an elastic
// twin springs back.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <optional>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/swung/dnurbs_swung_surface.h"
#include "dnurbs/nurbs/swung_refinement.h"
#include "dnurbs/nurbs/swung_shapes.h"
#include "tests/common/error_message.h"
#include "tests/dynamics/swung/swung_model_helpers.h"
#include "tests/nurbs/swung_sample_shapes.h"

namespace dnurbs {
namespace {

using testing::error_message;
using ::testing::HasSubstr;
using testing::model_cases;
using testing::ModelCase;
using testing::perturbed;
using testing::plate_material;
using testing::random_vector;

// The thin plate of plate_material with a constant mass density, so that fixed weights take the
// separable path.
DNurbsSurfaceMaterial constant_plate() {
  DNurbsSurfaceMaterial material = plate_material();
  material.mass_density = 1.2;
  return material;
}

DNurbsSwungSettings rest_settings(WeightMode mode, bool separable, bool geometric = false) {
  DNurbsSwungSettings settings;
  settings.weight_mode = mode;
  settings.separable_assembly = separable;
  settings.geometric_stiffness = geometric;
  settings.initial_shape_at_rest = true;
  return settings;
}

// Every model case with the varying plate (general quadrature), and the fixed-weight cases with
// the constant plate on both paths.
struct RestCase {
  const char* name;
  DNurbsSwungSurface model;
  DNurbsSurfaceMaterial material;
};
std::vector<RestCase> rest_cases(bool geometric = false) {
  std::vector<RestCase> cases;
  for (const ModelCase& c : model_cases()) {
    cases.push_back(
        {c.name,
         DNurbsSwungSurface(c.surface, plate_material(), rest_settings(c.mode, false, geometric)),
         plate_material()});
    if (c.mode == WeightMode::kFixed) {
      for (const bool separable : {true, false}) {
        cases.push_back({c.name,
                         DNurbsSwungSurface(c.surface, constant_plate(),
                                            rest_settings(c.mode, separable, geometric)),
                         constant_plate()});
      }
    }
  }
  return cases;
}

Eigen::VectorXd internal_force(const Model& model, const Eigen::VectorXd& q) {
  Eigen::VectorXd force = Eigen::VectorXd::Zero(model.velocity_count());
  model.add_internal_force(q, force);
  return force;
}

TEST(SwungRestShape, AtTheInitialRestTheForceAndEnergyAreExactlyZero) {
  int separable_cases = 0;
  for (const RestCase& c : rest_cases()) {
    const DNurbsSwungSurface& model = c.model;
    separable_cases += model.uses_separable_assembly() ? 1 : 0;
    ASSERT_TRUE(model.has_rest_shape());
    EXPECT_EQ(model.rest_coordinates(), model.initial_coordinates());
    const Eigen::VectorXd q = model.initial_coordinates();
    // S^Q(q) - S^Q(q_r) (or q - q_r in the closed forms) by the same arithmetic: exactly 0
    EXPECT_EQ(internal_force(model, q).lpNorm<Eigen::Infinity>(), 0.0) << c.name;
    EXPECT_EQ(model.potential_energy(q), 0.0) << c.name;
    // Measured from zero, tension pulls every one of these surfaces towards its axis
    DNurbsSwungSettings from_zero =
        rest_settings(model.weight_mode(), model.uses_separable_assembly());
    from_zero.initial_shape_at_rest = false;
    const DNurbsSwungSurface pulled(model.initial_surface(), c.material, from_zero);
    EXPECT_FALSE(pulled.has_rest_shape());
    EXPECT_GT(internal_force(pulled, q).lpNorm<Eigen::Infinity>(), 0.1) << c.name;
  }
  EXPECT_EQ(separable_cases, 2);  // the random surface and the sphere
}

TEST(SwungRestShape, InternalForceIsMinusTheEnergyGradientAndTheTangentItsDerivative) {
  for (const bool geometric : {false, true}) {
    for (RestCase& c : rest_cases(geometric)) {
      DNurbsSwungSurface& model = c.model;
      model.set_rest_shape(perturbed(model, 5));
      const Eigen::VectorXd q = perturbed(model, 9);
      const Eigen::VectorXd force = internal_force(model, q);
      ModelMatrices matrices;
      model.assemble_matrices(q, matrices);
      const Eigen::MatrixXd stiffness(matrices.stiffness);
      // Central differences of E and of f_int: truncation (h^2 / 6) |E'''| ~ 1e-11 and
      // round-off eps |E| / h ~ 1e-10 relative to |f|; 1e-7 is far above both, far below a
      // missing rest term (of the size of f itself).
      const double h = 1e-5;
      double force_error = 0.0;
      double tangent_error = 0.0;
      for (Eigen::Index k = 0; k < q.size(); ++k) {
        Eigen::VectorXd plus = q;
        Eigen::VectorXd minus = q;
        plus[k] += h;
        minus[k] -= h;
        const double gradient =
            (model.potential_energy(plus) - model.potential_energy(minus)) / (2 * h);
        force_error = std::max(force_error, std::abs(force[k] + gradient));
        if (geometric) {
          // The exact tangent d^2E/dq^2, its second-derivative part weighed by S^Q - S^Q(q_r)
          const Eigen::VectorXd column =
              -(internal_force(model, plus) - internal_force(model, minus)) / (2 * h);
          tangent_error =
              std::max(tangent_error, (stiffness.col(k) - column).lpNorm<Eigen::Infinity>());
        }
      }
      EXPECT_LT(force_error, 1e-7 * force.lpNorm<Eigen::Infinity>()) << c.name;
      EXPECT_LT(tangent_error, 1e-7 * stiffness.lpNorm<Eigen::Infinity>()) << c.name;
    }
  }
}

TEST(SwungRestShape, EnergyAndForceAreTheTensorProductTwinsWithItsRestShape) {
  // The twin's control points Q(q) give the same surface, so its energy from the rest Q(q_r)
  // is the swung one, and its force comes back through the chain rule C = dQ/dq.
  for (const RestCase& c : rest_cases()) {
    if (c.model.weight_mode() == WeightMode::kFree) {
      continue;  // the twin's free weights carry a weight anchor the swung model has not
    }
    DNurbsSwungSurface model = c.model;
    const Eigen::VectorXd rest = perturbed(model, 5);
    model.set_rest_shape(rest);
    const Eigen::VectorXd q = perturbed(model, 9);
    DNurbsSettings twin_settings;
    twin_settings.quadrature_points = 0;
    DNurbsSurface twin(model.initial_surface().to_nurbs_surface(), c.material, twin_settings);
    twin.set_rest_shape(testing::twin_coordinates(model, rest));
    const Eigen::VectorXd twin_q = testing::twin_coordinates(model, q);
    const double energy = model.potential_energy(q);
    // The same Gauss points, the integrands regrouped: round-off of the sums
    EXPECT_NEAR(energy, twin.potential_energy(twin_q), 1e-12 * energy) << c.name;
    const Eigen::VectorXd force = internal_force(model, q);
    const Eigen::VectorXd twin_force =
        testing::twin_chain_rule(model, q).transpose() * internal_force(twin, twin_q);
    EXPECT_LT((force - twin_force).lpNorm<Eigen::Infinity>(),
              1e-12 * force.lpNorm<Eigen::Infinity>())
        << c.name;
  }
}

TEST(SwungRestShape, EnergyIsTheQuadraticFormOfTheRestStiffness) {
  for (const RestCase& c : rest_cases()) {
    const DNurbsSwungSurface& model = c.model;
    if (model.weight_mode() == WeightMode::kFree) {
      continue;  // a rational curve is not linear in its weights
    }
    const Eigen::VectorXd rest = model.initial_coordinates();
    ModelMatrices matrices;
    model.assemble_matrices(rest, matrices);
    const Eigen::MatrixXd stiffness(matrices.stiffness);
    // At the rest shape the exact tangent has no second-derivative part (S^Q - S^Q(q_r) = 0)
    DNurbsSwungSettings exact =
        rest_settings(WeightMode::kFixed, model.uses_separable_assembly(), true);
    const DNurbsSwungSurface tangent_model(model.initial_surface(), c.material, exact);
    ModelMatrices tangent;
    tangent_model.assemble_matrices(rest, tangent);
    EXPECT_LT((Eigen::MatrixXd(tangent.stiffness) - stiffness).lpNorm<Eigen::Infinity>(),
              1e-14 * stiffness.lpNorm<Eigen::Infinity>())
        << c.name;

    // One curve moved: S is linear in that curve's coordinates, E = 1/2 d^T K(q_r) d and
    // f_int = -K(q_r) d in its rows, up to the round-off of the sums
    const int split = model.layout().trajectory_offset(0);
    const Eigen::VectorXd random = 0.05 * random_vector(rest.size(), 21);
    for (const bool profile : {true, false}) {
      Eigen::VectorXd d = Eigen::VectorXd::Zero(rest.size());
      const Eigen::Index start = profile ? 0 : split;
      const Eigen::Index count = profile ? split : rest.size() - split;
      d.segment(start, count) = random.segment(start, count);
      const double quadratic = 0.5 * d.dot(stiffness * d);
      EXPECT_NEAR(model.potential_energy(rest + d), quadratic, 1e-12 * quadratic) << c.name;
      const Eigen::VectorXd force = internal_force(model, rest + d);
      const Eigen::VectorXd linear = -stiffness * d;
      EXPECT_LT((force - linear).segment(start, count).lpNorm<Eigen::Infinity>(),
                1e-12 * linear.lpNorm<Eigen::Infinity>())
          << c.name;
    }
    // Both curves moved: the remainder E - 1/2 d^T K d is of third order (S bilinear in the
    // curves): halving d divides it by 8, up to the fourth-order term (a few percent here)
    double remainder[2];
    for (int halving = 0; halving < 2; ++halving) {
      const Eigen::VectorXd d = random / std::pow(2.0, halving);
      remainder[halving] = model.potential_energy(rest + d) - 0.5 * d.dot(stiffness * d);
    }
    EXPECT_NEAR(remainder[0] / remainder[1], 8.0, 0.5) << c.name;
    std::cout << c.name << (model.uses_separable_assembly() ? " (separable)" : "")
              << ": third-order remainder ratio " << remainder[0] / remainder[1] << "\n";
  }
}

TEST(SwungRestShape, AHeldControlPointsRestFollowsTheYieldRulesClosedForm) {
  DNurbsSwungSettings settings = rest_settings(WeightMode::kFree, false);
  settings.plastic_flow = PlasticFlow{0.1, 3.0};
  DNurbsSwungSurface model(swung_sphere(1.0), plate_material(), settings);
  EXPECT_TRUE(model.has_rest_shape());
  const Eigen::VectorXd initial = model.initial_coordinates();
  Eigen::VectorXd q = initial;
  const int x = model.profile_offset(2);  // the equator's profile point, x
  const int y = model.trajectory_offset(3) + 1;
  q[x] += 0.5;            // beyond the yield distance: flows
  q[y] += 0.08;           // within it: elastic
  q[x + 2] *= 1.5;        // a weight: never flows
  const double dt = 0.1;  // c = rate dt = 0.3
  for (int n = 1; n <= 12; ++n) {
    EXPECT_EQ(model.flow_rest_shape(q, dt), 1);
    const Eigen::VectorXd rest = model.flowing_rest_coordinates();
    // r_n - r_0 = (d - yield) (1 - (1 - c)^n), the excess (d - yield) (1 - c)^n
    EXPECT_NEAR(rest[x] - initial[x], 0.4 * (1.0 - std::pow(0.7, n)), 1e-15) << n;
    Eigen::VectorXd others = rest - initial;
    others[x] = 0.0;
    EXPECT_EQ(others.lpNorm<Eigen::Infinity>(), 0.0) << n;
  }
  // Through System steps: the equator point held 0.5 out, the rest follows the same law
  DNurbsSwungSurface held = DNurbsSwungSurface(swung_sphere(1.0), plate_material(), settings);
  held.fix_profile_point(2);
  System system(held);
  Eigen::VectorXd start = held.initial_coordinates();
  start[x] += 0.5;
  system.set_state(start, Eigen::VectorXd::Zero(start.size()), 0.0);
  IntegratorSettings integrator_settings;
  integrator_settings.scheme = IntegratorScheme::kImplicitEuler;
  integrator_settings.newton_iterations = 1;
  Integrator integrator(integrator_settings);
  for (int n = 1; n <= 5; ++n) {
    integrator.step(system, dt);
    EXPECT_NEAR(system.flowing_rest_coordinates()[x] - initial[x], 0.4 * (1.0 - std::pow(0.7, n)),
                1e-15)
        << n;
  }
}

// The equator pushed in along -x for one second, then released; the run settles by t = 8.
struct DentRun {
  double pushed = 0.0;  // the equator point's inward displacement at release
  double final = 0.0;   // and at the end
  double rest = 0.0;    // the rest shape's at the end
  double speed = 0.0;   // |qd| at the end
};

DentRun run_dent(std::optional<PlasticFlow> flow) {
  DNurbsSurfaceMaterial material;
  material.damping_density = 3.0;
  material.a10 = 1.0;
  material.a01 = 1.0;
  material.b20 = 0.1;
  material.b11 = 0.1;
  material.b02 = 0.1;
  DNurbsSwungSettings settings = rest_settings(WeightMode::kFixed, true);
  settings.plastic_flow = flow;
  DNurbsSwungSurface sphere(refine_swung_surface(swung_sphere(1.0), 1, 0), material, settings);
  sphere.fix_poles();
  sphere.fix_trajectory();  // a surface of revolution throughout: the equator moves as a ring
  System system(sphere);
  const Eigen::Vector2d equator(0.5, 0.0);
  system.add_force(0, windowed(point_force(equator, Eigen::Vector3d(-8.0, 0.0, 0.0)), 0.0, 1.0));
  IntegratorSettings integrator_settings;
  integrator_settings.scheme = IntegratorScheme::kImplicitEuler;
  integrator_settings.newton_iterations = 1;
  Integrator integrator(integrator_settings);
  DentRun run;
  const double dt = 0.02;
  for (int step = 1; step <= 400; ++step) {
    integrator.step(system, dt);
    if (step == 50) {
      run.pushed = 1.0 - system.position(0, equator).x();
    }
  }
  run.final = 1.0 - system.position(0, equator).x();
  const Eigen::VectorXd rest =
      flow ? system.flowing_rest_coordinates() : Eigen::VectorXd(sphere.initial_coordinates());
  run.rest = 1.0 - sphere.position(rest, equator).x();
  run.speed = system.velocities().norm();
  return run;
}

TEST(SwungRestShape, APushedSphereKeepsADentWhileAnElasticTwinSpringsBack) {
  const DentRun elastic = run_dent(std::nullopt);
  const DentRun plastic = run_dent(PlasticFlow{0.01, 4.0});
  std::cout << "equator pushed in by " << elastic.pushed << " (elastic) and " << plastic.pushed
            << " (plastic); at t = 8: " << elastic.final << " and " << plastic.final
            << ", the plastic rest shape's " << plastic.rest << "; |qd| " << elastic.speed
            << " and " << plastic.speed << "\n";
  // Both were pushed in visibly; the plastic one gives more (its rest yields under the load)
  EXPECT_GT(elastic.pushed, 0.05);
  EXPECT_GT(plastic.pushed, elastic.pushed);
  // The elastic sphere springs back to its rest: what is left decays with the damping
  EXPECT_LT(std::abs(elastic.final), 1e-3 * elastic.pushed);
  // The plastic one keeps a dent of most of the push, and has settled at its moved rest
  EXPECT_GT(plastic.final, 0.5 * plastic.pushed);
  EXPECT_LT(std::abs(plastic.final - plastic.rest), 1e-3 * plastic.final);
  EXPECT_LT(plastic.speed, 1e-3);
}

TEST(SwungRestShape, ReleasingTheGaugeKeepsTheRestShapeAndItsFlow) {
  DNurbsSwungSettings settings = rest_settings(WeightMode::kFixed, true);
  settings.plastic_flow = PlasticFlow{0.01, 2.0};
  DNurbsSwungSurface model(swung_sphere(1.0), constant_plate(), settings);
  const Eigen::VectorXd rest = perturbed(model, 4);
  model.set_rest_shape(rest);
  ASSERT_GE(model.gauge_coordinate(), 0);
  model.fix_trajectory_point(1);  // off the origin: breaks the scaling, the gauge is released
  EXPECT_EQ(model.gauge_coordinate(), -1);
  EXPECT_EQ(model.rest_coordinates(), rest);
  ASSERT_TRUE(model.plastic_flow().has_value());
  EXPECT_EQ(model.plastic_flow()->yield, 0.01);
  EXPECT_EQ(internal_force(model, rest).lpNorm<Eigen::Infinity>(), 0.0);
}

TEST(SwungRestShape, BadRestShapesAndRulesAreRefusedByName) {
  DNurbsSwungSurface model(swung_sphere(1.0), plate_material(),
                           rest_settings(WeightMode::kFree, false));
  Eigen::VectorXd rest = model.initial_coordinates();
  EXPECT_THAT(error_message([&] { model.set_rest_shape(rest.head(4)); }),
              HasSubstr("rest shape vector has 4 entries, the swung surface has"));
  rest[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(error_message([&] { model.set_rest_shape(rest); }),
              HasSubstr("rest shape: coordinate 3 is nan (not finite)"));
  rest = model.initial_coordinates();
  rest[5] = 1e-4;
  EXPECT_THAT(
      error_message([&] { model.set_rest_shape(rest); }),
      HasSubstr("rest shape: weight coordinate 5 is 1e-04, below the minimum weight 0.001"));
  EXPECT_THAT(error_message([&] {
                model.set_plastic_flow(PlasticFlow{-1.0, 1.0});
              }),
              HasSubstr("plastic yield -1"));
  // Without plastic flow there is no flowing rest shape to restore
  EXPECT_EQ(model.flowing_rest_coordinates().size(), 0);
  EXPECT_EQ(model.flow_rest_shape(model.initial_coordinates(), 0.1), 0);
  EXPECT_THAT(error_message([&] { model.restore_flowing_rest_coordinates(rest); }),
              HasSubstr("this model's rest shape does not flow"));
  // Stopping the flow keeps the rest where it is
  model.set_plastic_flow(PlasticFlow{0.0, 1.0});
  const Eigen::VectorXd kept = model.rest_coordinates();
  model.set_plastic_flow(std::nullopt);
  EXPECT_EQ(model.rest_coordinates(), kept);
}

}  // namespace
}  // namespace dnurbs
