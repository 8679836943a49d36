// The rest shape and plastic flow of triangular D-NURBS surfaces (rational_control_net_model.h,
// "Rest shape"): a curved patch is at rest with its initial shape as rest, the force is -dE/dq of
// the energy of the change, fixed weights give the quadratic form of q - q_r, and a push on a
// plastic patch leaves a dent.

#include <cmath>
#include <iostream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/triangular/triangular_dnurbs_surface.h"
#include "tests/common/error_message.h"
#include "triangular_model_helpers.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

// A soft plate under tension: a unit force at the centre of the clamped unit square dents it
// elastically by about 0.05.
DNurbsSurfaceMaterial soft_plate() {
  DNurbsSurfaceMaterial material;
  material.mass_density = 1.0;
  material.damping_density = 3.0;
  material.a10 = 0.7;
  material.a01 = 0.4;
  material.b20 = 0.05;
  material.b11 = 0.02;
  material.b02 = 0.08;
  return material;
}

TriangularDNurbsSettings settings(WeightMode mode, bool at_rest) {
  TriangularDNurbsSettings result;
  result.weight_mode = mode;
  result.initial_shape_at_rest = at_rest;
  return result;
}

// |f_int(q0)| / sum_i sum_j |K_ij q_j|: the internal force at the initial shape relative to the
// size of its terms.
double relative_initial_force(const TriangularDNurbsSurface& model) {
  const Eigen::VectorXd q = model.initial_coordinates();
  Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
  model.add_internal_force(q, force);
  ModelMatrices matrices;
  model.assemble_matrices(q, matrices);
  const Eigen::VectorXd scale = matrices.stiffness.cwiseAbs() * q.cwiseAbs();
  return force.lpNorm<Eigen::Infinity>() / scale.lpNorm<Eigen::Infinity>();
}

TEST(TriangularRestShape, ACurvedPatchIsAtRestWithItsInitialShapeAsRest) {
  const auto basis = test::triangular_basis(test::unit_square(2), 2);
  for (const WeightMode mode : {WeightMode::kFixed, WeightMode::kFree}) {
    const TriangularNurbsSurface surface = test::curved_triangular_surface(basis, true);
    const TriangularDNurbsSurface at_rest(surface, soft_plate(), settings(mode, true));
    const TriangularDNurbsSurface from_zero(surface, soft_plate(), settings(mode, false));
    const double with_rest = relative_initial_force(at_rest);
    const double without = relative_initial_force(from_zero);
    std::cout << (mode == WeightMode::kFixed ? "fixed" : "free")
              << " weights: relative force at the initial shape " << with_rest
              << " with the rest shape, " << without << " without\n";
    EXPECT_LT(with_rest, 1e-13);  // round-off of sums of unit-size terms
    EXPECT_GT(without, 1e-3);     // measured from zero, tension pulls the patch in
    EXPECT_LT(at_rest.potential_energy(at_rest.initial_coordinates()), 1e-26);
    EXPECT_TRUE(at_rest.has_rest_shape());
    EXPECT_FALSE(from_zero.has_rest_shape());
  }
}

TEST(TriangularRestShape, InternalForceIsMinusTheEnergyGradient) {
  const auto basis = test::triangular_basis(test::unit_square(1), 2);
  for (const WeightMode mode : {WeightMode::kFixed, WeightMode::kFree}) {
    TriangularDNurbsSurface model(test::curved_triangular_surface(basis, true), soft_plate(),
                                  settings(mode, false));
    // The rest shape: the initial coordinates moved by a smooth field, weights kept
    Eigen::VectorXd rest = model.initial_coordinates();
    const int stride = mode == WeightMode::kFixed ? 3 : 4;
    for (Eigen::Index i = 0; i < rest.size(); i += stride) {
      rest[i + 2] += 0.1 * std::cos(3.0 * rest[i]);
    }
    model.set_rest_shape(rest);
    Eigen::VectorXd checked =
        model.initial_coordinates() + 0.05 * test::random_velocity(rest.size(), 3);
    if (mode == WeightMode::kFree) {
      for (Eigen::Index i = 3; i < checked.size(); i += 4) {
        checked[i] = std::max(checked[i], 0.5);  // weights stay well above the minimum
      }
    }
    Eigen::VectorXd force = Eigen::VectorXd::Zero(checked.size());
    model.add_internal_force(checked, force);
    const double h = 1e-6;
    double worst = 0.0;
    for (Eigen::Index k = 0; k < checked.size(); ++k) {
      Eigen::VectorXd qp = checked;
      Eigen::VectorXd qm = checked;
      qp[k] += h;
      qm[k] -= h;
      const double gradient = (model.potential_energy(qp) - model.potential_energy(qm)) / (2 * h);
      worst = std::max(worst, std::abs(force[k] + gradient) / (1.0 + std::abs(gradient)));
    }
    std::cout << (mode == WeightMode::kFixed ? "fixed" : "free")
              << " weights: largest |f + dE/dq| / (1 + |dE/dq|) " << worst << "\n";
    // Central differences: truncation h^2 |E'''| and rounding 1e-16 E / h
    EXPECT_LT(worst, 1e-7);
  }
}

TEST(TriangularRestShape, FixedWeightEnergyIsTheQuadraticFormOfTheChange) {
  const auto basis = test::triangular_basis(test::unit_square(2), 2);
  TriangularDNurbsSurface model(test::curved_triangular_surface(basis, true), soft_plate(),
                                settings(WeightMode::kFixed, false));
  const Eigen::VectorXd rest =
      model.initial_coordinates() + 0.1 * test::random_velocity(model.coordinate_count(), 7);
  model.set_rest_shape(rest);
  const Eigen::VectorXd q =
      model.initial_coordinates() + 0.2 * test::random_velocity(model.coordinate_count(), 8);
  const Eigen::VectorXd d = q - rest;
  const SparseMatrix& stiffness = model.constant_matrices()->stiffness;
  const double expected = 0.5 * d.dot(stiffness * d);
  EXPECT_NEAR(model.potential_energy(q), expected, 1e-12 * expected);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
  model.add_internal_force(q, force);
  const Eigen::VectorXd expected_force = -(stiffness * d);
  EXPECT_LT((force - expected_force).norm(), 1e-13 * expected_force.norm());
  // The Kronecker step path forms K (q - q_r) with the rest coordinates
  ASSERT_NE(model.linear_rest_coordinates(), nullptr);
  EXPECT_EQ(*model.linear_rest_coordinates(), rest);
}

// The centre of a clamped flat patch pushed down for 4 s, then released for 200 s.
struct Dent {
  double loaded = 0.0;
  double settled = 0.0;
};

Dent push_and_release(double yield) {
  const auto basis = test::triangular_basis(test::unit_square(3), 2);
  TriangularDNurbsSettings plastic;
  plastic.plastic_flow = PlasticFlow{yield, 3.0};
  const TriangularDNurbsSurface model(flat_triangular_surface(basis), soft_plate(), plastic);
  System system(model);
  system.fix_border(0);
  const Eigen::Vector2d centre(0.5, 0.5);
  system.add_force(0, point_force(centre, Eigen::Vector3d(0.0, 0.0, -1.0)));
  Integrator integrator(IntegratorSettings{IntegratorScheme::kImplicitEuler});
  for (int step = 0; step < 40; ++step) {
    integrator.step(system, 0.1);
  }
  Dent dent;
  dent.loaded = system.position(0, centre).z();
  system.clear_forces();
  for (int step = 0; step < 400; ++step) {
    integrator.step(system, 0.5);
  }
  dent.settled = system.position(0, centre).z();
  return dent;
}

TEST(TriangularRestShape, APushBeyondTheYieldDistanceLeavesADent) {
  const Dent plastic = push_and_release(0.01);
  const Dent elastic = push_and_release(10.0);  // never reached: fully elastic
  std::cout << "centre height: plastic " << plastic.loaded << " loaded, " << plastic.settled
            << " settled; elastic " << elastic.loaded << " loaded, " << elastic.settled
            << " settled\n";
  EXPECT_LT(plastic.loaded, -0.05);
  // The dent stays, smaller than under the load (the elastic part springs back)
  EXPECT_LT(plastic.settled, 0.2 * plastic.loaded);
  EXPECT_GT(plastic.settled, plastic.loaded);
  // Without yielding the patch returns flat, up to the decay of its slowest mode
  EXPECT_LT(elastic.loaded, -0.02);
  EXPECT_LT(std::abs(elastic.settled), 1e-8);
}

TEST(TriangularRestShape, BadRestShapesAreRefusedNamingTheEntry) {
  const auto basis = test::triangular_basis(test::unit_square(1), 2);
  TriangularDNurbsSurface model(test::curved_triangular_surface(basis, false), soft_plate(),
                                settings(WeightMode::kFree, false));
  Eigen::VectorXd rest = model.initial_coordinates();
  rest[5] = std::nan("");
  EXPECT_THAT(testing::error_message([&] { model.set_rest_shape(rest); }),
              HasSubstr("rest shape: coordinate 5 is nan"));
  rest = model.initial_coordinates();
  rest[7] = 0.0;  // weight 1
  EXPECT_THAT(testing::error_message([&] { model.set_rest_shape(rest); }),
              HasSubstr("rest shape: weight 1 is 0"));
  EXPECT_THAT(testing::error_message([&] {
                model.set_plastic_flow(PlasticFlow{0.1, -2.0});
              }),
              HasSubstr("plastic rate -2"));
  EXPECT_FALSE(model.has_rest_shape());  // nothing changed by the refused calls
}

}  // namespace
}  // namespace dnurbs
