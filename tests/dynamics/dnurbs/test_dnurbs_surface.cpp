// Tests of dynamics/dnurbs/dnurbs_surface.h (Terzopoulos 2003, eq. 1.27 with the
// thin-plate-under-tension energy of eq 1.20): mass and stiffness matrices, sculpting to static
// equilibrium, and the pressure and gravity forces of dynamics/core/forces.h.

#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"

#include <cmath>
#include <iostream>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/integrators/static_equilibrium.h"
#include "dnurbs/nurbs/gauss_legendre.h"
#include "tests/common/dynamics_test_helpers.h"

namespace dnurbs {
namespace {

using test::flat_patch;

DNurbsSurfaceMaterial plate_material() {
  DNurbsSurfaceMaterial material;
  material.mass_density = 1.0;
  material.damping_density = 2.0;
  material.a10 = 1.0;
  material.a01 = 0.5;
  material.b20 = 0.02;
  material.b11 = 0.01;
  material.b02 = 0.03;
  return material;
}

TEST(DNurbsSurfaceMass, EntriesSumToDensityTimesParametricArea) {
  KnotVector knots_u = KnotVector::clamped_from_breakpoints(2, {0.0, 0.5, 2.0});
  KnotVector knots_v = KnotVector::clamped_from_breakpoints(3, {-1.0, 0.0, 0.25, 1.0});
  const int count = knots_u.control_point_count() * knots_v.control_point_count();
  DNurbsSurfaceMaterial material;
  material.mass_density = 0.7;
  const DNurbsSurface model(NurbsSurface(knots_u, knots_v, Eigen::MatrixX3d::Random(count, 3)),
                            material);
  const Eigen::MatrixXd S(model.scalar_matrices()->mass);
  // Exact Gauss rule (p + 1, q + 1 points); round-off over a few hundred additions.
  EXPECT_NEAR(S.sum(), 0.7 * 2.0 * 2.0, 1e-12);
  EXPECT_NEAR(model.parametric_measure(), 4.0, 1e-15);
  EXPECT_LT((S - S.transpose()).norm(), 1e-15);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues().minCoeff(), 0.0);
}

TEST(DNurbsSurfaceStiffness, RigidTranslationCostsNothingAndKIsSymmetricPsd) {
  const NurbsSurface patch = flat_patch(3, 2, 3, 4);
  const DNurbsSurface model(NurbsSurface(patch.knots_u(), patch.knots_v(),
                                         Eigen::MatrixX3d::Random(patch.control_point_count(), 3)),
                            plate_material());
  const Eigen::MatrixXd K(model.constant_matrices()->stiffness);
  Eigen::VectorXd translation(K.rows());
  for (int i = 0; i < K.rows() / 3; ++i) {
    translation.segment<3>(3 * i) << -0.4, 1.1, 0.25;
  }
  // Derivatives of the partition of unity vanish; round-off relative to the entries.
  EXPECT_LT((K * translation).lpNorm<Eigen::Infinity>(), 1e-12 * K.lpNorm<Eigen::Infinity>());
  EXPECT_LT((K - K.transpose()).norm(), 1e-15);
  const Eigen::VectorXd eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K).eigenvalues();
  EXPECT_GT(eigenvalues.minCoeff(), -1e-12 * eigenvalues.maxCoeff());  // PSD up to round-off
}

TEST(DNurbsSurfaceSculpting, PointForceOnClampedPatchSettlesToTheStaticSolution) {
  DNurbsSurface model(flat_patch(3, 3, 5, 5), plate_material());
  model.fix_border();
  System system(model);
  system.add_force(0, point_force(Eigen::Vector2d(0.4, 0.55), Eigen::Vector3d(0.1, -0.2, 1.0)));

  System reference = system;
  solve_static_equilibrium(reference);

  IntegratorSettings settings;
  settings.scheme = IntegratorScheme::kImplicitEuler;
  Integrator integrator(settings);
  int steps = 0;
  double change = 1.0;
  while (change > 1e-14 && steps < 5000) {
    const Eigen::VectorXd before = system.coordinates();
    integrator.step(system, 0.5);
    change = (system.coordinates() - before).lpNorm<Eigen::Infinity>();
    ++steps;
  }
  const double error = (system.coordinates() - reference.coordinates()).lpNorm<Eigen::Infinity>();
  std::cout << "sculpting: " << steps << " implicit-euler steps, distance to K q = f: " << error
            << "\n";
  // Implicit Euler's fixed point is K q = f exactly; what is left is the decay of the slowest
  // mode below the 1e-14 step change (and round-off of two factorizations).
  EXPECT_LT(error, 1e-8);
  // The pushed point moved along the force, the border did not move.
  EXPECT_GT(system.position(0, Eigen::Vector2d(0.4, 0.55)).z(), 0.0);
  EXPECT_EQ(system.position(0, Eigen::Vector2d(0.0, 0.3)),
            reference.position(0, Eigen::Vector2d(0.0, 0.3)));
  EXPECT_EQ(integrator.factorization_count(), 1);
}

TEST(DNurbsSurfaceSculpting, StaticSolveWithoutFixedPointsIsRejected) {
  System system(DNurbsSurface(flat_patch(2, 2, 2, 2), plate_material()));
  system.add_force(0, point_force(Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d(0.0, 0.0, 1.0)));
  EXPECT_THROW(solve_static_equilibrium(system), Error);
}

// Volume of the cone from the origin over the surface, V = (1/3) integral x . (x_u x x_v),
// by a fine Gauss rule on each span.
double cone_volume(const DNurbsSurface& model, const Eigen::VectorXd& q) {
  const NurbsSurface surface = model.surface(q);
  const std::vector<double> breaks = {0.0, 0.25, 0.5, 0.75, 1.0};
  double volume = 0.0;
  for (size_t i = 0; i + 1 < breaks.size(); ++i) {
    for (size_t j = 0; j + 1 < breaks.size(); ++j) {
      const GaussLegendreRule ru = gauss_legendre_rule_on(8, breaks[i], breaks[i + 1]);
      const GaussLegendreRule rv = gauss_legendre_rule_on(8, breaks[j], breaks[j + 1]);
      for (int a = 0; a < 8; ++a) {
        for (int b = 0; b < 8; ++b) {
          const SurfaceDerivatives d = surface.derivatives(ru.nodes[a], rv.nodes[b], 1);
          volume += ru.weights[a] * rv.weights[b] * d(0, 0).dot(d(1, 0).cross(d(0, 1))) / 3.0;
        }
      }
    }
  }
  return volume;
}

// With the border held, every variation keeps the boundary, so the virtual work of a pressure
// p is p dV: the generalized pressure force on the free coordinates is p dV/dq.
TEST(PressureForce, EqualsPressureTimesVolumeGradientOnFreeCoordinates) {
  NurbsSurface patch = flat_patch(3, 2, 4, 4);
  Eigen::MatrixX3d points = patch.control_points();
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    points(i, 2) = 0.3 * std::sin(2.0 * points(i, 0)) * std::cos(points(i, 1)) + 0.2;
  }
  for (const WeightMode mode : {WeightMode::kFixed, WeightMode::kFree}) {
    DNurbsSettings settings;
    settings.weight_mode = mode;
    settings.quadrature_points = 8;  // the integrand is rational for free weights
    Eigen::VectorXd weights = Eigen::VectorXd::Ones(points.rows());
    if (mode == WeightMode::kFree) {
      for (Eigen::Index i = 0; i < weights.size(); ++i) {
        weights[i] = 1.0 + 0.3 * std::sin(static_cast<double>(i));
      }
    }
    DNurbsSurface model(NurbsSurface(patch.knots_u(), patch.knots_v(), points, weights), {},
                        settings);
    model.fix_border();
    if (mode == WeightMode::kFree) {
      // Border weights shape the boundary curves too: hold them so the boundary stays put.
      const int m = patch.control_point_count_u();
      const int n = patch.control_point_count_v();
      for (int i = 0; i < m; ++i) {
        for (int j = 0; j < n; ++j) {
          if (i == 0 || j == 0 || i == m - 1 || j == n - 1) {
            model.fix_weight(patch.control_point_index(i, j));
          }
        }
      }
    }
    const Eigen::VectorXd q = model.initial_coordinates();
    Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
    pressure(2.5)(model, 0.0, q, Eigen::VectorXd::Zero(q.size()), force);
    std::vector<bool> fixed(static_cast<size_t>(q.size()), false);
    for (const int index : model.fixed_coordinates()) {
      fixed[static_cast<size_t>(index)] = true;
    }
    const double h = 1e-6;
    double worst = 0.0;
    for (int k = 0; k < q.size(); ++k) {
      if (fixed[static_cast<size_t>(k)]) {
        continue;
      }
      Eigen::VectorXd plus = q;
      Eigen::VectorXd minus = q;
      plus[k] += h;
      minus[k] -= h;
      const double fd = 2.5 * (cone_volume(model, plus) - cone_volume(model, minus)) / (2.0 * h);
      worst = std::max(worst, std::abs(force[k] - fd));
    }
    // Central difference O(h^2) + round-off O(1e-16 / h) ~ 1e-10; the model's 8-point rule
    // against the reference 8-point rule on the same spans is exact for fixed weights and
    // ~1e-12 accurate for the smooth rational integrand.
    EXPECT_LT(worst, 1e-8) << (mode == WeightMode::kFree ? "free" : "fixed") << " weights";
  }
}

TEST(GravityForce, EqualsMassMatrixTimesUniformAcceleration) {
  DNurbsSurfaceMaterial material;
  material.mass_density =
      MaterialFunction([](const Eigen::Vector2d& u) { return 1.0 + u.x() * u.y(); });
  const DNurbsSurface model(flat_patch(2, 3, 3, 2), material);
  const Eigen::VectorXd q = model.initial_coordinates();
  Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  gravity(g)(model, 0.0, q, Eigen::VectorXd::Zero(q.size()), force);
  // integral mu L^T g = M [g, g, ...] because sum_a R_a = 1 (same quadrature: round-off).
  Eigen::VectorXd uniform(q.size());
  for (int i = 0; i < model.control_point_count(); ++i) {
    uniform.segment<3>(3 * i) = g;
  }
  EXPECT_LT((force - model.constant_matrices()->mass * uniform).norm(), 1e-13);
}

TEST(SpringForce, PullsTheMaterialPointTowardsAMovingTarget) {
  const DNurbsSurface model(flat_patch(2, 2, 3, 3), plate_material());
  const Eigen::Vector2d u(0.3, 0.6);
  const Force spring = spring_force(
      u, [](double t) { return Eigen::Vector3d(0.3, 0.6, t); }, 4.0);
  const Eigen::VectorXd q = model.initial_coordinates();
  Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
  spring(model, 2.0, q, Eigen::VectorXd::Zero(q.size()), force);
  // L^T k (target - x) with x(u) = (0.3, 0.6, 0): only z, of total k * 2 (sum R_a = 1).
  double total_z = 0.0;
  for (int i = 0; i < model.control_point_count(); ++i) {
    EXPECT_NEAR(force[3 * i], 0.0, 1e-15);
    EXPECT_NEAR(force[3 * i + 1], 0.0, 1e-15);
    total_z += force[3 * i + 2];
  }
  EXPECT_NEAR(total_z, 8.0, 1e-14);
  EXPECT_THROW(spring_force(
                   u, [](double) { return Eigen::Vector3d::Zero(); }, -1.0),
               Error);
}

}  // namespace
}  // namespace dnurbs
