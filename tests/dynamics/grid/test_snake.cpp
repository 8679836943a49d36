#include "dnurbs/dynamics/grid/snake.h"

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/integrators/semi_implicit_step.h"

namespace dnurbs {
namespace {

// N nodes at equal angles, at radius r (1 + wobble cos 2 angle).
NodePositions circle(int n, double radius, double wobble = 0.0) {
  NodePositions positions = NodePositions::Zero(n, 3);
  for (int i = 0; i < n; ++i) {
    const double angle = 2 * std::numbers::pi * i / n;
    const double r = radius * (1.0 + wobble * std::cos(2 * angle));
    positions(i, 0) = r * std::cos(angle);
    positions(i, 1) = r * std::sin(angle);
  }
  return positions;
}

SnakeMaterial random_material(int n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> weight(0.1, 2.0);
  SnakeMaterial material;
  material.tension.resize(n);
  material.rigidity.resize(n);
  for (int i = 0; i < n; ++i) {
    material.tension[i] = weight(random);
    material.rigidity[i] = 1e-3 * weight(random);
  }
  return material;
}

TEST(Snake, ClosedStiffnessIsTheMatrixOfEquations1_8To1_11) {
  // Entry by entry, indices modulo N; every other entry zero. The products of weights and
  // powers of h are the same operations in both, so they agree to a few ulps (1e-13 relative).
  const int n = 12;
  const SnakeMaterial material = random_material(n, 11);
  const Snake snake(NodeChain(n, true), circle(n, 1.0), material);
  const Eigen::MatrixXd k(snake.scalar().stiffness);
  const double h = 1.0 / n;
  const auto w1 = [&](int i) { return material.tension[(i % n + n) % n]; };
  const auto w2 = [&](int i) { return material.rigidity[(i % n + n) % n]; };
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    const double a =
        (w1(i - 1) + w1(i)) / (h * h) + (w2(i - 1) + 4 * w2(i) + w2(i + 1)) / std::pow(h, 4);
    const double b = -w1(i) / (h * h) - 2 * (w2(i) + w2(i + 1)) / std::pow(h, 4);
    const double c = w2(i + 1) / std::pow(h, 4);
    expected(i, i) = a;
    expected(i, (i + 1) % n) = expected((i + 1) % n, i) = b;
    expected(i, (i + 2) % n) = expected((i + 2) % n, i) = c;
  }
  EXPECT_LE((k - expected).cwiseAbs().maxCoeff(), 1e-13 * expected.cwiseAbs().maxCoeff());
  // The corner entries of eq 1.8: (0, N-2) = c_{N-2}, (0, N-1) = b_{N-1}, (1, N-1) = c_{N-1}.
  EXPECT_DOUBLE_EQ(k(0, n - 2), w2(n - 1) / std::pow(h, 4));
  EXPECT_DOUBLE_EQ(k(0, n - 1), -w1(n - 1) / (h * h) - 2 * (w2(n - 1) + w2(0)) / std::pow(h, 4));
  EXPECT_DOUBLE_EQ(k(1, n - 1), w2(0) / std::pow(h, 4));
}

TEST(Snake, OpenStiffnessIsTheHessianOfTheDiscreteEnergy) {
  // E = (1/2) sum_{i<N-1} w1_i |u_{i+1} - u_i|^2 / h^2 + (1/2) sum_{0<i<N-1} w2_i |u_{i+1} - 2 u_i
  // + u_{i-1}|^2 / h^4 is quadratic, so u^T K u = 2 E(u) exactly up to round-off (1e-12 rel.).
  const int n = 9;
  const SnakeMaterial material = random_material(n, 5);
  const Snake snake(NodeChain(n, false), circle(n, 1.0), material);
  const Eigen::MatrixXd k(snake.scalar().stiffness);
  const double h = 1.0 / (n - 1);
  std::mt19937 random(2);
  std::normal_distribution<double> normal;
  Eigen::VectorXd u(n);
  for (int i = 0; i < n; ++i) {
    u[i] = normal(random);
  }
  double energy = 0.0;
  for (int i = 0; i + 1 < n; ++i) {
    energy += 0.5 * material.tension[i] * std::pow(u[i + 1] - u[i], 2) / (h * h);
  }
  for (int i = 1; i + 1 < n; ++i) {
    energy +=
        0.5 * material.rigidity[i] * std::pow(u[i + 1] - 2 * u[i] + u[i - 1], 2) / std::pow(h, 4);
  }
  EXPECT_NEAR(u.dot(k * u), 2 * energy, 1e-12 * energy);
  EXPECT_EQ((k - k.transpose()).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(k(0, n - 1), 0.0);  // no wrap-around for an open snake
}

TEST(Snake, ClosedSnakeUnderRadialPotentialConvergesToTheMinimumCircle) {
  // P = kappa (|x| - R)^2 has its minimum on the circle of radius R. Starting from a wobbly circle,
  // the damped snake becomes a circle of radius r = 2 kappa R / (2 kappa + lambda), lambda the
  // eigenvalue of K for the circle mode (tension and rigidity pull it slightly inside R); it
  // tends to R as w1, w2 -> 0. Every step reuses the single LDL^T factorization (eq 1.13).
  const int n = 32;
  const double big_r = 2.0;
  const double kappa = 50.0;
  SnakeMaterial material;
  material.damping_density = 8.0;
  material.constant_tension = 1e-3;
  material.constant_rigidity = 1e-7;
  const Snake snake(NodeChain(n, true), circle(n, 1.5 * big_r, 0.2), material);
  System system(snake);
  system.add_force(0, potential_force([&](const Eigen::Vector2d& x) {
                     return kappa * std::pow(x.norm() - big_r, 2);
                   }));
  Integrator integrator(IntegratorSettings{IntegratorScheme::kCentral});
  for (int s = 0; s < 4000; ++s) {
    integrator.step(system, 0.01);
  }
  EXPECT_EQ(integrator.factorization_count(), 1);
  const double theta = 2 * std::numbers::pi / n;
  const double mode = 2 - 2 * std::cos(theta);
  const double lambda = material.constant_tension * n * n * mode +
                        material.constant_rigidity * std::pow(n, 4) * mode * mode;
  const double expected = 2 * kappa * big_r / (2 * kappa + lambda);
  const NodePositions r = snake.positions(system.coordinates(0));
  // Radii converge to the equilibrium; 1e-6 covers the gradient's central differences (step
  // 1e-6: ~1e-9 relative) and the remaining transient (damped for 40 time units).
  EXPECT_LE((r.leftCols<2>().rowwise().norm().array() - expected).abs().maxCoeff(), 1e-6);
  EXPECT_LT(std::abs(expected - big_r), 0.01 * big_r);
  EXPECT_EQ(r.col(2).cwiseAbs().maxCoeff(), 0.0);  // planar forces keep it planar
}

TEST(Snake, SemiImplicitStepperIsTheCentralIntegrator) {
  // Both are Terzopoulos 2003, eq. 1.13 (the stepper solves for the increment, the integrator for
  // the acceleration): the trajectories agree to round-off (1e-10 over 300 steps of values ~1).
  const int n = 16;
  SnakeMaterial material = random_material(n, 9);
  material.damping_density = 0.5;
  const Snake snake(NodeChain(n, false), circle(n, 1.0, 0.1), material);
  System central_system(snake);
  central_system.add_force(
      0, potential_force([](const Eigen::Vector2d& x) { return 0.5 * x.squaredNorm(); }));
  System seed_system = central_system;
  Integrator integrator(IntegratorSettings{IntegratorScheme::kCentral});
  SemiImplicitStepper stepper;
  for (int s = 0; s < 300; ++s) {
    integrator.step(central_system, 0.002);
    stepper.step(seed_system, 0.002);
  }
  EXPECT_LE((central_system.coordinates() - seed_system.coordinates()).cwiseAbs().maxCoeff(),
            1e-10);
  EXPECT_GT((central_system.coordinates() - snake.initial_coordinates()).cwiseAbs().maxCoeff(),
            1e-3);  // it moved
}

TEST(Snake, ImagePotentialPullsTheSnakeOntoAnEdge) {
  // A bright disk of radius 10 pixels; -|grad(G_2 * I)| is lowest on its edge. A closed snake
  // started at radius 15 settles near radius 10 (within 1 pixel: the blur and the tension move
  // the minimum by a fraction of a pixel).
  Eigen::MatrixXd image = Eigen::MatrixXd::Zero(64, 64);
  for (int row = 0; row < 64; ++row) {
    for (int col = 0; col < 64; ++col) {
      image(row, col) = std::hypot(col - 32.0, row - 32.0) < 10.0 ? 1.0 : 0.0;
    }
  }
  const Potential potential = image_potential(image, 2.0, 20.0);
  const int n = 40;
  SnakeMaterial material;
  material.damping_density = 2.0;
  material.constant_tension = 1e-4;
  material.constant_rigidity = 1e-8;
  NodePositions start = circle(n, 13.0);
  start.col(0).array() += 32.0;
  start.col(1).array() += 32.0;
  const Snake snake(NodeChain(n, true), start, material);
  System system(snake);
  system.add_force(0, potential_force(potential, 1e-3));
  Integrator integrator(IntegratorSettings{IntegratorScheme::kCentral});
  for (int s = 0; s < 3000; ++s) {
    integrator.step(system, 0.05);
  }
  const NodePositions r = snake.positions(system.coordinates(0));
  const Eigen::ArrayXd radii =
      (r.leftCols<2>().rowwise() - Eigen::RowVector2d(32.0, 32.0)).rowwise().norm().array();
  EXPECT_NEAR(radii.mean(), 10.0, 1.0);
  EXPECT_LT(radii.maxCoeff() - radii.minCoeff(), 1.0);
}

TEST(Snake, BadInputNamesTheValue) {
  const auto message = [&](auto&& make) -> std::string {
    try {
      make();
    } catch (const Error& error) {
      return error.what();
    }
    return "no error";
  };
  SnakeMaterial negative;
  negative.constant_tension = -0.25;
  EXPECT_NE(message([&] { Snake(NodeChain(8, true), circle(8, 1), negative); }).find("-0.25"),
            std::string::npos);
  EXPECT_NE(message([] { NodeChain(3, true); }).find("3"), std::string::npos);
  NodePositions bad = circle(8, 1);
  bad(4, 0) = std::nan("");
  EXPECT_NE(message([&] { Snake(NodeChain(8, false), bad, SnakeMaterial{}); }).find("node 4"),
            std::string::npos);
  EXPECT_THROW(image_potential(Eigen::MatrixXd::Zero(1, 5), 1.0), Error);
  EXPECT_THROW(image_potential(Eigen::MatrixXd::Zero(5, 5), -1.0), Error);
}

}  // namespace
}  // namespace dnurbs
