// Plastic rest shapes of the grid surfaces (dynamics/core/plastic_flow.h): the PDE surface
// (Romero 2005) and the Terzopoulos surface, whose rest positions yield so that a push leaves a
// dent.

#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/grid/pde_surface.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/integrators/semi_implicit_step.h"
#include "tests/common/error_message.h"
#include "tests/common/grid_scenes.h"

namespace dnurbs {
namespace {

using test::sheet_material;
using test::unit_square_grid;
using ::testing::HasSubstr;

constexpr double kYield = 0.05;
constexpr double kRate = 2.0;
constexpr double kDt = 0.1;  // c = min(1, rate dt) = 0.2

PdeSurface plastic_pde_surface() {
  const Grid grid = unit_square_grid(9);
  PdeSurfaceMaterial material;
  material.damping_density = 5.0;
  PdeSurface surface(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()), material);
  surface.set_plastic_flow(PlasticFlow{kYield, kRate});
  return surface;
}

TerzopoulosSurface plastic_terzopoulos_surface() {
  const Grid grid = unit_square_grid(9);
  TerzopoulosSurface surface(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()),
                             sheet_material(0.1, 0.0, 1e-4, 2.0));
  surface.fix_border();
  surface.set_plastic_flow(PlasticFlow{kYield, kRate});
  return surface;
}

// One node held at a distance s = 0.3 from its rest position for n steps: the excess over the
// yield distance decays as (1 - c)^n (0.3 - yield), c = rate dt, along the displacement; every
// other node's rest position stays where it was. Returns the largest error against that.
double single_node_rule_error(Model& model, const std::function<Eigen::VectorXd()>& rest,
                              int node) {
  const Eigen::VectorXd initial = model.initial_coordinates();
  Eigen::VectorXd q = initial;
  const Eigen::Vector3d direction = Eigen::Vector3d(1.0, -2.0, 2.0) / 3.0;
  q.segment<3>(3 * node) += 0.3 * direction;
  const double c = kRate * kDt;
  double error = 0.0;
  for (int n = 1; n <= 6; ++n) {
    EXPECT_EQ(model.flow_rest_shape(q, kDt), 1);
    const Eigen::VectorXd r = rest();
    const double expected_excess = std::pow(1.0 - c, n) * (0.3 - kYield);
    const Eigen::Vector3d expected =
        initial.segment<3>(3 * node) + (0.3 - kYield - expected_excess) * direction;
    error = std::max(error, (r.segment<3>(3 * node) - expected).norm());
    Eigen::VectorXd others = r - initial;
    others.segment<3>(3 * node).setZero();
    EXPECT_EQ(others.lpNorm<Eigen::Infinity>(), 0.0);  // within the yield distance: untouched
  }
  return error;
}

TEST(GridPlasticFlow, ASingleNodeYieldsByTheRuleInClosedForm) {
  PdeSurface pde = plastic_pde_surface();
  const Eigen::VectorXd pde_initial = pde.initial_coordinates();
  const int pde_node = pde.active_slot(pde.grid().index(4, 4));
  const double pde_error = single_node_rule_error(
      pde, [&] { return pde.rest_coordinates(); }, pde_node);
  TerzopoulosSurface sheet = plastic_terzopoulos_surface();
  const Eigen::VectorXd sheet_initial = sheet.initial_coordinates();
  const double sheet_error = single_node_rule_error(
      sheet, [&] { return sheet.flowing_rest_coordinates(); }, sheet.grid().index(4, 4));
  std::cout << "closed-form rest position error: PDE " << pde_error << ", Terzopoulos "
            << sheet_error << "\n";
  // Six updates r += c e d of unit-size numbers: a few ulps each
  EXPECT_LT(pde_error, 1e-15);
  EXPECT_LT(sheet_error, 1e-15);
  // The initial shape is kept apart from the rest shape that flowed
  EXPECT_EQ(pde.initial_coordinates(), pde_initial);
  EXPECT_EQ(sheet.initial_coordinates(), sheet_initial);
}

TEST(GridPlasticFlow, ThePdeSurfaceForceIsMeasuredFromTheFlowedRest) {
  PdeSurface surface = plastic_pde_surface();
  Eigen::VectorXd q = surface.initial_coordinates();
  q[3 * surface.active_slot(surface.grid().index(3, 5)) + 2] = 0.4;
  surface.flow_rest_shape(q, kDt);
  const Eigen::VectorXd d = q - surface.rest_coordinates();
  ASSERT_GT(surface.rest_coordinates().norm(), 0.0);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
  surface.add_internal_force(q, force);
  const Eigen::VectorXd expected = -(surface.constant_matrices()->stiffness * d);
  EXPECT_LT((force - expected).lpNorm<Eigen::Infinity>(),
            1e-12 * expected.lpNorm<Eigen::Infinity>());
  EXPECT_NEAR(surface.potential_energy(q), 0.5 * d.dot(surface.constant_matrices()->stiffness * d),
              1e-14 * d.squaredNorm() * surface.constant_matrices()->stiffness.norm());
  // At the flowed rest shape nothing acts
  force.setZero();
  surface.add_internal_force(surface.rest_coordinates(), force);
  EXPECT_EQ(force.lpNorm<Eigen::Infinity>(), 0.0);
}

TEST(GridPlasticFlow, TheTerzopoulosTensorsFollowTheFlowedRest) {
  TerzopoulosSurface surface = plastic_terzopoulos_surface();
  Eigen::VectorXd q = surface.initial_coordinates();
  for (int k = 0; k < surface.grid().node_count(); ++k) {
    const auto [i, j] = surface.grid().node(k);
    q[3 * k + 2] = 0.3 * std::sin(0.4 * i) * std::cos(0.3 * j);  // a bend of every node
  }
  EXPECT_GT(surface.flow_rest_shape(q, kDt), 40);
  // A surface built with the flowed rest shape has the same G0 and B0: the same force and energy
  // at any state
  const TerzopoulosSurface built(surface.grid(), surface.rest_positions(), surface.material());
  Eigen::VectorXd probe = q;
  probe[3 * 40 + 2] += 0.05;
  Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
  Eigen::VectorXd built_force = Eigen::VectorXd::Zero(q.size());
  surface.add_internal_force(probe, force);
  built.add_internal_force(probe, built_force);
  EXPECT_EQ((force - built_force).lpNorm<Eigen::Infinity>(), 0.0);
  EXPECT_EQ(surface.potential_energy(probe), built.potential_energy(probe));
  // At the flowed rest itself the metric and curvature differences vanish: no force, no energy
  force.setZero();
  surface.add_internal_force(surface.flowing_rest_coordinates(), force);
  EXPECT_EQ(force.lpNorm<Eigen::Infinity>(), 0.0);
  EXPECT_EQ(surface.potential_energy(surface.flowing_rest_coordinates()), 0.0);
}

// A surface pushed down by `push` for 4 s and released for 60 s, in steps of dt of `step`.
// `node` is the node whose height is reported.
struct Dent {
  double loaded = 0.0;             // at the end of the push
  double loaded_rest = 0.0;        // the rest position's height then
  double settled = 0.0;            // at the end
  double settled_from_rest = 0.0;  // |q - rest| at the end
};

Dent push_and_release(const Model& model, int node, const Force& push, double dt,
                      const std::function<void(System&, double)>& step) {
  System system(model);
  system.add_force(0, push);
  const int push_steps = static_cast<int>(std::lround(4.0 / dt));
  for (int s = 0; s < push_steps; ++s) {
    step(system, dt);
  }
  Dent dent;
  const int z = model.control_point_offset(node) + 2;
  dent.loaded = system.coordinates(0)[z];
  dent.loaded_rest = system.model(0).flowing_rest_coordinates()[z];
  system.clear_forces();
  for (int s = 0; s < 15 * push_steps; ++s) {
    step(system, dt);
  }
  dent.settled = system.coordinates(0)[z];
  dent.settled_from_rest = (system.coordinates(0) - system.model(0).flowing_rest_coordinates())
                               .lpNorm<Eigen::Infinity>();
  return dent;
}

TEST(GridPlasticFlow, APushBeyondTheYieldDistanceMovesTheRestShape) {
  for (const double yield : {kYield, 100.0}) {  // 100: never reached, fully elastic
    // The PDE surface pushed at its centre node, implicit Euler: released, the damped surface
    // settles on its rest shape, which the push has moved
    PdeSurface pde = plastic_pde_surface();
    pde.set_plastic_flow(PlasticFlow{yield, kRate});
    const int centre = pde.active_slot(pde.grid().index(4, 4));
    Integrator integrator(IntegratorSettings{IntegratorScheme::kImplicitEuler});
    const Dent dent = push_and_release(
        pde, centre, control_point_force({centre}, Eigen::Vector3d(0.0, 0.0, -20.0)), kDt,
        [&](System& system, double dt) { integrator.step(system, dt); });
    // The Terzopoulos sheet under a load on every node, stepped as in Wu & de Melo (the
    // semi-implicit step at dt = 0.005; the linearized K is indefinite where B < B0, which the
    // linearly implicit Euler step cannot factor). Released, a sheet this little resistant to
    // curving may pop through to the mirrored bump (as elastic as the dent): only the push's
    // effect on the rest shape is checked.
    TerzopoulosSurface sheet = plastic_terzopoulos_surface();
    sheet.set_plastic_flow(PlasticFlow{yield, kRate});
    SemiImplicitStepper stepper;
    const Dent sheet_dent =
        push_and_release(sheet, sheet.grid().index(4, 4), gravity(Eigen::Vector3d(0.0, 0.0, -0.5)),
                         0.005, [&](System& system, double dt) { stepper.step(system, dt); });
    std::cout << "yield " << yield << ": PDE centre " << dent.loaded << " loaded (rest "
              << dent.loaded_rest << "), " << dent.settled << " settled (" << dent.settled_from_rest
              << " from rest); Terzopoulos centre " << sheet_dent.loaded << " loaded (rest "
              << sheet_dent.loaded_rest << ")\n";
    EXPECT_LT(dent.loaded, -2.0 * kYield);
    EXPECT_LT(sheet_dent.loaded, -2.0 * kYield);
    // Implicit Euler's fixed point is f_int = 0: the rest shape (what is left is the decay of
    // the slowest mode over 60 s)
    EXPECT_LT(dent.settled_from_rest, 1e-8);
    if (yield == kYield) {
      // The rest followed the node far beyond the yield distance, lagging it by the yield
      // distance plus the excess of a node still sinking (about its speed / rate)
      for (const Dent& pushed : {dent, sheet_dent}) {
        EXPECT_LT(pushed.loaded_rest, -5.0 * kYield);
        EXPECT_LT(pushed.loaded_rest, pushed.loaded + 3.0 * kYield);
        EXPECT_GT(pushed.loaded_rest, pushed.loaded + kYield);
      }
      // The dent stays, smaller than under the load: the elastic part springs back
      EXPECT_LT(dent.settled, 0.5 * dent.loaded);
      EXPECT_GT(dent.settled, dent.loaded);
    } else {
      EXPECT_EQ(dent.loaded_rest, 0.0);
      EXPECT_EQ(sheet_dent.loaded_rest, 0.0);
      EXPECT_LT(std::abs(dent.settled), 1e-8);
    }
  }
}

TEST(GridPlasticFlow, RestCoordinatesAreRestoredOrRefusedNamingTheValue) {
  PdeSurface pde = plastic_pde_surface();
  TerzopoulosSurface sheet = plastic_terzopoulos_surface();
  for (Model* model : std::initializer_list<Model*>{&pde, &sheet}) {
    Eigen::VectorXd rest = model->flowing_rest_coordinates();
    ASSERT_EQ(rest.size(), model->coordinate_count());
    rest[7] = 0.25;
    model->restore_flowing_rest_coordinates(rest);
    EXPECT_EQ(model->flowing_rest_coordinates(), rest);
    EXPECT_THAT(testing::error_message(
                    [&] { model->restore_flowing_rest_coordinates(rest.head(rest.size() - 1)); }),
                HasSubstr("rest coordinates: " + std::to_string(rest.size() - 1) + " given"));
    rest[4] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THAT(testing::error_message([&] { model->restore_flowing_rest_coordinates(rest); }),
                HasSubstr("rest coordinate 4 is nan"));
  }
  EXPECT_THAT(testing::error_message([&] {
                pde.set_plastic_flow(PlasticFlow{-1.0, 1.0});
              }),
              HasSubstr("plastic yield -1"));
  EXPECT_THAT(testing::error_message([&] {
                sheet.set_plastic_flow(PlasticFlow{0.1, 0.0});
              }),
              HasSubstr("plastic rate 0"));
  // Without plastic flow there is no rest shape to restore, and none flows
  pde.set_plastic_flow(std::nullopt);
  EXPECT_EQ(pde.flowing_rest_coordinates().size(), 0);
  Eigen::VectorXd far = pde.initial_coordinates();
  far.setConstant(5.0);
  EXPECT_EQ(pde.flow_rest_shape(far, kDt), 0);
  EXPECT_THAT(testing::error_message(
                  [&] { pde.restore_flowing_rest_coordinates(pde.initial_coordinates()); }),
              HasSubstr("this model's rest shape does not flow"));
}

}  // namespace
}  // namespace dnurbs
