// Tests of dynamics/triangular/triangular_dnurbs_surface.h (Qin & Terzopoulos 1997, triangular
// D-NURBS): mass equals density times area, K annihilates translations, energies and forces
// against their definitions, the free-weight Jacobian, Jdot qd and inertial force against
// finite differences, sculpting to static equilibrium, and bad input.

#include "dnurbs/dynamics/triangular/triangular_dnurbs_surface.h"

#include <iostream>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/integrators/static_equilibrium.h"
#include "triangular_model_helpers.h"

namespace dnurbs {
namespace {

DNurbsSurfaceMaterial plate_under_tension() {
  DNurbsSurfaceMaterial material;
  material.mass_density = 1.3;
  material.damping_density = 0.4;
  material.a10 = 0.7;
  material.a01 = 0.2;
  material.b20 = 0.05;
  material.b11 = 0.02;
  material.b02 = 0.08;
  return material;
}

TriangularDNurbsSettings free_weights() {
  TriangularDNurbsSettings settings;
  settings.weight_mode = WeightMode::kFree;
  return settings;
}

TEST(TriangularDNurbsMass, SumIsDensityTimesDomainAreaOnEveryDomain) {
  DNurbsSurfaceMaterial material;
  material.mass_density = 0.7;
  const std::vector<Triangulation> domains = {test::unit_square(3), l_shape_triangulation(1),
                                              square_with_hole_triangulation(1)};
  for (const Triangulation& domain : domains) {
    for (int n = 1; n <= 3; ++n) {
      const auto basis = test::triangular_basis(domain, n);
      const TriangularDNurbsSurface model(test::curved_triangular_surface(basis, false), material);
      const Eigen::MatrixXd mass(model.scalar_matrices()->mass);
      // Partition of unity makes the sum exactly 0.7 sum_g w_g = 0.7 area; round-off of the
      // weights' sum over ~1e5 points.
      EXPECT_NEAR(mass.sum(), 0.7 * domain.domain_area(), 1e-12 * domain.domain_area())
          << "area " << domain.domain_area() << " degree " << n;
      EXPECT_NEAR(model.parametric_measure(), domain.domain_area(), 1e-14);
      EXPECT_LT((mass - mass.transpose()).norm(), 1e-15 * mass.norm());
      // Positive definite: the B-splines are linearly independent on these domains.
      EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(mass).eigenvalues().minCoeff(), 0.0);
    }
  }
}

TEST(TriangularDNurbsStiffness, AnnihilatesTranslationsAndIsSymmetricSemiDefinite) {
  const auto basis = test::triangular_basis(l_shape_triangulation(1), 2);
  const TriangularDNurbsSurface model(test::curved_triangular_surface(basis, false),
                                      plate_under_tension());
  const Eigen::MatrixXd stiffness(model.constant_matrices()->stiffness);
  Eigen::VectorXd translation(stiffness.rows());
  for (Eigen::Index i = 0; i < stiffness.rows() / 3; ++i) {
    translation.segment<3>(3 * i) << -0.4, 1.1, 0.25;
  }
  // Derivatives of the partition of unity vanish; round-off relative to the entries.
  EXPECT_LT((stiffness * translation).lpNorm<Eigen::Infinity>(),
            1e-12 * stiffness.lpNorm<Eigen::Infinity>());
  EXPECT_LT((stiffness - stiffness.transpose()).norm(), 1e-15 * stiffness.norm());
  const Eigen::VectorXd eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(stiffness).eigenvalues();
  EXPECT_GT(eigenvalues.minCoeff(), -1e-12 * eigenvalues.maxCoeff());
  // Exactly three zero modes (the translations): the tension terms see every other motion.
  EXPECT_LT(eigenvalues[2], 1e-12 * eigenvalues.maxCoeff());
  EXPECT_GT(eigenvalues[3], 1e-8 * eigenvalues.maxCoeff());
}

TEST(TriangularDNurbsStiffness, EnergyAndInternalForceAreTheQuadraticForm) {
  const auto basis = test::triangular_basis(test::unit_square(2), 3);
  const TriangularDNurbsSurface model(test::curved_triangular_surface(basis, true),
                                      plate_under_tension());
  const Eigen::VectorXd q = model.initial_coordinates();
  const SparseMatrix& stiffness = model.constant_matrices()->stiffness;
  // The energy by quadrature (free weights: E = (1/2) q^T K(q) q too, as J_alpha q = x^alpha by
  // Euler's theorem for the weights) equals the fixed-weight (1/2) q^T K q of the same shape
  // (rounding of two quadrature sums: 1e-12 relative).
  const TriangularDNurbsSurface free(test::curved_triangular_surface(basis, true),
                                     plate_under_tension(), free_weights());
  const Eigen::VectorXd qf = free.initial_coordinates();
  ModelMatrices free_matrices;
  free.assemble_matrices(qf, free_matrices);
  const double energy = 0.5 * q.dot(stiffness * q);
  EXPECT_NEAR(model.potential_energy(q), energy, 1e-12 * energy);
  EXPECT_NEAR(free.potential_energy(qf), energy, 1e-12 * energy);
  EXPECT_NEAR(0.5 * qf.dot(free_matrices.stiffness * qf), energy, 1e-12 * energy);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
  model.add_internal_force(q, force);
  EXPECT_LT((force + stiffness * q).norm(), 1e-14 * (stiffness * q).norm());
  // Uniform distributed force: by partition of unity the generalized forces add up to the
  // force per area times the area (non-rational surface).
  const TriangularDNurbsSurface flat(flat_triangular_surface(basis), plate_under_tension());
  Eigen::VectorXd f = Eigen::VectorXd::Zero(q.size());
  flat.add_distributed_force(
      flat.initial_coordinates(),
      [](const MaterialSample&) { return Eigen::Vector3d(0.5, -1.0, 2.0); }, f);
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < flat.control_point_count(); ++i) {
    total += f.segment<3>(3 * i);
  }
  EXPECT_LT((total - Eigen::Vector3d(0.5, -1.0, 2.0)).norm(), 1e-13);
}

TEST(TriangularDNurbsJacobian, PositionJacobianMatchesDifferencesWithFreeWeights) {
  const auto basis = test::triangular_basis(l_shape_triangulation(1), 2);
  const TriangularDNurbsSurface model(test::curved_triangular_surface(basis, true), {},
                                      free_weights());
  const Eigen::VectorXd q = model.initial_coordinates();
  const double h = 1e-7;
  for (const Eigen::Vector2d& u : {Eigen::Vector2d(0.3, 0.2), Eigen::Vector2d(1.62, 0.71),
                                   Eigen::Vector2d(0.45, 1.5), Eigen::Vector2d(1.0, 0.5)}) {
    const Eigen::MatrixXd jacobian(model.position_jacobian(q, u));
    ASSERT_EQ(jacobian.cols(), q.size());
    Eigen::MatrixXd difference(3, q.size());
    for (Eigen::Index k = 0; k < q.size(); ++k) {
      Eigen::VectorXd plus = q;
      Eigen::VectorXd minus = q;
      plus[k] += h;
      minus[k] -= h;
      difference.col(k) = (model.position(plus, u) - model.position(minus, u)) / (2 * h);
    }
    // Truncation h^2 |d^2 x / dw^2| and rounding 1e-16 / h.
    EXPECT_LT((jacobian - difference).cwiseAbs().maxCoeff(), 1e-8) << u.transpose();
  }
}

TEST(TriangularDNurbsJacobian, JdotTimesVelocityIsTheSecondDerivativeAlongTheVelocity) {
  const auto basis = test::triangular_basis(test::unit_square(2), 2);
  const TriangularDNurbsSurface model(test::curved_triangular_surface(basis, true), {},
                                      free_weights());
  const Eigen::VectorXd q = model.initial_coordinates();
  const Eigen::VectorXd qd = test::random_velocity(q.size(), 3);
  const double h = 1e-4;
  for (const Eigen::Vector2d& u : {Eigen::Vector2d(0.3, 0.2), Eigen::Vector2d(0.7, 0.55)}) {
    // Along q(t) = q + t qd (qdd = 0) the acceleration of the point is Jdot qd.
    const Eigen::Vector3d expected = (model.position(q + h * qd, u) - 2.0 * model.position(q, u) +
                                      model.position(q - h * qd, u)) /
                                     (h * h);
    const Eigen::Vector3d rate = model.jacobian_rate_times_velocity(q, qd, u);
    // Truncation h^2 |x''''| ~ 1e-8 and rounding 1e-16 / h^2 = 1e-8.
    EXPECT_LT((rate - expected).norm(), 1e-6 * (1.0 + expected.norm())) << u.transpose();
  }
  const TriangularDNurbsSurface fixed(test::curved_triangular_surface(basis, true));
  EXPECT_EQ(fixed.jacobian_rate_times_velocity(fixed.initial_coordinates(),
                                               test::random_velocity(fixed.coordinate_count(), 1),
                                               Eigen::Vector2d(0.3, 0.2)),
            Eigen::Vector3d::Zero());
}

// Lagrange: d/dt (M qd) - dT/dq = M qdd - g, so g = dT/dq - Mdot qd with T = qd^T M(q) qd / 2.
TEST(TriangularDNurbsFreeWeights, InertialForceMatchesLagrangianDifferences) {
  const auto basis = test::triangular_basis(test::unit_square(1), 2);
  const TriangularDNurbsSurface model(test::curved_triangular_surface(basis, true), {},
                                      free_weights());
  const Eigen::VectorXd q = model.initial_coordinates();
  const Eigen::VectorXd qd = test::random_velocity(q.size(), 11);
  const double h = 1e-5;
  auto kinetic = [&](const Eigen::VectorXd& at) {
    ModelMatrices m;
    model.assemble_matrices(at, m);
    return 0.5 * qd.dot(m.mass * qd);
  };
  ModelMatrices plus;
  ModelMatrices minus;
  model.assemble_matrices(q + h * qd, plus);
  model.assemble_matrices(q - h * qd, minus);
  Eigen::VectorXd expected = -((plus.mass - minus.mass) * qd) / (2.0 * h);
  for (Eigen::Index k = 0; k < q.size(); ++k) {
    Eigen::VectorXd qp = q;
    Eigen::VectorXd qm = q;
    qp[k] += h;
    qm[k] -= h;
    expected[k] += (kinetic(qp) - kinetic(qm)) / (2.0 * h);
  }
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  model.add_inertial_force(q, qd, g);
  // O(h^2) truncation + O(1e-16 |T| / h) round-off; relative to |g|.
  EXPECT_LT((g - expected).norm(), 1e-7 * std::max(1.0, expected.norm())) << "|g| " << g.norm();
}

TEST(TriangularDNurbsFreeWeights, MatricesEnergyAndForceMatchTheirDefinitions) {
  const auto basis = test::triangular_basis(test::unit_square(1), 2);
  const TriangularDNurbsSurface model(test::curved_triangular_surface(basis, true),
                                      plate_under_tension(), free_weights());
  const Eigen::VectorXd q = model.initial_coordinates();
  ModelMatrices matrices;
  model.assemble_matrices(q, matrices);
  // M = sum_p w_p mu L_p^T L_p over the model's own quadrature points, L from position_jacobian.
  const TriangularQuadrature& quadrature = model.quadrature();
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(q.size(), q.size());
  for (int p = 0; p < quadrature.point_count(); ++p) {
    const Eigen::MatrixXd jacobian(model.position_jacobian(q, quadrature.parameter(p)));
    expected += 1.3 * quadrature.weight(p) * jacobian.transpose() * jacobian;
  }
  const Eigen::MatrixXd mass(matrices.mass);
  EXPECT_LT((mass - expected).norm(), 1e-12 * expected.norm());  // same sums, round-off
  EXPECT_LT((mass - mass.transpose()).norm(), 1e-15 * mass.norm());
  // E = q^T K(q) q / 2 (x^alpha = J_alpha q: x is homogeneous of degree 0 in the weights), and
  // f_int = -dE/dq by central differences.
  const double energy = model.potential_energy(q);
  EXPECT_NEAR(energy, 0.5 * q.dot(matrices.stiffness * q), 1e-12 * energy);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
  model.add_internal_force(q, force);
  const double h = 1e-6;
  for (Eigen::Index k = 0; k < q.size(); k += 5) {
    Eigen::VectorXd qp = q;
    Eigen::VectorXd qm = q;
    qp[k] += h;
    qm[k] -= h;
    const double gradient = (model.potential_energy(qp) - model.potential_energy(qm)) / (2 * h);
    // Truncation h^2 and rounding 1e-16 E / h.
    EXPECT_NEAR(force[k], -gradient, 1e-7 * (1.0 + std::abs(gradient))) << "coordinate " << k;
  }
}

TEST(TriangularDNurbsFreeWeights, GaugeProjectionAndOffsets) {
  const auto basis = test::triangular_basis(test::unit_square(1), 1);
  TriangularDNurbsSurface model(test::curved_triangular_surface(basis, true), {}, free_weights());
  EXPECT_EQ(model.coordinate_count(), 4 * model.control_point_count());
  EXPECT_EQ(model.fixed_coordinates(), std::vector<int>{3});  // weight 0: the gauge
  Eigen::VectorXd q = model.initial_coordinates();
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(q.size());
  q[model.weight_offset(2)] = -0.5;
  qd[model.weight_offset(2)] = -2.0;
  qd[model.weight_offset(3)] = -1.0;
  model.project_state(q, qd);
  EXPECT_EQ(q[model.weight_offset(2)], model.minimum_weight());
  EXPECT_EQ(qd[model.weight_offset(2)], 0.0);
  EXPECT_EQ(qd[model.weight_offset(3)], -1.0);  // weight 3 is above the minimum: untouched
  model.fix_control_point(4);
  EXPECT_EQ(model.fixed_coordinates().size(), 4U);
  EXPECT_EQ(model.weights(model.initial_coordinates()), model.initial_surface().weights());
  EXPECT_EQ(model.control_points(model.initial_coordinates()),
            model.initial_surface().control_points());
  EXPECT_THROW(model.control_point_offset(model.control_point_count()), Error);
  const TriangularDNurbsSurface fixed(test::curved_triangular_surface(basis, true));
  EXPECT_THROW(fixed.weight_offset(0), Error);
  EXPECT_EQ(fixed.kronecker_block_size(), 3);
  EXPECT_EQ(model.kronecker_block_size(), 0);
  EXPECT_EQ(model.constant_matrices(), nullptr);
}

TEST(TriangularDNurbsSculpting, PointForceOnAnLShapeSettlesToTheStaticSolution) {
  const auto basis = test::triangular_basis(l_shape_triangulation(1), 2);
  TriangularDNurbsSurface model(flat_triangular_surface(basis), plate_under_tension());
  // Hold every control point of the triangles of the L's lower arm: the upper arm bends.
  for (int f = 0; f < model.control_point_count(); ++f) {
    if (basis->triangulation().centroid(basis->triangle_of(f)).y() < 1.0) {
      model.fix_control_point(f);
    }
  }
  System system(model);
  const Eigen::Vector2d pushed(0.5, 1.6);  // in the L's upper arm
  system.add_force(0, point_force(pushed, Eigen::Vector3d(0.0, 0.0, 1.0)));
  System reference = system;
  solve_static_equilibrium(reference);
  IntegratorSettings settings;
  settings.scheme = IntegratorScheme::kImplicitEuler;
  Integrator integrator(settings);
  int steps = 0;
  double change = 1.0;
  while (change > 1e-13 && steps < 5000) {
    const Eigen::VectorXd before = system.coordinates();
    integrator.step(system, 0.5);
    change = (system.coordinates() - before).lpNorm<Eigen::Infinity>();
    ++steps;
  }
  const double error = (system.coordinates() - reference.coordinates()).lpNorm<Eigen::Infinity>();
  std::cout << "triangular sculpting: " << steps
            << " implicit-euler steps, distance to K q = f: " << error << "\n";
  // Implicit Euler's fixed point is K q = f; what remains is the slowest mode's decay below
  // the 1e-13 step change.
  EXPECT_LT(error, 1e-8);
  EXPECT_GT(system.position(0, pushed).z(), 0.0);
  EXPECT_EQ(integrator.factorization_count(), 1);  // constant matrices, factored once
}

TEST(TriangularDNurbsSurface, BadInputThrowsErrorNamingTheValue) {
  const auto basis = test::triangular_basis(test::unit_square(1), 1);
  const TriangularNurbsSurface surface = test::curved_triangular_surface(basis, true);
  TriangularDNurbsSettings settings;
  settings.quadrature_degree = 15;
  EXPECT_THROW(TriangularDNurbsSurface(surface, {}, settings), Error);
  settings = {};
  settings.quadrature_subdivisions = 65;
  EXPECT_THROW(TriangularDNurbsSurface(surface, {}, settings), Error);
  settings = free_weights();
  settings.minimum_weight = 0.9;  // above some weights
  EXPECT_THROW(TriangularDNurbsSurface(surface, {}, settings), Error);
  settings.minimum_weight = 0.0;
  EXPECT_THROW(TriangularDNurbsSurface(surface, {}, settings), Error);
  DNurbsSurfaceMaterial material;
  material.b20 = -1.0;
  EXPECT_THROW(TriangularDNurbsSurface(surface, material), Error);
  material = {};
  material.mass_density = std::nan("");
  EXPECT_THROW(TriangularDNurbsSurface(surface, material), Error);
  const TriangularDNurbsSurface model(surface);
  EXPECT_THROW(model.position(Eigen::VectorXd::Zero(5), Eigen::Vector2d(0.5, 0.5)), Error);
  const TriangularDNurbsSurface free(surface, {}, free_weights());
  Eigen::VectorXd g = Eigen::VectorXd::Zero(free.velocity_count());
  EXPECT_THROW(free.add_inertial_force(free.initial_coordinates(), Eigen::VectorXd::Zero(3), g),
               Error);
  EXPECT_THROW(model.position(model.initial_coordinates(), Eigen::Vector2d(2.0, 0.5)), Error);
}

}  // namespace
}  // namespace dnurbs
