// Hard cases, well-posed free weights (issue 16, part 3; rational_control_net_model.h, "Well-posed
// free weights"): straight and curved rods (cubic, 9 control points, ends fixed) and flat and
// curved sheets (bicubic, 6 by 6, border fixed), each pushed by a constant point force and pulled
// by a mouse spring to a fixed target, 10,000 newmark steps of dt = 0.01 with free weights, the
// default (scale-aware) weight regularization and the default integrator settings (which iterate
// Newton for free weights: IntegratorSettings::automatic_newton).
//
// Before the regularization (the base commit, exact D-NURBS with weight inertia 0) all eight
// failed: the straight rod and the flat sheet (pushed and pulled) at their first step, the
// effective matrix not factorable (M singular beyond the gauge); the curved rod diverged to energy
// > 1e12 at step 4 (pushed) and 2 (pulled), the curved sheet at step 7 and 5. With a weight
// inertia alone (1e-5 to 1e-2, no weight stiffness) the sheets still diverged within 10 to 340
// steps, their weights drifting into the minimum along the null directions.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/spring.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "hardcase_helpers.h"

namespace dnurbs {
namespace {

using hardcase::record_result;

constexpr int kSteps = 10000;
constexpr double kDt = 0.01;

DNurbsSettings free_weights() {
  DNurbsSettings settings;
  settings.weight_mode = WeightMode::kFree;
  return settings;
}

// The cubic rod x(u) = (u, 0, 0) (linear parametrization) or bent to z = 0.3 sin(pi x).
NurbsCurve rod(bool curved) {
  const KnotVector knots = KnotVector::clamped_uniform(3, 6 + 3);
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(knots.control_point_count(), 3);
  points.col(0) = hardcase::greville(knots);
  if (curved) {
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      points(i, 2) = 0.3 * std::sin(M_PI * points(i, 0));
    }
  }
  return NurbsCurve(knots, points);
}

// The flat bicubic (u, v, 0) with 6 by 6 control points, or bulged to z = 0.2 sin(pi x) sin(pi y).
NurbsSurface sheet(bool curved) {
  const NurbsSurface flat = hardcase::flat_bicubic(3);
  if (!curved) {
    return flat;
  }
  Eigen::MatrixX3d points = flat.control_points();
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    points(i, 2) = 0.2 * std::sin(M_PI * points(i, 0)) * std::sin(M_PI * points(i, 1));
  }
  return NurbsSurface(flat.knots_u(), flat.knots_v(), points);
}

System make_system(bool is_rod, bool curved) {
  if (is_rod) {
    DNurbsCurveMaterial material;
    material.damping_density = 0.5;
    material.tension = 1.0;
    material.rigidity = 0.01;
    DNurbsCurve model(rod(curved), material, free_weights());
    model.fix_control_point(0);
    model.fix_control_point(model.control_point_count() - 1);
    return System(model);
  }
  DNurbsSurfaceMaterial material;
  material.damping_density = 0.5;
  material.a10 = material.a01 = 1.0;
  material.b20 = material.b02 = 0.01;
  DNurbsSurface model(sheet(curved), material, free_weights());
  model.fix_border();
  return System(model);
}

struct RunResult {
  int steps = 0;              // accepted steps
  std::string refused;        // the message of a refused step
  double largest_excess = 0;  // max over steps of (E_n - E_0 - W_n) / (E_0 + |W|_max)
  double largest_energy = 0;
  double smallest_weight = std::numeric_limits<double>::infinity();
};

// E_n = kinetic + elastic + spring energy; W_n = f . (x_n(u) - x_0(u)), the work of the constant
// push (the pull's spring is conservative: its energy is in E_n, its work 0).
RunResult run_case(bool is_rod, bool curved, bool pull) {
  System system = make_system(is_rod, curved);
  const Eigen::Vector2d u = is_rod ? Eigen::Vector2d(0.4, 0.0) : Eigen::Vector2d(0.4, 0.6);
  const Eigen::Vector3d force(0.0, 0.0, -1.0);
  const Eigen::Vector3d x0 = system.position(0, u);
  if (pull) {
    const Eigen::Vector3d target = x0 + Eigen::Vector3d(0.0, 0.0, 0.3);
    system.add_spring(0, mouse_spring(
                             u, [target](double) { return target; }, 10.0));
  } else {
    system.add_force(0, point_force(u, force));
  }
  const auto& model = dynamic_cast<const RationalControlNetModel&>(system.model(0));
  const double e0 = system.kinetic_energy() + system.potential_energy() + system.spring_energy();
  Integrator integrator;
  RunResult result;
  result.largest_excess = -std::numeric_limits<double>::infinity();
  double largest_work = 0.0;
  try {
    for (int n = 0; n < kSteps; ++n) {
      integrator.step(system, kDt);
      const double e = system.kinetic_energy() + system.potential_energy() + system.spring_energy();
      const double work = pull ? 0.0 : force.dot(system.position(0, u) - x0);
      largest_work = std::max(largest_work, std::abs(work));
      result.largest_excess =
          std::max(result.largest_excess, (e - e0 - work) / (e0 + largest_work));
      result.largest_energy = std::max(result.largest_energy, e);
      result.smallest_weight =
          std::min(result.smallest_weight, model.weights(system.coordinates()).minCoeff());
      result.steps = n + 1;
    }
  } catch (const Error& error) {
    result.refused = error.what();
  }
  return result;
}

struct Case {
  const char* name;
  bool is_rod;
  bool curved;
  bool pull;
};

constexpr std::array<Case, 8> kCases{{{"straight rod pushed", true, false, false},
                                      {"straight rod pulled", true, false, true},
                                      {"curved rod pushed", true, true, false},
                                      {"curved rod pulled", true, true, true},
                                      {"flat sheet pushed", false, false, false},
                                      {"flat sheet pulled", false, false, true},
                                      {"curved sheet pushed", false, true, false},
                                      {"curved sheet pulled", false, true, true}}};

class FreeWeightRuns : public ::testing::TestWithParam<Case> {};

TEST_P(FreeWeightRuns, EnergyStaysWithinTheWorkDoneAndWeightsAboveTheMinimum) {
  const Case c = GetParam();
  const RunResult r = run_case(c.is_rod, c.curved, c.pull);
  // No refused step: all 10,000 accepted.
  EXPECT_EQ(r.refused, "");
  EXPECT_EQ(r.steps, kSteps);
  // Energy bound from the power balance (energy_budget.h): with damping 0.5 the energy may only
  // fall below E_0 + W. Measured: the largest (E_n - E_0 - W_n) / (E_0 + |W|) is <= 0 in all
  // eight cases (the damping dissipates); the 1e-6 allows the linearly implicit step's
  // truncation error of a state-dependent M, O(dt^2) per unit of moved energy, if it ever beat
  // the dissipation.
  EXPECT_LE(r.largest_excess, 1e-6) << c.name;
  // The fixed-weight twins reach 0.78 to 1.55; free weights with the regularization the same
  // within 2% (measured 0.777 to 1.56): a bound of 2 catches any runaway.
  EXPECT_LE(r.largest_energy, 2.0) << c.name;
  // Every weight at or above the minimum 1e-3.
  EXPECT_GE(r.smallest_weight, 1e-3) << c.name;
  record_result(std::string("largest energy over 10,000 steps, free weights, ") + c.name,
                r.largest_energy, "<= 2, E_n <= E_0 + W_n, weights >= 1e-3");
}

INSTANTIATE_TEST_SUITE_P(PushedAndPulled, FreeWeightRuns, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string name = info.param.name;
                           std::replace(name.begin(), name.end(), ' ', '_');
                           return name;
                         });

// examples/scenes/curve_sculpting.json with free weights (its rod: cubic, 8 control points
// evenly spaced on [0, 7] with uniform knots, mass 1, damping 2, tension 5, rigidity 0.5, the
// end control points fixed), from rest with no force: before the regularization one newmark step
// of dt = 0.01 jumped to kinetic energy 2.6e9 (issue 16). This start is far from equilibrium
// (elastic energy 370, initial acceleration 4.8e4 mostly in the weights, which reparametrize the
// rod). With the default integrator settings (IntegratorSettings::automatic_newton: Newton
// iterations for free weights) the run takes every step; linearly implicit it is refused at step
// 16, with one Newton iteration at step 66, with two its energy rises to 1.44 E_0 (measured).
struct SculptingRun {
  int steps = 0;
  double first_kinetic = 0.0;   // kinetic energy after step 1 / E_0
  double largest_excess = 0.0;  // max_n E_n / E_0 - 1
  double final_ratio = 0.0;     // E_end / E_0
  double smallest_weight = 0.0;
  double minimum_weight = 0.0;
};

SculptingRun run_curve_sculpting(double dt, double duration) {
  const KnotVector knots = KnotVector::clamped_uniform(3, 8);
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(8, 3);
  for (int i = 0; i < 8; ++i) {
    points(i, 0) = i;
  }
  DNurbsCurveMaterial material;
  material.damping_density = 2.0;
  material.tension = 5.0;
  material.rigidity = 0.5;
  DNurbsCurve model(NurbsCurve(knots, points), material, free_weights());
  model.fix_control_point(0);
  model.fix_control_point(7);
  System system(model);
  const auto& rod = dynamic_cast<const RationalControlNetModel&>(system.model(0));
  const double e0 = system.kinetic_energy() + system.potential_energy();
  Integrator integrator;
  SculptingRun run;
  run.minimum_weight = rod.minimum_weight();
  run.smallest_weight = std::numeric_limits<double>::infinity();
  const auto steps = static_cast<int>(std::lround(duration / dt));
  for (int n = 0; n < steps; ++n) {
    integrator.step(system, dt);  // throws (fails the test) on a refused step
    const double e = system.kinetic_energy() + system.potential_energy();
    if (n == 0) {
      run.first_kinetic = system.kinetic_energy() / e0;
    }
    run.largest_excess = std::max(run.largest_excess, e / e0 - 1.0);
    run.final_ratio = e / e0;
    run.smallest_weight =
        std::min(run.smallest_weight, rod.weights(system.coordinates()).minCoeff());
    run.steps = n + 1;
  }
  return run;
}

TEST(FreeWeightCurveSculpting, DefaultStepsTakeEveryStepAndTheEnergyRiseIsTruncationError) {
  const SculptingRun coarse = run_curve_sculpting(0.01, 2.0);
  const SculptingRun fine = run_curve_sculpting(0.005, 2.0);
  EXPECT_EQ(coarse.steps, 200);
  // The first step's kinetic energy is bounded by the elastic energy it can release: <= E_0
  // (measured 127 / 370 = 0.34; 2.6e9 before).
  EXPECT_LE(coarse.first_kinetic, 1.0);
  // From rest, without forces and with damping, the exact E(t) <= E_0 (energy_budget.h). Newmark
  // keeps that only up to its truncation error when M depends on q: the excess over E_0 must fall
  // at least as fast as the scheme's order 2 when dt halves (measured 7.4e-2 at dt = 0.01,
  // 1.3e-3 at 0.005, none below: order 5.8, the violent start being resolved).
  EXPECT_LE(fine.largest_excess, 0.25 * coarse.largest_excess);
  // The damping dissipates: the energy after 2 s is below E_0 (measured 0.50 and 0.44 E_0)
  EXPECT_LT(coarse.final_ratio, 1.0);
  EXPECT_LT(fine.final_ratio, 1.0);
  EXPECT_GE(coarse.smallest_weight, coarse.minimum_weight);
  record_result("largest E_n / E_0 - 1, curve_sculpting rod with free weights, dt = 0.01 and 0.005",
                coarse.largest_excess, "falls >= 4x when dt halves (order >= 2); every step taken");
}

}  // namespace
}  // namespace dnurbs
