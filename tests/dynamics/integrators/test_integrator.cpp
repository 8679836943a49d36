// Tests of dynamics/integrators/integrator.h: orders of accuracy of central (Terzopoulos 2003,
// eq. 1.13), implicit-euler and newmark against the exact modal solution of a linear D-NURBS
// string, Newmark energy conservation, the factor-once fast path, and error handling.

#include "dnurbs/dynamics/integrators/integrator.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"
#include "tests/common/dynamics_test_helpers.h"

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

// Terzopoulos 2003 eq 1.13 treats the inertia by central differences but the stiffness at t + dt
// and the force at t: K q(t+dt) - K q(t) = O(dt) is a first-order truncation error, so the scheme
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

// ----------------------------------------------------------------------------------------------
// The integrator factors A block by block (one block per model): a constant D-NURBS block is
// factored once per (dt, scheme) even beside a state-dependent deformable superquadric whose block
// is re-factored at every solve, and, the models being uncoupled in M, D, K, the trajectory of
// the mixed System is that of each model stepped alone in its own System.

constexpr double kDt = 0.01;
const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);

// A point load on the sheet.
Force sheet_load() {
  return point_force(Eigen::Vector2d(0.4, 0.65), Eigen::Vector3d(0.1, 0.0, -2.0));
}

// Model 0: a 7 x 7 fixed-weight D-NURBS membrane with its border fixed (constant M, D, K with the
// S (x) I_3 structure) under a point load; model 1: a deformable superquadric with its global
// deformations free (state-dependent matrices) under gravity, spinning and deforming.
System sheet_and_superquadric() {
  DNurbsSurfaceMaterial material;
  material.damping_density = 0.1;
  material.a10 = 1.0;
  material.a01 = 1.0;
  material.b20 = 0.01;
  material.b02 = 0.01;
  DNurbsSurface sheet(test::flat_patch(3, 3, 4, 4), material);
  sheet.fix_border();
  SuperquadricShapeParameters shape = SuperquadricShapeParameters::Zero();
  shape << 1.0, 0.3, 0.25, 0.35, 0.8, 1.2, 0.1, -0.05, 0, 0, 0, 0.2, 0, 0;
  DeformableSuperquadricSettings settings;
  settings.parts = DeformableSuperquadricParts::global();
  const DeformableSuperquadricModel body(
      shape, Eigen::Vector3d(0.5, 0.5, 1.0),
      Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1.0, 2.0, 0.5).normalized())),
      settings);
  System system;
  system.add_model(sheet);
  system.add_model(body);
  system.add_force(0, sheet_load());
  system.add_force(1, gravity(kGravity));
  Eigen::VectorXd spin = Eigen::VectorXd::Zero(body.velocity_count());
  for (int i = 3; i < body.velocity_count(); ++i) {
    spin[i] = 0.5 * std::sin(1.7 * i);  // angular velocity and shape rates
  }
  system.set_velocities(1, spin);
  return system;
}

// Steps `system` `steps` times with a fresh integrator of `settings`.
Integrator run(System& system, const IntegratorSettings& settings, int steps) {
  Integrator integrator(settings);
  for (int k = 0; k < steps; ++k) {
    integrator.step(system, kDt);
  }
  return integrator;
}

double relative_difference(const Eigen::VectorXd& value, const Eigen::VectorXd& reference) {
  return (value - reference).norm() / reference.norm();
}

TEST(BlockFactorization, ConstantBlockIsFactoredOnceBesideAStateDependentOne) {
  System system = sheet_and_superquadric();
  ASSERT_FALSE(system.matrices_are_constant());
  IntegratorSettings settings;  // newmark
  settings.newton_iterations = 2;
  settings.newton_tolerance = 0.0;  // every iteration runs: 3 solves per step
  const int steps = 40;
  const Integrator integrator = run(system, settings, steps);
  EXPECT_EQ(integrator.block_factorization_count(0), 1);          // the D-NURBS sheet
  EXPECT_EQ(integrator.block_factorization_count(1), 3 * steps);  // the superquadric
  EXPECT_EQ(integrator.factorization_count(), 1 + 3 * steps);
  EXPECT_EQ(integrator.last_newton_iterations(), 2);
  EXPECT_THROW(static_cast<void>(integrator.block_factorization_count(2)), Error);
  EXPECT_THROW(static_cast<void>(integrator.block_factorization_count(-1)), Error);
}

TEST(BlockFactorization, NewTimeStepRefactorsTheConstantBlockOnce) {
  System system = sheet_and_superquadric();
  Integrator integrator;
  for (int k = 0; k < 5; ++k) {
    integrator.step(system, kDt);
  }
  for (int k = 0; k < 5; ++k) {
    integrator.step(system, 2.0 * kDt);
  }
  EXPECT_EQ(integrator.block_factorization_count(0), 2);
  EXPECT_EQ(integrator.block_factorization_count(1), 10);
}

TEST(BlockFactorization, MixedTrajectoryEqualsEachModelSteppedAlone) {
  // Uncoupled models: the block solves of the mixed System are the solves of the single-model
  // Systems, so the states agree to rounding (assert 1e-12 relative).
  for (const IntegratorScheme scheme :
       {IntegratorScheme::kNewmark, IntegratorScheme::kImplicitEuler, IntegratorScheme::kCentral}) {
    System mixed = sheet_and_superquadric();
    System sheet(mixed.model(0));
    System body(mixed.model(1));
    sheet.add_force(0, sheet_load());
    body.add_force(0, gravity(kGravity));
    body.set_velocities(0, mixed.velocities(1));
    const IntegratorSettings settings{scheme};
    const int steps = 30;  // central goes unstable on the spinning superquadric near 60
    run(mixed, settings, steps);
    run(sheet, settings, steps);
    run(body, settings, steps);
    const int sheet_size = sheet.velocity_count();
    const int body_size = body.velocity_count();
    const double sheet_error =
        relative_difference(mixed.coordinates().head(sheet_size), sheet.coordinates());
    const double body_error =
        relative_difference(mixed.coordinates().tail(body.coordinate_count()), body.coordinates());
    const double velocity_error =
        std::max(relative_difference(mixed.velocities().head(sheet_size), sheet.velocities()),
                 relative_difference(mixed.velocities().tail(body_size), body.velocities()));
    std::cout << to_string(scheme) << ": mixed against alone, coordinates " << sheet_error << ", "
              << body_error << ", velocities " << velocity_error << "\n";
    EXPECT_LT(sheet_error, 1e-12) << to_string(scheme);
    EXPECT_LT(body_error, 1e-12) << to_string(scheme);
    EXPECT_LT(velocity_error, 1e-12) << to_string(scheme);
    // Both models moved (the comparison is not between two rest states).
    EXPECT_GT((sheet.coordinates() - mixed.model(0).initial_coordinates()).norm(), 1e-3);
    EXPECT_GT((body.coordinates() - mixed.model(1).initial_coordinates()).norm(), 1e-3);
  }
}

}  // namespace
}  // namespace dnurbs
