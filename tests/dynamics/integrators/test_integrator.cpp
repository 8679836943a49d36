// Tests of dynamics/integrators/integrator.h: orders of accuracy of central (seed 001 eq 1.13),
// implicit-euler and newmark against the exact modal solution of a linear D-NURBS string,
// Newmark energy conservation, the factor-once fast path, and error handling.

#include "dynamics/integrators/integrator.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "dynamics/dnurbs/dnurbs_curve.h"
#include "dynamics/core/forces.h"
#include "tests/common/dynamics_test_helpers.h"
#include "core/error.h"

namespace dnurbs {
namespace {

// The same curve model without the S (x) I_3 declaration: integrators take the general path.
class GeneralPathCurve : public DNurbsCurve {
 public:
  using DNurbsCurve::DNurbsCurve;
  std::unique_ptr<Model> clone() const override {
    return std::make_unique<GeneralPathCurve>(*this);
  }
  int kronecker_block_size() const override { return 0; }
};

// A clamped D-NURBS string (degree 3, 10 spans, w1 = 1, mu = 1, gamma = c so D = c M) started
// in its first discrete mode: y = amplitude * phi, v = 0. The exact solution of the discrete
// system is y(t) = amplitude * phi * e^{-ct/2} (cos wd t + c/(2 wd) sin wd t).
struct ModeCase {
  DNurbsCurve model;
  Eigen::VectorXd phi;  // per control point, zero at the clamped ends
  double omega = 0.0;
  double damping = 0.0;
  double amplitude = 0.1;

  explicit ModeCase(double c, bool general_path = false) : model(make_model(c)), damping(c) {
    const Eigen::MatrixXd M(model.scalar_matrices()->mass);
    const Eigen::MatrixXd K(model.scalar_matrices()->stiffness);
    const auto n = static_cast<int>(M.rows());
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eigen(K.block(1, 1, n - 2, n - 2),
                                                                    M.block(1, 1, n - 2, n - 2));
    omega = std::sqrt(eigen.eigenvalues()[0]);
    phi = Eigen::VectorXd::Zero(n);
    phi.segment(1, n - 2) = eigen.eigenvectors().col(0);
    phi /= phi.cwiseAbs().maxCoeff();
    model.fix_control_point(0);
    model.fix_control_point(n - 1);
    general = general_path;
  }

  static DNurbsCurve make_model(double c) {
    DNurbsCurveMaterial material;
    material.tension = 1.0;
    material.damping_density = c;
    return DNurbsCurve(test::straight_curve(3, 10), material);
  }

  System system() const {
    System result;
    if (general) {
      DNurbsCurveMaterial material;
      material.tension = 1.0;
      material.damping_density = damping;
      GeneralPathCurve copy(test::straight_curve(3, 10), material);
      copy.fix_control_point(0);
      copy.fix_control_point(static_cast<int>(phi.size()) - 1);
      result.add_model(copy);
    } else {
      result.add_model(model);
    }
    Eigen::VectorXd q = model.initial_coordinates();
    for (Eigen::Index i = 0; i < phi.size(); ++i) {
      q[3 * i + 1] = amplitude * phi[i];
    }
    result.set_coordinates(0, q);
    return result;
  }

  double exact(double t) const {
    const double wd = std::sqrt(omega * omega - 0.25 * damping * damping);
    return amplitude * std::exp(-0.5 * damping * t) *
           (std::cos(wd * t) + 0.5 * damping / wd * std::sin(wd * t));
  }

  // Largest y error over the control points after `steps` steps over one period.
  double error(IntegratorScheme scheme, int steps) const {
    System s = system();
    IntegratorSettings settings;
    settings.scheme = scheme;
    Integrator integrator(settings);
    const double period = 2.0 * std::numbers::pi / omega;
    const double dt = period / steps;
    for (int k = 0; k < steps; ++k) {
      integrator.step(s, dt);
    }
    double worst = 0.0;
    for (Eigen::Index i = 0; i < phi.size(); ++i) {
      worst = std::max(worst, std::abs(s.coordinates()[3 * i + 1] - exact(s.time()) * phi[i]));
    }
    return worst;
  }

  bool general = false;
};

double observed_order(const ModeCase& mode, IntegratorScheme scheme) {
  const double coarse = mode.error(scheme, 200);
  const double fine = mode.error(scheme, 400);
  const double order = std::log2(coarse / fine);
  std::cout << to_string(scheme) << ": errors " << coarse << " -> " << fine << ", order " << order
            << "\n";
  return order;
}

TEST(IntegratorOrder, ImplicitEulerIsFirstOrder) {
  const ModeCase mode(0.05);  // lightly damped: exercises the D terms
  // Expected 1; the bound allows the O(dt) term of the error constant at 200-400 steps/period.
  EXPECT_NEAR(observed_order(mode, IntegratorScheme::kImplicitEuler), 1.0, 0.15);
}

TEST(IntegratorOrder, NewmarkIsSecondOrder) {
  const ModeCase mode(0.05);
  EXPECT_NEAR(observed_order(mode, IntegratorScheme::kNewmark), 2.0, 0.05);
}

// Seed 001 eq 1.13 treats the inertia by central differences but the stiffness at t + dt and
// the force at t: K q(t+dt) - K q(t) = O(dt) is a first-order truncation error, so the scheme
// is first order (and numerically dissipative), not second order like the explicit central
// difference method.
TEST(IntegratorOrder, SeedCentralSchemeIsFirstOrderBecauseStiffnessIsImplicit) {
  const ModeCase mode(0.05);
  EXPECT_NEAR(observed_order(mode, IntegratorScheme::kCentral), 1.0, 0.15);
}

TEST(IntegratorOrder, GeneralPathMatchesKroneckerFastPath) {
  const ModeCase fast(0.05, false);
  const ModeCase general(0.05, true);
  for (const auto scheme :
       {IntegratorScheme::kCentral, IntegratorScheme::kImplicitEuler, IntegratorScheme::kNewmark}) {
    System a = fast.system();
    System b = general.system();
    ASSERT_EQ(a.kronecker_block_size(), 3);
    ASSERT_EQ(b.kronecker_block_size(), 0);
    IntegratorSettings settings;
    settings.scheme = scheme;
    Integrator ia(settings);
    Integrator ib(settings);
    for (int k = 0; k < 50; ++k) {
      ia.step(a, 0.01);
      ib.step(b, 0.01);
    }
    // Same equations, different factorizations (scalar vs 3x expanded): round-off only.
    EXPECT_LT((a.coordinates() - b.coordinates()).lpNorm<Eigen::Infinity>(), 1e-13)
        << to_string(scheme);
    EXPECT_LT((a.velocities() - b.velocities()).lpNorm<Eigen::Infinity>(), 1e-11)
        << to_string(scheme);
  }
}

TEST(IntegratorEnergy, UndampedNewmarkConservesEnergyOverTenThousandSteps) {
  const ModeCase mode(0.0);
  System system = mode.system();
  System rest(mode.model);
  const double rest_energy = rest.potential_energy();  // the stretched straight string
  Integrator integrator;
  const double dt = 2.0 * std::numbers::pi / mode.omega / 37.0;
  const double initial = system.kinetic_energy() + system.potential_energy() - rest_energy;
  double drift = 0.0;
  for (int k = 0; k < 10000; ++k) {
    integrator.step(system, dt);
    if (k % 100 == 99) {
      const double energy = system.kinetic_energy() + system.potential_energy() - rest_energy;
      drift = std::max(drift, std::abs(energy - initial) / initial);
    }
  }
  std::cout << "newmark relative energy drift over 10000 steps: " << drift << "\n";
  // Average acceleration conserves the energy of a linear undamped system exactly; what is
  // left is round-off accumulated over 1e4 steps (and the cancellation of the rest energy).
  EXPECT_LT(drift, 1e-9);
  EXPECT_EQ(integrator.factorization_count(), 1);
}

TEST(IntegratorFastPath, FactorsOncePerTimeStepAndScheme) {
  const ModeCase mode(0.1);
  System system = mode.system();
  Integrator integrator;
  for (int k = 0; k < 20; ++k) {
    integrator.step(system, 0.01);
  }
  EXPECT_EQ(integrator.factorization_count(), 1);
  integrator.step(system, 0.02);
  integrator.step(system, 0.02);
  EXPECT_EQ(integrator.factorization_count(), 2);
}

TEST(IntegratorErrors, NonPositiveOrNanTimeStepIsRejectedWithItsValue) {
  const ModeCase mode(0.0);
  System system = mode.system();
  Integrator integrator;
  for (const double dt : {0.0, -0.5, std::numeric_limits<double>::quiet_NaN(),
                          std::numeric_limits<double>::infinity()}) {
    try {
      integrator.step(system, dt);
      FAIL() << "no error for dt " << dt;
    } catch (const Error& error) {
      std::ostringstream expected;
      expected.precision(17);
      expected << "dt = " << dt;
      EXPECT_NE(std::string(error.what()).find(expected.str()), std::string::npos) << error.what();
    }
  }
  EXPECT_EQ(system.time(), 0.0);
}

TEST(IntegratorErrors, NonFiniteStepThrowsAndLeavesStateIntact) {
  const ModeCase mode(0.0);
  for (const auto scheme :
       {IntegratorScheme::kCentral, IntegratorScheme::kImplicitEuler, IntegratorScheme::kNewmark}) {
    System system = mode.system();
    system.add_force(0, point_force(Eigen::Vector2d(0.5, 0.0), [](double t) {
                       return t > 0.05 ? Eigen::Vector3d(std::nan(""), 0.0, 0.0)
                                       : Eigen::Vector3d(0.0, 1.0, 0.0);
                     }));
    IntegratorSettings settings;
    settings.scheme = scheme;
    Integrator integrator(settings);
    Eigen::VectorXd q;
    Eigen::VectorXd v;
    double t = 0.0;
    EXPECT_THROW(
        {
          for (int k = 0; k < 100; ++k) {
            q = system.coordinates();
            v = system.velocities();
            t = system.time();
            integrator.step(system, 0.01);
          }
        },
        Error)
        << to_string(scheme);
    EXPECT_EQ(system.coordinates(), q);
    EXPECT_EQ(system.velocities(), v);
    EXPECT_EQ(system.time(), t);
    EXPECT_TRUE(system.coordinates().allFinite());
  }
}

TEST(IntegratorSchemes, NamesRoundTripAndUnknownNameIsRejected) {
  for (const auto scheme :
       {IntegratorScheme::kCentral, IntegratorScheme::kImplicitEuler, IntegratorScheme::kNewmark}) {
    EXPECT_EQ(parse_integrator_scheme(to_string(scheme)), scheme);
  }
  EXPECT_THROW(parse_integrator_scheme("rk4"), Error);
}

}  // namespace
}  // namespace dnurbs
