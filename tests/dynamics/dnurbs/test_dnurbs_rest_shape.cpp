// The rest shape of the D-NURBS energy (dynamics/dnurbs/dnurbs_model.h): with the initial shape
// as rest, every generated shape (nurbs/shape_generators.h, nurbs/primitive_shapes.h) feels no
// internal force, while the energy measured from zero (Terzopoulos 2003, eq. 1.20) pulls every
// curved one. The force is -dE/dq of E = 1/2 integral sum_alpha k_alpha |x^alpha(q) -
// x^alpha(q_r)|^2 (central differences), a pushed shape returns to its rest shape, and static
// equilibrium holds the rest shape.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/sparse_matrix.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/integrators/static_equilibrium.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "dnurbs/nurbs/shape_generators.h"
#include "tests/common/dynamics_test_helpers.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

DNurbsSettings rest_settings(WeightMode mode, bool at_rest) {
  DNurbsSettings settings;
  settings.weight_mode = mode;
  settings.initial_shape_at_rest = at_rest;
  return settings;
}

// Every surface generator of the library, named.
std::vector<std::pair<std::string, NurbsSurface>> generated_surfaces() {
  std::vector<NurbsCurve> sections;
  sections.push_back(full_circle(1.0));
  sections.push_back(full_circle(0.6, {0, 0, 1}));
  sections.push_back(full_circle(0.9, {0.1, 0, 2}));
  return {
      {"plane", greville_plane({2, 1.5}, {6, 5}, {3, 2})},
      {"box", box({1, 2, 0.5})},
      {"cylinder", cylinder(0.5, 2.0)},
      {"cone", cone(1.0, 1.5)},
      {"sphere", sphere(1.3)},
      {"torus", torus(1.0, 0.3)},
      {"periodic torus", periodic_torus(1.0, 0.3)},
      {"revolve", revolve(straight_profile(0.5, 0.0, 1.0, 1.0, 4), 2.0)},
      {"extrude", extrude(half_circle_xz(0.8), {0, 1, 0.2})},
      {"loft", loft(sections)},
      {"split sphere", split_spans(sphere(1.0), {2, 2})},
  };
}

// max_i |f_i| over the internal force at the initial coordinates, relative to the size of the
// terms that cancel in it (max_i sum_j |K_ij q_j| of the stiffness at q).
double relative_internal_force(const DNurbsSurface& model) {
  const Eigen::VectorXd q = model.initial_coordinates();
  Eigen::VectorXd force = Eigen::VectorXd::Zero(model.coordinate_count());
  model.add_internal_force(q, force);
  ModelMatrices matrices;
  model.assemble_matrices(q, matrices);
  const double scale = (matrices.stiffness.cwiseAbs() * q.cwiseAbs()).maxCoeff();
  return force.lpNorm<Eigen::Infinity>() / scale;
}

TEST(DNurbsRestShape, EveryGeneratedSurfaceIsAtRestWithItsInitialShapeAsRest) {
  for (const auto& [name, surface] : generated_surfaces()) {
    for (const WeightMode mode : {WeightMode::kFixed, WeightMode::kFree}) {
      const DNurbsSurface at_rest(surface, test::plate_under_tension(2.0),
                                  rest_settings(mode, true));
      EXPECT_TRUE(at_rest.has_rest_shape());
      // x^alpha(q) - x^alpha(q_r) at the same q by the same arithmetic: zero up to round-off.
      EXPECT_LT(relative_internal_force(at_rest), 1e-12) << name;
      EXPECT_LT(at_rest.potential_energy(at_rest.initial_coordinates()), 1e-24) << name;

      // Measured from zero, tension pulls on everything but a flat sheet off its border.
      const DNurbsSurface from_zero(surface, test::plate_under_tension(2.0),
                                    rest_settings(mode, false));
      EXPECT_FALSE(from_zero.has_rest_shape());
      EXPECT_GT(relative_internal_force(from_zero), 1e-3) << name;
    }
  }
}

TEST(DNurbsRestShape, CurvesAreAtRestWithTheirInitialShapeAsRest) {
  DNurbsCurveMaterial material;
  material.tension = 3.0;
  material.rigidity = 0.4;
  for (const WeightMode mode : {WeightMode::kFixed, WeightMode::kFree}) {
    for (const NurbsCurve& curve : {full_circle(0.7), half_circle_xz(1.2)}) {
      const DNurbsCurve at_rest(curve, material, rest_settings(mode, true));
      const DNurbsCurve from_zero(curve, material, rest_settings(mode, false));
      const Eigen::VectorXd q = at_rest.initial_coordinates();
      Eigen::VectorXd rest_force = Eigen::VectorXd::Zero(q.size());
      Eigen::VectorXd zero_force = Eigen::VectorXd::Zero(q.size());
      at_rest.add_internal_force(q, rest_force);
      from_zero.add_internal_force(q, zero_force);
      EXPECT_LT(rest_force.lpNorm<Eigen::Infinity>(), 1e-13 * zero_force.lpNorm<Eigen::Infinity>());
      EXPECT_GT(zero_force.lpNorm<Eigen::Infinity>(), 0.1);
    }
  }
}

TEST(DNurbsRestShape, FreeWeightSphereStepsInPlaceFromRest) {
  const NurbsSurface surface = sphere(1.0);
  const DNurbsSurface model(surface, test::plate_under_tension(2.0),
                            rest_settings(WeightMode::kFree, true));
  System system(model);
  Integrator integrator(IntegratorSettings{});
  for (int step = 0; step < 10; ++step) {
    integrator.step(system, 0.1);
  }
  EXPECT_LT((system.coordinates() - model.initial_coordinates()).lpNorm<Eigen::Infinity>(), 1e-13);
}

TEST(DNurbsRestShape, FixedWeightShapesStayExactlyAtRestThroughTheKroneckerStep) {
  // The integrators form f_int = -K (q - q_r) from the scalar matrices (Model::
  // linear_rest_coordinates): at q = q_r the force is exactly zero, however the product rounds
  // (forming K q - K q_r instead left about 1e-16 of the terms: a shape at rest crept, and a run
  // with no forces stopped as diverged on an energy of 1e-31 over its budget of 0).
  for (const auto& [name, surface] : generated_surfaces()) {
    const DNurbsSurface model(surface, test::plate_under_tension(2.0),
                              rest_settings(WeightMode::kFixed, true));
    ASSERT_NE(model.linear_rest_coordinates(), nullptr);
    System system(model);
    Integrator integrator(IntegratorSettings{});
    for (int step = 0; step < 20; ++step) {
      integrator.step(system, 0.05);
    }
    EXPECT_EQ((system.coordinates() - model.initial_coordinates()).lpNorm<Eigen::Infinity>(), 0.0)
        << name;
    EXPECT_EQ(system.velocities().lpNorm<Eigen::Infinity>(), 0.0) << name;
  }
}

// The sphere pushed off its rest shape: q_r + a smooth displacement of every control point.
Eigen::VectorXd displaced(const DNurbsSurface& model, double amplitude) {
  Eigen::VectorXd q = model.initial_coordinates();
  const int stride = model.coordinate_count() / model.initial_surface().control_point_count();
  for (int i = 0; i < model.initial_surface().control_point_count(); ++i) {
    for (int r = 0; r < 3; ++r) {
      q[i * stride + r] += amplitude * std::sin(0.7 * i + 1.3 * r);
    }
    if (stride == 4) {
      q[i * stride + 3] *= 1.0 + 0.2 * amplitude * std::cos(0.4 * i);
    }
  }
  return q;
}

TEST(DNurbsRestShape, InternalForceIsMinusTheEnergyGradient) {
  for (const WeightMode mode : {WeightMode::kFixed, WeightMode::kFree}) {
    const DNurbsSurface model(sphere(1.0), test::plate_under_tension(2.0),
                              rest_settings(mode, true));
    const Eigen::VectorXd q = displaced(model, 0.05);
    Eigen::VectorXd force = Eigen::VectorXd::Zero(model.coordinate_count());
    model.add_internal_force(q, force);
    // Central differences: truncation (h^2 / 6) E''' ~ 1e-12 and round-off eps E / h ~ 1e-10
    // relative to |f|, so 1e-7 is far above both and far below any wrong term.
    const double h = 1e-5;
    double largest_error = 0.0;
    for (int k = 0; k < model.coordinate_count(); ++k) {
      Eigen::VectorXd plus = q;
      Eigen::VectorXd minus = q;
      plus[k] += h;
      minus[k] -= h;
      const double gradient =
          (model.potential_energy(plus) - model.potential_energy(minus)) / (2 * h);
      largest_error = std::max(largest_error, std::abs(force[k] + gradient));
    }
    EXPECT_GT(force.lpNorm<Eigen::Infinity>(), 1e-2);
    EXPECT_LT(largest_error, 1e-7 * force.lpNorm<Eigen::Infinity>())
        << (mode == WeightMode::kFree ? "free" : "fixed");
  }
}

TEST(DNurbsRestShape, FixedWeightEnergyIsTheQuadraticFormOfTheChange) {
  // Fixed weights: J constant, E(q) = 1/2 (q - q_r)^T K (q - q_r) and f = -K (q - q_r) exactly.
  const DNurbsSurface model(torus(1.0, 0.4), test::plate_under_tension(2.0),
                            rest_settings(WeightMode::kFixed, true));
  const Eigen::VectorXd q = displaced(model, 0.1);
  const Eigen::VectorXd change = q - model.initial_coordinates();
  const SparseMatrix& stiffness = model.constant_matrices()->stiffness;
  const double expected = 0.5 * change.dot(stiffness * change);
  EXPECT_NEAR(model.potential_energy(q), expected, 1e-12 * expected);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(model.coordinate_count());
  model.add_internal_force(q, force);
  const Eigen::VectorXd expected_force = -(stiffness * change);
  EXPECT_LT((force - expected_force).lpNorm<Eigen::Infinity>(),
            1e-13 * (stiffness.cwiseAbs() * q.cwiseAbs()).maxCoeff());
}

TEST(DNurbsRestShape, SetRestShapeMovesTheRestAndTheWeightAnchor) {
  DNurbsSurface model(sphere(1.0), test::plate_under_tension(2.0),
                      rest_settings(WeightMode::kFree, false));
  const Eigen::VectorXd rest = displaced(model, 0.08);
  model.set_rest_shape(rest);
  EXPECT_TRUE(model.has_rest_shape());
  Eigen::VectorXd force = Eigen::VectorXd::Zero(model.coordinate_count());
  model.add_internal_force(rest, force);
  // The weight anchor k_w (w - w_0) follows the rest shape's weights: no force anywhere.
  EXPECT_EQ(force.lpNorm<Eigen::Infinity>(), 0.0);
  EXPECT_EQ(model.potential_energy(rest), 0.0);
  force.setZero();
  model.add_internal_force(model.initial_coordinates(), force);
  EXPECT_GT(force.lpNorm<Eigen::Infinity>(), 1e-2);
}

TEST(DNurbsRestShape, BadRestShapesAreRefusedNamingTheEntry) {
  DNurbsSurface model(sphere(1.0), test::plate_under_tension(2.0),
                      rest_settings(WeightMode::kFree, false));
  const Eigen::VectorXd short_vector = Eigen::VectorXd::Zero(5);
  EXPECT_THAT(testing::error_message([&] { model.set_rest_shape(short_vector); }),
              ::testing::HasSubstr("5 entries"));
  Eigen::VectorXd q = model.initial_coordinates();
  q[7] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(testing::error_message([&] { model.set_rest_shape(q); }),
              ::testing::HasSubstr("rest shape: coordinate 7 is nan"));
  q = model.initial_coordinates();
  q[4 * 3 + 3] = 1e-4;
  EXPECT_THAT(testing::error_message([&] { model.set_rest_shape(q); }),
              ::testing::HasSubstr("rest shape: weight 3 is 1e-04, below the minimum weight"));
  EXPECT_FALSE(model.has_rest_shape());
}

// The control points of the bottom profile row (u = 0: the south pole of the sphere, the base
// circle of a cylinder), fixed to remove the translations the energy of a change leaves free.
void fix_first_row(System& system, const NurbsSurface& surface) {
  for (int j = 0; j < surface.control_point_count_v(); ++j) {
    system.fix_point(0, surface.control_point_index(0, j));
  }
}

TEST(DNurbsRestShape, PushedSphereReturnsToItsRestShape) {
  const NurbsSurface surface = sphere(1.0);
  for (const bool at_rest : {true, false}) {
    const DNurbsSurface model(surface, test::plate_under_tension(2.0),
                              rest_settings(WeightMode::kFixed, at_rest));
    System system(model);
    fix_first_row(system, surface);
    system.add_force(0, point_force(Eigen::Vector2d(0.7, 0.3), Eigen::Vector3d(0.0, 0.0, -5.0)));
    IntegratorSettings settings;
    settings.scheme = IntegratorScheme::kImplicitEuler;
    Integrator integrator(settings);
    for (int step = 0; step < 20; ++step) {
      integrator.step(system, 0.05);
    }
    const double pushed =
        (system.coordinates() - model.initial_coordinates()).lpNorm<Eigen::Infinity>();
    system.clear_forces();
    for (int step = 0; step < 400; ++step) {
      integrator.step(system, 0.5);
    }
    // The largest distance of x(u, v) from the sphere's own point S(u, v) at samples
    double distance = 0.0;
    for (const double u : {0.2, 0.5, 0.8}) {
      for (const double v : {0.1, 0.45, 0.9}) {
        const Eigen::Vector2d parameter(u, v);
        distance = std::max(distance, (system.position(0, parameter) - surface.point(u, v)).norm());
      }
    }
    if (at_rest) {
      EXPECT_GT(pushed, 1e-2);
      // Implicit Euler's fixed point is f_int = 0, the rest shape; what is left is the decay of
      // the slowest mode after 400 steps.
      EXPECT_LT(distance, 1e-8);
    } else {
      // Measured from zero, tension shrinks the sphere onto its fixed south pole.
      EXPECT_GT(distance, 0.1);
    }
  }
}

// The centre height of a clamped sheet pushed down for 2 s and then released until it settles,
// with a plastic rest shape of the given yield distance.
struct DentHeights {
  double loaded = 0.0;   // at the end of the push
  double settled = 0.0;  // after the release
};
DentHeights pushed_and_released(double yield) {
  DNurbsSettings settings;
  settings.plastic_flow = PlasticFlow{yield, 5.0};
  const NurbsSurface sheet = greville_plane({2, 2}, {7, 7}, {3, 3});
  const DNurbsSurface model(sheet, test::plate_under_tension(2.0), settings);
  System system(model);
  system.fix_border(0);
  const Eigen::Vector2d centre(1.0, 1.0);
  system.add_force(0, point_force(centre, Eigen::Vector3d(0.0, 0.0, -4.0)));
  IntegratorSettings integrator_settings;
  integrator_settings.scheme = IntegratorScheme::kImplicitEuler;
  Integrator integrator(integrator_settings);
  for (int step = 0; step < 40; ++step) {
    integrator.step(system, 0.05);
  }
  DentHeights heights;
  heights.loaded = system.position(0, centre).z();
  system.clear_forces();
  for (int step = 0; step < 400; ++step) {
    integrator.step(system, 0.5);
  }
  heights.settled = system.position(0, centre).z();
  return heights;
}

TEST(DNurbsRestShape, APushBeyondTheYieldDistanceLeavesADent) {
  const DentHeights plastic = pushed_and_released(0.01);
  const DentHeights elastic = pushed_and_released(10.0);  // never reached: fully elastic
  std::cout << "centre height: plastic " << plastic.loaded << " loaded, " << plastic.settled
            << " settled; elastic " << elastic.loaded << " loaded, " << elastic.settled
            << " settled\n";
  EXPECT_LT(plastic.loaded, -0.05);
  // The dent stays, smaller than under the load (the elastic part springs back)
  EXPECT_LT(plastic.settled, 0.2 * plastic.loaded);
  EXPECT_GT(plastic.settled, plastic.loaded);
  // Without yielding the sheet returns flat, up to the decay of its slowest mode
  EXPECT_LT(elastic.loaded, -0.05);
  EXPECT_LT(std::abs(elastic.settled), 1e-8);
}

TEST(DNurbsRestShape, StaticEquilibriumKeepsTheRestShape) {
  const NurbsSurface surface = cylinder(0.5, 2.0, 5);
  const DNurbsSurface model(surface, test::plate_under_tension(2.0),
                            rest_settings(WeightMode::kFixed, true));
  System system(model);
  fix_first_row(system, surface);
  solve_static_equilibrium(system);
  // K q = K q_r on the free coordinates: the rest shape, up to the solve's round-off.
  EXPECT_LT((system.coordinates() - model.initial_coordinates()).lpNorm<Eigen::Infinity>(), 1e-10);

  // A step from rest stays at rest (the step solves for the increment).
  System stepped(model);
  fix_first_row(stepped, surface);
  Integrator integrator(IntegratorSettings{});
  for (int step = 0; step < 10; ++step) {
    integrator.step(stepped, 0.1);
  }
  EXPECT_LT((stepped.coordinates() - model.initial_coordinates()).lpNorm<Eigen::Infinity>(), 1e-13);
}

}  // namespace
}  // namespace dnurbs
