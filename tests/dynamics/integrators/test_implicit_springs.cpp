// Tests of dynamics/integrators/implicit_springs.h: springs whose stiffness is in the step matrix.
// A clamped D-NURBS sheet (bicubic, 5 by 5 spans) and a clamped rod (cubic, 10 spans) with one
// spring, stiffness 1 to 1e6, dt 1/60 to 0.1: undamped Newmark conserves the energy of
// model plus spring, implicit Euler never gains energy, the static pull is the direct solve of (K +
// k N N^T) P = k N target^T, and a drag (target and parameter moving every step) follows the
// trajectory of a step matrix refactored from scratch.

#include "dnurbs/dynamics/integrators/implicit_springs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/integrators/static_equilibrium.h"
#include "tests/common/dynamics_test_helpers.h"

namespace dnurbs {
namespace {

constexpr std::array<double, 4> kStiffnesses{1.0, 1e2, 1e4, 1e6};
constexpr std::array<double, 3> kTimeSteps{1.0 / 60.0, 0.02, 0.1};

// The same curve without the S (x) I_3 declaration: springs become three velocity-space terms.
class GeneralPathCurve : public DNurbsCurve {
 public:
  using DNurbsCurve::DNurbsCurve;
  std::unique_ptr<Model> clone() const override {
    return std::make_unique<GeneralPathCurve>(*this);
  }
  int kronecker_block_size() const override { return 0; }
};

// A clamped flat bicubic sheet (8 by 8 control points on [0, 1]^2, border fixed), tension 1.
DNurbsSurface clamped_sheet(double damping) {
  DNurbsSurfaceMaterial material;
  material.a10 = material.a01 = 1.0;
  material.damping_density = damping;
  DNurbsSurface sheet(test::flat_patch(3, 3, 5, 5), material);
  sheet.fix_border();
  return sheet;
}

// A straight cubic rod (13 control points on [0, 1]) with both ends clamped, tension 1.
template <typename Curve = DNurbsCurve>
Curve clamped_rod(double damping) {
  DNurbsCurveMaterial material;
  material.tension = 1.0;
  material.damping_density = damping;
  Curve rod(test::straight_curve(3, 10), material);
  rod.fix_control_point(0);
  rod.fix_control_point(rod.control_point_count() - 1);
  return rod;
}

// Model + spring: one spring at u pulling toward target (fixed).
System with_spring(const Model& model, const Eigen::Vector2d& u, const Eigen::Vector3d& target,
                   double k) {
  System system(model);
  system.add_spring(0, mouse_spring(
                           u, [target](double) { return target; }, k));
  return system;
}

double total_energy(const System& system) {
  return system.kinetic_energy() + system.potential_energy() + system.spring_energy();
}

struct SpringCase {
  const char* name;
  bool sheet;
};
constexpr std::array<SpringCase, 2> kModels{{{"sheet", true}, {"rod", false}}};

System spring_case(bool sheet, double k, double damping) {
  if (sheet) {
    return with_spring(clamped_sheet(damping), {0.5, 0.5}, {0.5, 0.5, 0.3}, k);
  }
  return with_spring(clamped_rod(damping), {0.5, 0.0}, {0.5, 0.3, 0.0}, k);
}

// Largest |E_n - E_0| over `steps` steps, relative to the spring's initial energy (the energy
// that the spring and the model exchange).
double energy_drift(System system, IntegratorScheme scheme, double dt, int steps,
                    double* largest_gain = nullptr) {
  IntegratorSettings settings;
  settings.scheme = scheme;
  Integrator integrator(settings);
  const double e0 = total_energy(system);
  const double scale = system.spring_energy();
  double drift = 0.0;
  double gain = -1e300;
  double previous = e0;
  for (int n = 0; n < steps; ++n) {
    integrator.step(system, dt);
    const double e = total_energy(system);
    drift = std::max(drift, std::abs(e - e0) / scale);
    gain = std::max(gain, (e - previous) / scale);
    previous = e;
  }
  if (largest_gain != nullptr) {
    *largest_gain = gain;
  }
  return drift;
}

TEST(ImplicitSprings, UndampedNewmarkConservesEnergyOfModelPlusSpring) {
  // Newmark's average acceleration is the trapezoidal rule: on the linear system
  // M a + (K + k L^T L) q = k L^T target it conserves (1/2) v^T M v + (1/2) q^T K q
  // + (1/2) k |L q - target|^2 exactly, so the drift is rounding: about 1e-16 per step times the
  // condition of the step matrix, measured at most 6e-11 (sheet, k = 1e6, dt = 0.1) over 600
  // steps, 7e-13 or less for k <= 1e4.
  for (const SpringCase& model : kModels) {
    for (const double k : kStiffnesses) {
      for (const double dt : kTimeSteps) {
        const double drift =
            energy_drift(spring_case(model.sheet, k, 0.0), IntegratorScheme::kNewmark, dt, 600);
        EXPECT_LT(drift, 1e-9) << model.name << " k = " << k << " dt = " << dt;
      }
    }
  }
}

TEST(ImplicitSprings, ImplicitEulerNeverGainsEnergy) {
  // Implicit Euler on a linear undamped system: E_{n+1} - E_n = -(1/2) dt^2 (a^T M a
  // + v^T K~ v) <= 0 with K~ = K + k L^T L. A gain may only be rounding: 1e-12 of the spring's
  // energy (measured gains at most 6e-14, where the motion has died out).
  for (const SpringCase& model : kModels) {
    for (const double k : kStiffnesses) {
      for (const double dt : kTimeSteps) {
        double gain = 0.0;
        energy_drift(spring_case(model.sheet, k, 0.0), IntegratorScheme::kImplicitEuler, dt, 600,
                     &gain);
        EXPECT_LT(gain, 1e-12) << model.name << " k = " << k << " dt = " << dt;
      }
    }
  }
}

// The direct solve of (K_ff + k N_f N_f^T) P_f = k N_f target^T - (K_fc + k N_f N_c^T) P_c in
// the scalar (node by 3) form, dense, from the model's scalar stiffness and its basis N(u).
Eigen::MatrixX3d direct_static_pull(const Model& model, const Eigen::Vector2d& u,
                                    const Eigen::Vector3d& target, double k) {
  const Eigen::MatrixXd K(model.scalar_matrices()->stiffness);
  const Eigen::Index nodes = K.rows();
  const SparseMatrix L = model.position_jacobian(model.initial_coordinates(), u);
  Eigen::VectorXd N = Eigen::VectorXd::Zero(nodes);
  for (Eigen::Index j = 0; j < nodes; ++j) {
    N[j] = L.coeff(0, 3 * j);
  }
  std::vector<bool> fixed(static_cast<size_t>(nodes), false);
  for (const int index : model.fixed_coordinates()) {
    fixed[static_cast<size_t>(index / 3)] = true;
  }
  std::vector<Eigen::Index> free;
  for (Eigen::Index j = 0; j < nodes; ++j) {
    if (!fixed[static_cast<size_t>(j)]) {
      free.push_back(j);
    }
  }
  const Eigen::MatrixXd S = K + k * N * N.transpose();
  const Eigen::VectorXd q0 = model.initial_coordinates();
  Eigen::MatrixX3d held =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(q0.data(), nodes,
                                                                                  3);
  for (const Eigen::Index j : free) {
    held.row(j).setZero();
  }
  const Eigen::MatrixX3d rhs_full = k * N * target.transpose() - S * held;
  const auto f = static_cast<Eigen::Index>(free.size());
  Eigen::MatrixXd S_ff(f, f);
  Eigen::MatrixX3d rhs(f, 3);
  for (Eigen::Index a = 0; a < f; ++a) {
    rhs.row(a) = rhs_full.row(free[static_cast<size_t>(a)]);
    for (Eigen::Index b = 0; b < f; ++b) {
      S_ff(a, b) = S(free[static_cast<size_t>(a)], free[static_cast<size_t>(b)]);
    }
  }
  Eigen::MatrixX3d result = held;
  const Eigen::MatrixX3d solution = S_ff.ldlt().solve(rhs);
  for (Eigen::Index a = 0; a < f; ++a) {
    result.row(free[static_cast<size_t>(a)]) = solution.row(a);
  }
  return result;
}

Eigen::MatrixX3d as_nodes(const Eigen::VectorXd& q) {
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      q.data(), q.size() / 3, 3);
}

// The condition number lambda_max / lambda_min of the scalar step matrix on the free nodes,
// c_M M + c_D D + c_K (K + sum k N N^T) over the given springs (parameter, stiffness): the
// factor by which two backward-stable solves of one step may differ, relative to the unit
// roundoff.
double step_condition(const Model& model,
                      const std::vector<std::pair<Eigen::Vector2d, double>>& springs,
                      double position_coefficient, double velocity_coefficient,
                      double mass_coefficient = 1.0) {
  const ModelMatrices& scalar = *model.scalar_matrices();
  Eigen::MatrixXd A = mass_coefficient * Eigen::MatrixXd(scalar.mass) +
                      position_coefficient * Eigen::MatrixXd(scalar.stiffness);
  if (scalar.damping.nonZeros() > 0) {
    A += velocity_coefficient * Eigen::MatrixXd(scalar.damping);
  }
  const Eigen::VectorXd q0 = model.initial_coordinates();
  for (const auto& [u, k] : springs) {
    const SparseMatrix L = model.position_jacobian(q0, u);
    Eigen::VectorXd N = Eigen::VectorXd::Zero(A.rows());
    for (Eigen::Index j = 0; j < N.size(); ++j) {
      N[j] = L.coeff(0, 3 * j);
    }
    A += position_coefficient * k * N * N.transpose();
  }
  std::vector<bool> fixed(static_cast<size_t>(A.rows()), false);
  for (const int index : model.fixed_coordinates()) {
    fixed[static_cast<size_t>(index / 3)] = true;
  }
  std::vector<Eigen::Index> free;
  for (Eigen::Index j = 0; j < A.rows(); ++j) {
    if (!fixed[static_cast<size_t>(j)]) {
      free.push_back(j);
    }
  }
  Eigen::MatrixXd A_ff(free.size(), free.size());
  for (size_t a = 0; a < free.size(); ++a) {
    for (size_t b = 0; b < free.size(); ++b) {
      A_ff(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) = A(free[a], free[b]);
    }
  }
  const Eigen::VectorXd eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A_ff).eigenvalues();
  return eigenvalues.maxCoeff() / eigenvalues.minCoeff();
}

constexpr double kUnitRoundoff = 1.1e-16;

TEST(ImplicitSprings, StaticPullMatchesTheDirectSolve) {
  // solve_static_equilibrium with the spring's k L^T L in K, and a damped implicit Euler run to
  // rest, against the dense solve of (K + k N N^T) P = k N target^T. Both are backward stable
  // solves of the same system: their difference is rounding, below 2 n kappa u for n free nodes
  // and kappa the condition of K_ff + k N N^T (from 30 at k = 1 to 4e6 at k = 1e6 on the sheet).
  // Measured: at most 2e-12 relative up to k = 1e4 (below the 1e-10), 1e-10 and 4e-11
  // on the sheet at k = 1e6, where 2 n kappa u is 3e-8.
  for (const SpringCase& model : kModels) {
    for (const double k : kStiffnesses) {
      System system = spring_case(model.sheet, k, 2.0);
      const Eigen::Vector2d u = model.sheet ? Eigen::Vector2d(0.5, 0.5) : Eigen::Vector2d(0.5, 0.0);
      const Eigen::Vector3d target = system.spring_state(0, 0.0).target;
      const Eigen::MatrixX3d direct = direct_static_pull(system.model(0), u, target, k);
      const double scale = direct.cwiseAbs().maxCoeff();

      const double free_nodes = model.sheet ? 36.0 : 11.0;
      const double kappa = step_condition(system.model(0), {{u, k}}, 1.0, 0.0, 0.0);
      const double tolerance = (k <= 1e4 ? 1e-10 : 2.0 * free_nodes * kappa * kUnitRoundoff);
      System statics = system;
      solve_static_equilibrium(statics);
      EXPECT_LT((as_nodes(statics.coordinates()) - direct).cwiseAbs().maxCoeff(), tolerance * scale)
          << model.name << " k = " << k;

      // Implicit Euler with damping converges to the fixed point a = v = 0, where its step
      // equation is the static one: stepped until the velocity is at rounding level.
      IntegratorSettings settings;
      settings.scheme = IntegratorScheme::kImplicitEuler;
      Integrator integrator(settings);
      for (int n = 0; n < 3000 && (n < 10 || system.velocities().norm() > 1e-14); ++n) {
        integrator.step(system, 0.1);
      }
      EXPECT_LE(system.velocities().norm(), 1e-14) << model.name << " k = " << k;
      EXPECT_LT((as_nodes(system.coordinates()) - direct).cwiseAbs().maxCoeff(), tolerance * scale)
          << model.name << " k = " << k;
    }
  }
}

// The coefficients (c_K, c_D) of K and D in the step matrix: Newmark's (beta dt^2, gamma dt),
// implicit Euler's (dt^2, dt).
std::pair<double, double> coefficients(const IntegratorSettings& settings, double dt) {
  if (settings.scheme == IntegratorScheme::kNewmark) {
    return {settings.newmark_beta * dt * dt, settings.newmark_gamma * dt};
  }
  return {dt * dt, dt};
}

IntegratorSettings implicit_euler() {
  IntegratorSettings settings;
  settings.scheme = IntegratorScheme::kImplicitEuler;
  return settings;
}

// A drag: the spring's parameter and target move every step.
Spring drag(bool sheet, double k) {
  if (sheet) {
    return dragged_spring(
        [](double t) { return Eigen::Vector2d(0.3 + 0.2 * std::sin(t), 0.5 + 0.1 * t); },
        [](double t) { return Eigen::Vector3d(0.5, 0.5, 0.2 * t); }, k);
  }
  return dragged_spring([](double t) { return Eigen::Vector2d(0.5 + 0.3 * std::sin(t), 0.0); },
                        [](double t) { return Eigen::Vector3d(0.5, 0.3 * std::sin(2 * t), 0.1); },
                        k);
}

// Stacked trajectory of `steps` steps under `treatment`, with the integrator's factorization
// count at the end.
Eigen::MatrixXd trajectory(const Model& model, const Spring& spring, IntegratorSettings settings,
                           SpringTreatment treatment, double dt, int steps,
                           int* factorizations = nullptr) {
  System system(model);
  system.add_spring(0, spring);
  settings.springs = treatment;
  Integrator integrator(settings);
  Eigen::MatrixXd result(system.coordinate_count(), steps);
  for (int n = 0; n < steps; ++n) {
    integrator.step(system, dt);
    result.col(n) = system.coordinates();
  }
  if (factorizations != nullptr) {
    *factorizations = integrator.factorization_count();
  }
  return result;
}

TEST(ImplicitSprings, DragFollowsTheRefactoredTrajectoryWithOneFactorization) {
  // Woodbury (target form) against the step matrix with the spring summed in and refactored at
  // every step: the same step equations, solved two ways, each backward stable. One step's
  // solutions differ by about kappa(A) u relative (kappa the step matrix's condition, u the unit
  // roundoff) and the differences of 40 steps of a damped recursion add up: tolerance 40
  // kappa u of the largest displacement (kappa from 3 at k = 1 to 1e8 at k = 1e6, dt = 0.1).
  // Measured: below 1e-12 relative up to k = 1e4 (at most 5e-13), 7e-11 at k = 1e6. The parameter
  // moves, so the scheme is implicit Euler (implicit_springs.h, "Stability"); Newmark's drags are
  // the next test.
  const int steps = 40;
  for (const SpringCase& model : kModels) {
    for (const double k : kStiffnesses) {
      for (const double dt : {1.0 / 60.0, 0.1}) {
        {
          const IntegratorSettings settings = implicit_euler();
          const DNurbsSurface sheet = clamped_sheet(0.5);
          const DNurbsCurve rod = clamped_rod(0.5);
          const Model& shape = model.sheet ? static_cast<const Model&>(sheet) : rod;
          const Spring spring = drag(model.sheet, k);
          int low_rank_factorizations = 0;
          int refactorizations = 0;
          const Eigen::MatrixXd low_rank =
              trajectory(shape, spring, settings, SpringTreatment::kLowRank, dt, steps,
                         &low_rank_factorizations);
          const Eigen::MatrixXd refactored = trajectory(
              shape, spring, settings, SpringTreatment::kRefactor, dt, steps, &refactorizations);
          const Eigen::MatrixXd rest = shape.initial_coordinates().replicate(1, steps);
          const double scale = (refactored - rest).cwiseAbs().maxCoeff();
          double kappa = 0.0;
          const auto [c_position, c_velocity] = coefficients(settings, dt);
          for (int n = 1; n <= steps; ++n) {
            kappa = std::max(kappa, step_condition(shape, {{spring(n * dt).parameter, k}},
                                                   c_position, c_velocity));
          }
          const double difference = (low_rank - refactored).cwiseAbs().maxCoeff() / scale;
          const std::string name = std::string(model.name) + " " +
                                   std::string(to_string(settings.scheme)) +
                                   " k = " + std::to_string(k) + " dt = " + std::to_string(dt);
          EXPECT_LT(difference, steps * kappa * kUnitRoundoff) << name;
          if (k <= 1e4) {
            EXPECT_LT(difference, 1e-12) << name;
          }
          EXPECT_LT(scale, 2.0) << name;  // bounded: the sheet follows a target below 1
          EXPECT_EQ(low_rank_factorizations, 1) << name;  // the drag never refactors
          EXPECT_GE(refactorizations, steps) << name;     // one per step at least
        }
      }
    }
  }
}

TEST(ImplicitSprings, UndampedNewmarkDragsWithAFixedParameterStayBounded) {
  // Average-acceleration Newmark, the target dragged along a path at a fixed material point: a
  // time-invariant step matrix (one factorization, no term moves), energy changed only by the
  // target's work, so the sheet stays within reach of the target (displacements below 2) at
  // every k and dt, and follows the refactored step matrix to rounding; with the parameter
  // moving as well, a stiff spring's ringing grows (the
  // documented limit): measured at k = 1e6, dt = 0.1 a displacement above 1e3 after 40 steps.
  for (const double k : kStiffnesses) {
    for (const double dt : kTimeSteps) {
      const Spring pinned = mouse_spring(
          {0.4, 0.5}, [](double t) { return Eigen::Vector3d(0.4, 0.5, 0.3 * std::sin(t)); }, k);
      int factorizations = 0;
      const Eigen::MatrixXd path = trajectory(clamped_sheet(0.0), pinned, IntegratorSettings{},
                                              SpringTreatment::kLowRank, dt, 40, &factorizations);
      const Eigen::MatrixXd refactored = trajectory(
          clamped_sheet(0.0), pinned, IntegratorSettings{}, SpringTreatment::kRefactor, dt, 40);
      const Eigen::MatrixXd rest = clamped_sheet(0.0).initial_coordinates().replicate(1, 40);
      const double scale = (path - rest).cwiseAbs().maxCoeff();
      EXPECT_LT(scale, 2.0) << "k = " << k << " dt = " << dt;
      EXPECT_EQ(factorizations, 1);
      // Target form against pull in b: 40 kappa u, as in the previous test
      const double kappa =
          step_condition(clamped_sheet(0.0), {{{0.4, 0.5}, k}}, 0.25 * dt * dt, 0.0);
      EXPECT_LT((path - refactored).cwiseAbs().maxCoeff(), 40 * kappa * kUnitRoundoff * scale)
          << "k = " << k << " dt = " << dt;
    }
  }
  const Eigen::MatrixXd sliding =
      trajectory(clamped_sheet(0.5), drag(true, 1e6), IntegratorSettings{},
                 SpringTreatment::kLowRank, 0.1, 40);
  const Eigen::MatrixXd rest = clamped_sheet(0.5).initial_coordinates().replicate(1, 40);
  EXPECT_GT((sliding - rest).cwiseAbs().maxCoeff(), 1e3);
}

TEST(ImplicitSprings, NodeAndVelocityBlocksGiveTheSameTrajectory) {
  // The rank-one term k N N^T on the scalar matrix against the three terms k l_r^T l_r on the
  // velocity-space block of the same rod: the same equations with x, y and z uncoupled, computed
  // by the same operations in another order (measured: identical to the last bit). Tolerance
  // 1e-12 of displacements about 0.3: 40 steps of kappa u with kappa below 1e5 here (8e4 at
  // k = 1e6, dt = 0.1).
  for (const double k : kStiffnesses) {
    const IntegratorSettings euler = implicit_euler();
    const Eigen::MatrixXd nodes =
        trajectory(clamped_rod(0.5), drag(false, k), euler, SpringTreatment::kLowRank, 0.05, 40);
    const Eigen::MatrixXd velocities =
        trajectory(clamped_rod<GeneralPathCurve>(0.5), drag(false, k), euler,
                   SpringTreatment::kLowRank, 0.05, 40);
    EXPECT_LT((nodes - velocities).cwiseAbs().maxCoeff(), 1e-12) << "k = " << k;
  }
}

TEST(ImplicitSprings, AddingMovingAndRemovingSpringsNeverRefactors) {
  // Springs come and go between steps (set_spring, remove_spring, a windowed spring switching
  // on and off): the sheet's block stays factored once; the trajectory is that of the
  // refactored step matrix (rounding, as above).
  auto run = [](SpringTreatment treatment, int* factorizations) {
    System system(clamped_sheet(1.0));
    IntegratorSettings settings;
    settings.springs = treatment;
    Integrator integrator(settings);
    const auto at = [](double z) { return [z](double) { return Eigen::Vector3d(0.4, 0.6, z); }; };
    const int first = system.add_spring(0, mouse_spring({0.4, 0.6}, at(0.3), 1e3));
    system.add_spring(0, windowed_spring(mouse_spring({0.7, 0.3}, at(-0.2), 50.0), 0.2, 0.5));
    Eigen::MatrixXd result(system.coordinate_count(), 60);
    for (int n = 0; n < 60; ++n) {
      if (n == 10) {
        system.set_spring(first, mouse_spring({0.45, 0.55}, at(0.1), 2e3));
      }
      if (n == 20) {
        system.add_spring(0, mouse_spring({0.2, 0.2}, at(0.05), 1e4));
      }
      if (n == 40) {
        system.remove_spring(first);
      }
      integrator.step(system, 0.02);
      result.col(n) = system.coordinates();
    }
    *factorizations = integrator.factorization_count();
    return result;
  };
  int low_rank_factorizations = 0;
  int refactorizations = 0;
  const Eigen::MatrixXd low_rank = run(SpringTreatment::kLowRank, &low_rank_factorizations);
  const Eigen::MatrixXd refactored = run(SpringTreatment::kRefactor, &refactorizations);
  // Rounding of two backward-stable solves over 60 steps (first test): 60 kappa u of the largest
  // displacement, kappa with every spring at once (measured 2e-11 of displacements up to 9,
  // kappa 2.5e3; undamped by the scheme, the stiff springs ring).
  const double kappa = step_condition(clamped_sheet(1.0),
                                      {{{0.45, 0.55}, 2e3}, {{0.7, 0.3}, 50.0}, {{0.2, 0.2}, 1e4}},
                                      0.25 * 0.02 * 0.02, 0.5 * 0.02);
  const Eigen::MatrixXd rest = clamped_sheet(1.0).initial_coordinates().replicate(1, 60);
  EXPECT_LT((low_rank - refactored).cwiseAbs().maxCoeff(),
            60 * kappa * kUnitRoundoff * (refactored - rest).cwiseAbs().maxCoeff());
  EXPECT_EQ(low_rank_factorizations, 1);
  EXPECT_GT(refactorizations, 1);
}

TEST(ImplicitSprings, SolveHookSeesTheSpringsInALinearSolve) {
  // A hook that solves A delta = b with the integrator's own solve: the springs' pull moves into
  // b and A^{-1} is linear (no target in it); the trajectory is the hook-less one up to rounding.
  const IntegratorSettings euler = implicit_euler();
  const Eigen::MatrixXd plain =
      trajectory(clamped_sheet(0.5), drag(true, 1e4), euler, SpringTreatment::kLowRank, 0.02, 30);
  System system(clamped_sheet(0.5));
  system.add_spring(0, drag(true, 1e4));
  Integrator integrator(euler);
  bool linear = true;
  integrator.set_solve_hook([&linear](const StepSystem& step, Eigen::VectorXd& delta) {
    Eigen::VectorXd twice;
    step.solve(*step.rhs, delta);
    step.solve(2.0 * *step.rhs, twice);
    linear = linear && (twice - 2.0 * delta).norm() <= 1e-12 * delta.norm();
  });
  Eigen::MatrixXd hooked(system.coordinate_count(), 30);
  for (int n = 0; n < 30; ++n) {
    integrator.step(system, 0.02);
    hooked.col(n) = system.coordinates();
  }
  EXPECT_TRUE(linear);
  // Pull in b against pull in the target form: rounding of two backward-stable solves, 30 kappa u
  // of the largest displacement (as above; measured 2e-13 absolute)
  double kappa = 0.0;
  for (int n = 1; n <= 30; ++n) {
    const auto [c_position, c_velocity] = coefficients(euler, 0.02);
    kappa = std::max(
        kappa, step_condition(clamped_sheet(0.5), {{drag(true, 1e4)(0.02 * n).parameter, 1e4}},
                              c_position, c_velocity));
  }
  const Eigen::MatrixXd rest = clamped_sheet(0.5).initial_coordinates().replicate(1, 30);
  EXPECT_LT((hooked - plain).cwiseAbs().maxCoeff(),
            30 * kappa * kUnitRoundoff * (plain - rest).cwiseAbs().maxCoeff());
}

TEST(ImplicitSprings, ExplicitSpringsAreTheOldStepAndDivergeWhereImplicitOnesDoNot) {
  // k = 1e4 on the sheet at dt = 0.02: the explicit spring's frequency sqrt(k N^T M^-1 N) times
  // dt is far above Newmark's explicit-force limit, so the energy grows by orders of magnitude;
  // the implicit spring conserves it (first test).
  System explicit_system = spring_case(true, 1e4, 0.0);
  IntegratorSettings settings;
  settings.springs = SpringTreatment::kExplicit;
  Integrator integrator(settings);
  const double e0 = total_energy(explicit_system);
  bool diverged = false;
  try {
    for (int n = 0; n < 200; ++n) {
      integrator.step(explicit_system, 0.02);
    }
    diverged = total_energy(explicit_system) > 1e3 * e0;
  } catch (const Error&) {
    diverged = true;
  }
  EXPECT_TRUE(diverged);
  EXPECT_LT(energy_drift(spring_case(true, 1e4, 0.0), IntegratorScheme::kNewmark, 0.02, 200), 1e-9);
}

TEST(ImplicitSprings, BadSpringStatesThrowNamingTheSpring) {
  System system(clamped_sheet(0.0));
  system.add_spring(0, [](double t) {
    return SpringState{{0.5, 0.5}, {0.0, 0.0, t > 0.05 ? std::nan("") : 0.0}, 1.0};
  });
  Integrator integrator;
  integrator.step(system, 0.02);
  try {
    for (int n = 0; n < 5; ++n) {
      integrator.step(system, 0.02);
    }
    ADD_FAILURE() << "no Error for a NaN target";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("spring 0"), std::string::npos) << error.what();
  }
  EXPECT_TRUE(system.coordinates().allFinite());
  EXPECT_THROW(mouse_spring(
                   {0.5, 0.5}, [](double) { return Eigen::Vector3d::Zero(); }, -1.0),
               Error);
}

}  // namespace
}  // namespace dnurbs
