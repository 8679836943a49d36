// The deformation field model (Goldenstein et al. 2005, eqs. 1-4 as a Lagrangian model): its
// point Jacobian against central differences, its mass matrix against closed-form integrals, a
// single parameter under a point force against the 1-DOF oscillator m q'' + d q' + k q = L^T f,
// and its adaptive tessellation against the coarsest uniform grid of the same error bound.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/model_tessellation.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/fields/deformation_field_model.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/integrators/static_equilibrium.h"
#include "dnurbs/surface/adaptive_tessellation.h"

namespace dnurbs {
namespace {

// The unit square z = 0 as a constant field (a geometry image of a plane, eq. 2)
Eigen::Vector3d plane(double u, double v) {
  return {u, v, 0.0};
}

Eigen::Vector3d bump(double u, double v) {
  const double r2 = (u - 0.4) * (u - 0.4) + (v - 0.6) * (v - 0.6);
  return Eigen::Vector3d(0.2, -0.1, 1.0) * std::exp(-r2 / 0.05);
}

Eigen::Vector3d swirl(double u, double v) {
  return {std::sin(3.0 * v), u * v, std::cos(2.0 * u)};
}

DeformationFieldModel two_mode_model(const DeformationFieldSettings& settings = {}) {
  DeformationField field;
  field.constant(plane).add_vector(bump, 0).add_vector(swirl, 1);
  return {field, std::nullopt, ParameterDomain{}, Eigen::Vector2d(0.3, -0.2), settings};
}

TEST(DeformationFieldModel, PointJacobianMatchesCentralDifferences) {
  const DeformationFieldModel model = two_mode_model();
  const Eigen::Vector2d q(0.7, -0.4);
  const double h = 1e-6;
  for (const Eigen::Vector2d& u :
       {Eigen::Vector2d(0.4, 0.6), Eigen::Vector2d(0.1, 0.9), Eigen::Vector2d(0.77, 0.23)}) {
    const Eigen::MatrixXd jacobian = Eigen::MatrixXd(model.position_jacobian(q, u));
    ASSERT_EQ(jacobian.rows(), 3);
    ASSERT_EQ(jacobian.cols(), 2);
    for (int k = 0; k < 2; ++k) {
      Eigen::Vector2d plus = q;
      Eigen::Vector2d minus = q;
      plus(k) += h;
      minus(k) -= h;
      const Eigen::Vector3d difference =
          (model.position(plus, u) - model.position(minus, u)) / (2 * h);
      // x is affine in q: no truncation error, rounding ~ 1e-16 |x| / h ~ 1e-10
      EXPECT_LT((jacobian.col(k) - difference).norm(), 1e-9) << "parameter " << k;
    }
  }
  // x = plane + q_0 bump + q_1 swirl (eqs. 2 and 4)
  const Eigen::Vector2d u(0.25, 0.5);
  EXPECT_LT(
      (model.position(q, u) - (plane(0.25, 0.5) + 0.7 * bump(0.25, 0.5) - 0.4 * swirl(0.25, 0.5)))
          .norm(),
      1e-15);
}

TEST(DeformationFieldModel, TangentKinematicsMatchTheAnalyticDerivatives) {
  const DeformationFieldModel model = two_mode_model();
  const Eigen::Vector2d q(0.7, -0.4);
  const Eigen::Vector2d qd(2.0, 3.0);
  const double u = 0.45;
  const double v = 0.55;
  // d bump / du and d bump / dv, d swirl / du = (0, v, -2 sin 2u), d swirl / dv = (3 cos 3v, u, 0)
  const Eigen::Vector3d bump_u = bump(u, v) * (-2.0 * (u - 0.4) / 0.05);
  const Eigen::Vector3d bump_v = bump(u, v) * (-2.0 * (v - 0.6) / 0.05);
  const Eigen::Vector3d swirl_u(0.0, v, -2.0 * std::sin(2.0 * u));
  const Eigen::Vector3d swirl_v(3.0 * std::cos(3.0 * v), u, 0.0);
  TangentKinematics tangents;
  model.tangent_kinematics(q, qd, {u, v}, tangents);
  // Central differences of step 1e-5: truncation h^2 |f_uuu| / 6 < 1e-8 for the bump's third
  // derivatives (of order (2 / 0.05)^1.5 ~ 250), rounding 1e-16 / 1e-5
  const double tolerance = 1e-7;
  EXPECT_LT((tangents.su - (Eigen::Vector3d::UnitX() + 0.7 * bump_u - 0.4 * swirl_u)).norm(),
            tolerance);
  EXPECT_LT((tangents.sv - (Eigen::Vector3d::UnitY() + 0.7 * bump_v - 0.4 * swirl_v)).norm(),
            tolerance);
  EXPECT_EQ(tangents.columns, (std::vector<int>{0, 1}));
  EXPECT_LT((tangents.ju.col(0) - bump_u).norm(), tolerance);
  EXPECT_LT((tangents.ju.col(1) - swirl_u).norm(), tolerance);
  EXPECT_LT((tangents.jv.col(0) - bump_v).norm(), tolerance);
  EXPECT_LT((tangents.jv.col(1) - swirl_v).norm(), tolerance);
  // J_u qd with |qd| ~ 3.6: the same error times |qd|
  EXPECT_LT((tangents.su_rate - (2.0 * bump_u + 3.0 * swirl_u)).norm(), 5 * tolerance);
  EXPECT_EQ(tangents.su_bias, Eigen::Vector3d::Zero());
}

TEST(DeformationFieldModel, MassAndDampingAreTheClosedFormIntegrals) {
  // Uniform fields V_0, V_1 over the unit square: M = mu V^T V (area 1), D = gamma V^T V
  const Eigen::Vector3d v0(1.0, 2.0, -0.5);
  const Eigen::Vector3d v1(-0.3, 0.4, 1.5);
  DeformationField uniform;
  uniform.constant(plane)
      .add_vector([v0](double, double) { return Eigen::Vector3d(v0); }, 0)
      .add_vector([v1](double, double) { return Eigen::Vector3d(v1); }, 1);
  DeformationFieldSettings settings;
  settings.mass_density = 2.5;
  settings.damping_density = 0.75;
  settings.stiffness = Eigen::Vector2d(3.0, 4.0);
  const DeformationFieldModel model(uniform, std::nullopt, ParameterDomain{},
                                    Eigen::Vector2d::Zero(), settings);
  Eigen::Matrix<double, 3, 2> v;
  v << v0, v1;
  const Eigen::Matrix2d gram = v.transpose() * v;
  EXPECT_LT((Eigen::MatrixXd(model.constant_matrices()->mass) - 2.5 * gram).norm(), 1e-12);
  EXPECT_LT((Eigen::MatrixXd(model.constant_matrices()->damping) - 0.75 * gram).norm(), 1e-12);
  EXPECT_LT((Eigen::MatrixXd(model.constant_matrices()->stiffness) -
             Eigen::Matrix2d(Eigen::Vector2d(3.0, 4.0).asDiagonal()))
                .norm(),
            1e-15);

  // A bilinear field V_0 = (u, v, 0) on [0, 2] x [0, 1]: integral |V_0|^2 = 8/3 + 2/3 = 10/3,
  // integral V_0 . e_z = 0, integral |e_z|^2 = 2; Gauss with 3 points is exact for these
  // quadratics
  DeformationField bilinear;
  bilinear.add_vector([](double u, double v) { return Eigen::Vector3d(u, v, 0.0); }, 0)
      .add_vector([](double, double) { return Eigen::Vector3d::UnitZ(); }, 1);
  DeformationFieldSettings unit;
  unit.mass_density = 1.5;
  ParameterDomain domain;
  domain.u_max = 2.0;
  const DeformationFieldModel rectangle(bilinear, std::nullopt, domain, Eigen::Vector2d::Zero(),
                                        unit);
  const Eigen::Matrix2d expected = 1.5 * Eigen::Vector2d(10.0 / 3.0, 2.0).asDiagonal();
  EXPECT_LT((Eigen::MatrixXd(rectangle.constant_matrices()->mass) - expected).norm(), 1e-12);
}

// One parameter q moving the unit square along z: x = (u, v, q), L = e_z, m = mu, d = gamma
DeformationFieldModel piston(double mu, double gamma, double k) {
  DeformationField field;
  field.constant(plane).add_vector([](double, double) { return Eigen::Vector3d::UnitZ(); }, 0);
  DeformationFieldSettings settings;
  settings.mass_density = mu;
  settings.damping_density = gamma;
  settings.stiffness = Eigen::VectorXd::Constant(1, k);
  return {field, std::nullopt, ParameterDomain{}, Eigen::VectorXd::Zero(1), settings};
}

TEST(DeformationFieldModel, PointForceStaticEquilibriumIsLTransposeFOverK) {
  System system(piston(2.0, 1.0, 8.0));
  // L^T f = f_z = 3 wherever the force acts; f_x, f_y do no work on q
  system.add_force(0, point_force(Eigen::Vector2d(0.3, 0.8), Eigen::Vector3d(5.0, -1.0, 3.0)));
  solve_static_equilibrium(system);
  EXPECT_NEAR(system.coordinates()(0), 3.0 / 8.0, 1e-14);
}

// q(t) of m q'' + d q' + k q = F from rest: the underdamped step response
double step_response(double m, double d, double k, double force, double t) {
  const double omega0 = std::sqrt(k / m);
  const double zeta = d / (2.0 * std::sqrt(k * m));
  const double omega = omega0 * std::sqrt(1.0 - zeta * zeta);
  const double decay = std::exp(-zeta * omega0 * t);
  return force / k *
         (1.0 - decay * (std::cos(omega * t) +
                         zeta / std::sqrt(1.0 - zeta * zeta) * std::sin(omega * t)));
}

double newmark_error(int steps) {
  const double m = 2.0;
  const double d = 0.6;
  const double k = 8.0;
  const double end = 3.0;
  System system(piston(m, d, k));
  system.add_force(0, point_force(Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d(0.0, 0.0, 3.0)));
  Integrator integrator(IntegratorSettings{IntegratorScheme::kNewmark});
  double error = 0.0;
  for (int n = 1; n <= steps; ++n) {
    integrator.step(system, end / steps);
    error = std::max(
        error, std::abs(system.coordinates()(0) - step_response(m, d, k, 3.0, n * end / steps)));
  }
  return error;
}

TEST(DeformationFieldModel, PointForceFollowsTheOneDofOscillatorAtSecondOrder) {
  const double coarse = newmark_error(100);
  const double fine = newmark_error(200);
  // Newmark's average acceleration is second order: the error falls by 4 when dt halves
  EXPECT_LT(coarse, 1e-3);
  EXPECT_NEAR(coarse / fine, 4.0, 0.2) << coarse << " " << fine;
  std::cout << "max |q - q_exact| over t in [0, 3]: " << coarse << " (dt = 0.03), " << fine
            << " (dt = 0.015)\n";
}

TEST(DeformationFieldModel, AdaptiveTessellationMeetsItsBoundWithFewerVertices) {
  DeformationFieldSettings settings;
  settings.tessellation_max_error = 2e-3;
  const DeformationFieldModel model = two_mode_model(settings);
  const Eigen::Vector2d q(0.8, 0.0);
  ModelTessellationSettings resolution;
  resolution.segments_u = 4;
  resolution.segments_v = 4;
  const TriangleMesh adaptive = tessellate_model(model, q, resolution, "bump");
  const ParametricSurface surface = model.parametric_surface(q);
  RestrictedMesh restricted(surface, 4, 4);
  restricted.refine(surface_error_criterion(surface, 2e-3), settings.tessellation_max_level);
  EXPECT_EQ(adaptive.vertex_count(), restricted.to_triangle_mesh("bump").vertex_count());
  EXPECT_LE(mesh_surface_error(restricted, kDefaultErrorSampleOrder).max, 2e-3);
  const UniformTessellationChoice uniform = coarsest_uniform_tessellation(surface, 4, 4, 2e-3);
  EXPECT_LT(adaptive.vertex_count(), uniform.vertices);
  std::cout << "adaptive " << adaptive.vertex_count() << " vertices, coarsest uniform "
            << uniform.cells_u << " x " << uniform.cells_v << ": " << uniform.vertices << "\n";
}

TEST(DeformationFieldModel, RefusesBadValuesNamingThem) {
  DeformationField field;
  field.constant(plane);
  EXPECT_THROW(DeformationFieldModel(field, std::nullopt, ParameterDomain{}, Eigen::VectorXd(), {}),
               Error);
  DeformationFieldSettings settings;
  settings.stiffness = Eigen::Vector2d(1.0, -2.0);
  try {
    two_mode_model(settings);
    FAIL() << "a negative stiffness was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("stiffness -2 of parameter 1"), std::string::npos)
        << error.what();
  }
  settings.stiffness = Eigen::Vector2d(1.0, 2.0);
  settings.mass_density = 0.0;
  EXPECT_THROW(two_mode_model(settings), Error);
}

}  // namespace
}  // namespace dnurbs
