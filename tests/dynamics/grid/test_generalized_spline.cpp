#include "dnurbs/dynamics/grid/generalized_spline.h"

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/spring.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/grid/snake.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/integrators/static_equilibrium.h"

namespace dnurbs {
namespace {

using Field = std::function<Eigen::Vector3d(const Eigen::Vector2d&)>;

// q of a chain (node i at s = i h) or a grid (node (i, j) at (i h, j h)) sampled from v.
Eigen::VectorXd sample_chain(const NodeChain& chain, const Field& v) {
  Eigen::VectorXd q(3 * chain.count());
  for (int i = 0; i < chain.count(); ++i) {
    q.segment<3>(3 * i) = v(Eigen::Vector2d(chain.parameter(i), 0.0));
  }
  return q;
}

Eigen::VectorXd sample_grid(const Grid& grid, const Field& v) {
  Eigen::VectorXd q(3 * grid.node_count());
  for (int k = 0; k < grid.node_count(); ++k) {
    q.segment<3>(3 * k) = v(grid.parameter(k));
  }
  return q;
}

NodePositions as_positions(const Eigen::VectorXd& q) {
  NodePositions positions(q.size() / 3, 3);
  for (Eigen::Index i = 0; i < positions.rows(); ++i) {
    positions.row(i) = q.segment<3>(3 * i).transpose();
  }
  return positions;
}

GeneralizedSplineMaterial order(int n) {
  GeneralizedSplineMaterial material;
  material.order = n;
  return material;
}

// The discrete energy 1/2 q^T K q of v sampled on a chain of `intervals` cells.
double chain_energy(int intervals, bool closed, int n, const Field& v) {
  const NodeChain chain(closed ? intervals : intervals + 1, closed);
  const Eigen::VectorXd q = sample_chain(chain, v);
  const GeneralizedSpline spline(chain, as_positions(q), order(n));
  return spline.potential_energy(q);
}

double grid_energy(int intervals, int n, const Field& v) {
  const Grid grid(intervals + 1, intervals + 1, 1.0 / intervals);
  const Eigen::VectorXd q = sample_grid(grid, v);
  const GeneralizedSpline spline(grid, as_positions(q), order(n));
  return spline.potential_energy(q);
}

// Errors at 32, 64 and 128 cells against `exact`; returns the orders log2(e_k / e_{k+1}).
std::vector<double> energy_orders(const std::function<double(int)>& energy, double exact,
                                  std::vector<double>& errors, int coarsest = 32) {
  errors.clear();
  for (int cells = coarsest; cells <= 4 * coarsest; cells *= 2) {
    errors.push_back(std::abs(energy(cells) - exact));
  }
  return {std::log2(errors[0] / errors[1]), std::log2(errors[1] / errors[2])};
}

// --- (a) energy of order n against its closed form ---------------------------------------------

TEST(GeneralizedSplineEnergy, ClosedChainCircleConvergesAtOrderTwo) {
  // v(s) = (cos 2 pi s, sin 2 pi s, 0): |v^(m)| = (2 pi)^m, so S_n = 1/2 sum_m (2 pi)^(2m)
  // (eq 1.17, w = 1). The m-th difference of the samples has modulus (2 sin(pi h)/h)^m, an
  // O(h^2) relative error: order 2.
  const Field circle = [](const Eigen::Vector2d& s) {
    const double angle = 2 * std::numbers::pi * s.x();
    return Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0);
  };
  for (int n = 1; n <= 3; ++n) {
    double exact = 0.0;
    for (int m = 1; m <= n; ++m) {
      exact += 0.5 * std::pow(2 * std::numbers::pi, 2 * m);
    }
    std::vector<double> errors;
    const std::vector<double> orders = energy_orders(
        [&](int cells) { return chain_energy(cells, true, n, circle); }, exact, errors);
    SCOPED_TRACE("n = " + std::to_string(n));
    EXPECT_LT(errors[2], 2e-3 * exact);
    for (const double p : orders) {
      EXPECT_NEAR(p, 2.0, 0.02);
    }
  }
}

TEST(GeneralizedSplineEnergy, OpenChainPolynomialConvergesAtOrderTwo) {
  // v(s) = (s^4, s^3, 0) on [0, 1]: int |v'|^2 = 16/7 + 9/5, int |v''|^2 = 144/5 + 12,
  // int |v'''|^2 = 192 + 36. Midpoint sums over the stencil centres with the end factors
  // (a + 1)/2: O(h^2) (the end strips are integrated to O(h^2) too).
  const Field quartic = [](const Eigen::Vector2d& s) {
    return Eigen::Vector3d(std::pow(s.x(), 4), std::pow(s.x(), 3), 0.0);
  };
  const double terms[3] = {16.0 / 7 + 9.0 / 5, 144.0 / 5 + 12.0, 192.0 + 36.0};
  double exact = 0.0;
  for (int n = 1; n <= 3; ++n) {
    exact += 0.5 * terms[n - 1];
    std::vector<double> errors;
    const std::vector<double> orders = energy_orders(
        [&](int cells) { return chain_energy(cells, false, n, quartic); }, exact, errors);
    SCOPED_TRACE("n = " + std::to_string(n));
    EXPECT_LT(errors[2], 1e-3 * exact);
    for (const double p : orders) {
      EXPECT_NEAR(p, 2.0, 0.1);
    }
  }
}

TEST(GeneralizedSplineEnergy, GridPolynomialConvergesAtOrderTwo) {
  // v(u, v) = (u^3 v^2 + u v, 0, 0) on [0, 1]^2. Its derivatives: v_u = 3u^2 v^2 + v,
  // v_v = 2u^3 v + u; v_uu = 6u v^2, v_uv = 6u^2 v + 1, v_vv = 2u^3; v_uuu = 6v^2, v_uuv = 12uv,
  // v_uvv = 6u^2, v_vvv = 0. Integrated exactly with the multinomials of eq 1.17:
  // m = 1: 741/350, m = 2: 482/35, m = 3: 384/5.
  const Field cubic = [](const Eigen::Vector2d& u) {
    return Eigen::Vector3d(std::pow(u.x(), 3) * u.y() * u.y() + u.x() * u.y(), 0.0, 0.0);
  };
  // At n = 2 the O(h^2) errors of the m = 1 and m = 2 terms have opposite signs (the sum is a
  // third of the m = 1 error), so the O(h^3) terms of the end strips still show in the measured
  // orders (1.87 from 32 to 64 cells, 1.94 from 64 to 128): 0.15 there, 0.1 on the finer pair.
  const double terms[3] = {741.0 / 350, 482.0 / 35, 384.0 / 5};
  double exact = 0.0;
  for (int n = 1; n <= 3; ++n) {
    exact += 0.5 * terms[n - 1];
    std::vector<double> errors;
    const std::vector<double> orders =
        energy_orders([&](int cells) { return grid_energy(cells, n, cubic); }, exact, errors, 32);
    SCOPED_TRACE("n = " + std::to_string(n));
    EXPECT_LT(errors[2], 1e-3 * exact);
    EXPECT_NEAR(orders[0], 2.0, 0.15);
    EXPECT_NEAR(orders[1], 2.0, 0.1);
  }
}

TEST(GeneralizedSplineEnergy, GridTrigonometricConvergesAtOrderTwo) {
  // v = (cos(a u + b v), 0, 0): every |d^j v|^2 with |j| = m is a^(2 j1) b^(2 j2) sin^2 (m odd) or
  // cos^2 (m even) of the phase, and sum_j m!/j! a^(2 j1) b^(2 j2) = (a^2 + b^2)^m. With
  // C = int int cos 2(a u + b v) = (cos 2a + cos 2b - cos(2a + 2b) - 1) / (4 a b):
  // int sin^2 = (1 - C)/2, int cos^2 = (1 + C)/2. From 32 cells on: at 16 the O(h^4) terms
  // still bend the measured order of n = 3 to 1.89.
  const double a = 1.3;
  const double b = 0.7;
  const Field wave = [&](const Eigen::Vector2d& u) {
    return Eigen::Vector3d(std::cos(a * u.x() + b * u.y()), 0.0, 0.0);
  };
  const double c =
      (std::cos(2 * a) + std::cos(2 * b) - std::cos(2 * a + 2 * b) - 1.0) / (4 * a * b);
  double exact = 0.0;
  for (int n = 1; n <= 3; ++n) {
    exact += 0.5 * std::pow(a * a + b * b, n) * (n % 2 == 1 ? (1 - c) / 2 : (1 + c) / 2);
    std::vector<double> errors;
    const std::vector<double> orders =
        energy_orders([&](int cells) { return grid_energy(cells, n, wave); }, exact, errors, 32);
    SCOPED_TRACE("n = " + std::to_string(n));
    EXPECT_LT(errors[2], 1e-3 * exact);
    for (const double p : orders) {
      EXPECT_NEAR(p, 2.0, 0.1);
    }
  }
}

// --- (b) the Euler-Lagrange operator with varying weights ----------------------------------------

// d^k/dx^k of sin(c x + phase).
double sine_derivative(double c, double phase, int k, double x) {
  return std::pow(c, k) * std::sin(c * x + phase + k * std::numbers::pi / 2);
}

double weight(const Eigen::Vector2d& u) {
  return 1.0 + u.x() / 2;
}

// max over the nodes with parameters in [1/4, 3/4] (per direction) of |(S_K x)_i / measure_i -
// expected_i|, x the x coordinates.
double interior_residual_error(const GeneralizedSpline& spline, const Eigen::VectorXd& q,
                               const std::function<double(const Eigen::Vector2d&)>& expected,
                               const std::vector<Eigen::Vector2d>& parameters) {
  const Eigen::VectorXd x = as_positions(q).col(0);
  const Eigen::VectorXd kx = spline.scalar().stiffness * x;
  double error = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const Eigen::Vector2d& u = parameters[static_cast<size_t>(i)];
    if (u.minCoeff() < 0.25 - 1e-12 || u.maxCoeff() > 0.75 + 1e-12) {
      continue;
    }
    error = std::max(error, std::abs(kx[i] / spline.node_measure()[i] - expected(u)));
  }
  return error;
}

TEST(GeneralizedSplineEulerLagrange, ChainWithVaryingWeightsConvergesAtOrderTwo) {
  // v = sin(3 s), w_m(s) = 1 + s/2 for every m <= n; with w linear,
  // d^m (w v^(m)) = w v^(2m) + m w' v^(2m-1), so sum_m (-1)^m Delta_w^m v (eqs 1.18-1.19) is
  // sum_m (-1)^m (w v^(2m) + (m/2) v^(2m-1)). The differences and the weights at the stencil
  // centres are O(h^2); rounding grows as eps |v| / h^(2n) (2.8e-3 for n = 3 at h = 1/64, well
  // below the truncation error there, 0.65 against |v^(6)| = 729).
  for (int n = 1; n <= 3; ++n) {
    std::vector<double> errors;
    for (int cells = 16; cells <= 64; cells *= 2) {
      const NodeChain chain(cells + 1, false);
      GeneralizedSplineMaterial material;
      material.order = n;
      for (int m = 1; m <= n; ++m) {
        material.terms.push_back(SplineTerm{m, 0, MaterialFunction(weight), {}});
      }
      const Eigen::VectorXd q = sample_chain(chain, [](const Eigen::Vector2d& s) {
        return Eigen::Vector3d(std::sin(3 * s.x()), 0.0, 0.0);
      });
      const GeneralizedSpline spline(chain, as_positions(q), material);
      std::vector<Eigen::Vector2d> parameters;
      parameters.reserve(static_cast<size_t>(chain.count()));
      for (int i = 0; i < chain.count(); ++i) {
        parameters.emplace_back(chain.parameter(i), 0.5);
      }
      errors.push_back(interior_residual_error(
          spline, q,
          [&](const Eigen::Vector2d& u) {
            double sum = 0.0;
            for (int m = 1; m <= n; ++m) {
              sum +=
                  (m % 2 == 0 ? 1.0 : -1.0) * (weight(u) * sine_derivative(3, 0, 2 * m, u.x()) +
                                               0.5 * m * sine_derivative(3, 0, 2 * m - 1, u.x()));
            }
            return sum;
          },
          parameters));
    }
    SCOPED_TRACE("n = " + std::to_string(n));
    EXPECT_LT(errors[2], 2e-3 * std::pow(3.0, 2 * n));  // relative to |v^(2n)| = 3^(2n)
    EXPECT_NEAR(std::log2(errors[0] / errors[1]), 2.0, 0.1);
    EXPECT_NEAR(std::log2(errors[1] / errors[2]), 2.0, 0.1);
  }
}

TEST(GeneralizedSplineEulerLagrange, GridWithVaryingWeightsConvergesAtOrderTwo) {
  // v = sin(a u) sin(b v + 1/2), w_j(u, v) = 1 + u/2 for every j. w depends on u alone, so
  // d^j (w d^j v) = w d^(2j) v + j_1 w' d^(2 j_1 - 1, 2 j_2) v, summed with (-1)^m m!/j!.
  const double a = 2.0;
  const double b = 1.5;
  const auto derivative = [&](int ku, int kv, const Eigen::Vector2d& u) {
    return sine_derivative(a, 0.0, ku, u.x()) * sine_derivative(b, 0.5, kv, u.y());
  };
  for (int n = 1; n <= 3; ++n) {
    std::vector<double> errors;
    for (int cells = 16; cells <= 64; cells *= 2) {
      const Grid grid(cells + 1, cells + 1, 1.0 / cells);
      GeneralizedSplineMaterial material;
      material.order = n;
      for (int m = 1; m <= n; ++m) {
        for (int jv = 0; jv <= m; ++jv) {
          material.terms.push_back(SplineTerm{m - jv, jv, MaterialFunction(weight), {}});
        }
      }
      const Eigen::VectorXd q = sample_grid(grid, [&](const Eigen::Vector2d& u) {
        return Eigen::Vector3d(derivative(0, 0, u), 0.0, 0.0);
      });
      const GeneralizedSpline spline(grid, as_positions(q), material);
      errors.push_back(interior_residual_error(
          spline, q,
          [&](const Eigen::Vector2d& u) {
            double sum = 0.0;
            for (int m = 1; m <= n; ++m) {
              for (int jv = 0; jv <= m; ++jv) {
                const int ju = m - jv;
                const double multinomial =
                    std::tgamma(m + 1) / (std::tgamma(ju + 1) * std::tgamma(jv + 1));
                double term = weight(u) * derivative(2 * ju, 2 * jv, u);
                if (ju > 0) {
                  term += 0.5 * ju * derivative(2 * ju - 1, 2 * jv, u);
                }
                sum += (m % 2 == 0 ? 1.0 : -1.0) * multinomial * term;
              }
            }
            return sum;
          },
          grid.node_parameters()));
    }
    SCOPED_TRACE("n = " + std::to_string(n));
    EXPECT_LT(errors[2], 2e-3 * std::pow(a * a + b * b, n));
    EXPECT_NEAR(std::log2(errors[0] / errors[1]), 2.0, 0.1);
    EXPECT_NEAR(std::log2(errors[1] / errors[2]), 2.0, 0.1);
  }
}

// --- (c) the snake of eqs 1.8-1.11 ---------------------------------------------------------------

GeneralizedSplineMaterial snake_terms(const Eigen::VectorXd& w1, const Eigen::VectorXd& w2) {
  GeneralizedSplineMaterial material;
  material.order = 2;
  material.terms = {SplineTerm{1, 0, 1.0, w1}, SplineTerm{2, 0, 1.0, w2}};
  return material;
}

double relative_difference(const SparseMatrix& a, const SparseMatrix& b) {
  return Eigen::MatrixXd(a - b).cwiseAbs().maxCoeff() / Eigen::MatrixXd(b).cwiseAbs().maxCoeff();
}

TEST(GeneralizedSplineSnake, ClosedStiffnessIsTheSnakeMatrixTimesH) {
  // K / h = eq 1.8 for the same per-node w1, w2; the sums of weights over powers of h are
  // formed in another order, so they agree to rounding (1e-14 relative).
  const int n = 14;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> draw(0.1, 2.0);
  SnakeMaterial snake_material;
  snake_material.tension = Eigen::VectorXd::NullaryExpr(n, [&] { return draw(random); });
  snake_material.rigidity = Eigen::VectorXd::NullaryExpr(n, [&] { return 1e-3 * draw(random); });
  const NodeChain chain(n, true);
  const NodePositions initial = NodePositions::Random(n, 3);
  const Snake snake(chain, initial, snake_material);
  const GeneralizedSpline spline(chain, initial,
                                 snake_terms(snake_material.tension, snake_material.rigidity));
  const double h = chain.spacing();
  EXPECT_LT(relative_difference(spline.scalar().stiffness / h, snake.scalar().stiffness), 1e-14);
  EXPECT_LT(relative_difference(spline.scalar().mass / h, snake.scalar().mass), 1e-15);
}

TEST(GeneralizedSplineSnake, OpenStiffnessMatchesWithTheEndRigidityScaled) {
  // Open: the end anchors 1 and N-2 of the second difference carry c = 3/2 here (header), 1 in
  // the snake; a snake with w2 there multiplied by 3/2 has K / h (to rounding, 1e-14).
  const int n = 11;
  std::mt19937 random(6);
  std::uniform_real_distribution<double> draw(0.1, 2.0);
  const Eigen::VectorXd w1 = Eigen::VectorXd::NullaryExpr(n, [&] { return draw(random); });
  const Eigen::VectorXd w2 = Eigen::VectorXd::NullaryExpr(n, [&] { return draw(random); });
  const NodeChain chain(n, false);
  const NodePositions initial = NodePositions::Random(n, 3);
  const GeneralizedSpline spline(chain, initial, snake_terms(w1, w2));
  SnakeMaterial snake_material;
  snake_material.tension = w1;
  snake_material.rigidity = w2;
  snake_material.rigidity[1] *= 1.5;
  snake_material.rigidity[n - 2] *= 1.5;
  const Snake snake(chain, initial, snake_material);
  const double h = chain.spacing();
  EXPECT_LT(relative_difference(spline.scalar().stiffness / h, snake.scalar().stiffness), 1e-14);
  // Without the scaling only the rows away from the ends agree exactly
  snake_material.rigidity = w2;
  const Snake plain(chain, initial, snake_material);
  const Eigen::MatrixXd difference =
      Eigen::MatrixXd(spline.scalar().stiffness / h - plain.scalar().stiffness);
  EXPECT_LT(difference.block(4, 0, n - 8, n).cwiseAbs().maxCoeff(),
            1e-14 * Eigen::MatrixXd(plain.scalar().stiffness).cwiseAbs().maxCoeff());
  EXPECT_GT(difference.row(0).cwiseAbs().maxCoeff(), 0.0);
}

TEST(GeneralizedSplineSnake, WeightFunctionsAreSampledAtTheStencilCentres) {
  // A function w(s): the snake's w1_i = w((i + 1/2) h) (forward difference) and w2_i = w(i h)
  // (central difference), wrapped at s = 1 for a closed chain.
  const int n = 10;
  const auto w = [](const Eigen::Vector2d& s) { return 1.0 + s.x() / 2; };
  const NodeChain chain(n, true);
  const double h = chain.spacing();
  GeneralizedSplineMaterial material;
  material.order = 2;
  material.terms = {SplineTerm{1, 0, MaterialFunction(w), {}},
                    SplineTerm{2, 0, MaterialFunction(w), {}}};
  SnakeMaterial snake_material;
  snake_material.tension.resize(n);
  snake_material.rigidity.resize(n);
  for (int i = 0; i < n; ++i) {
    snake_material.tension[i] = w(Eigen::Vector2d((i + 0.5) * h, 0.0));
    snake_material.rigidity[i] = w(Eigen::Vector2d(i * h, 0.0));
  }
  const NodePositions initial = NodePositions::Random(n, 3);
  const GeneralizedSpline spline(chain, initial, material);
  const Snake snake(chain, initial, snake_material);
  EXPECT_LT(relative_difference(spline.scalar().stiffness / h, snake.scalar().stiffness), 1e-14);
}

// --- (d) the massless flow (section 2.6) --------------------------------------------------------

NodePositions circle(int n, double radius) {
  NodePositions positions = NodePositions::Zero(n, 3);
  for (int i = 0; i < n; ++i) {
    const double angle = 2 * std::numbers::pi * i / n;
    positions(i, 0) = radius * std::cos(angle);
    positions(i, 1) = radius * std::sin(angle);
  }
  return positions;
}

GeneralizedSplineMaterial massless_membrane(double tension, double gamma) {
  GeneralizedSplineMaterial material = membrane_material(1, tension);
  material.mass_density = 0.0;
  material.damping_density = gamma;
  return material;
}

TEST(GeneralizedSplineMasslessFlow, ImplicitEulerShrinksACircleByBackwardEuler) {
  // gamma u_t = -K u (per unit length): the circle is the first Fourier mode, K u = lambda h u
  // with lambda = 4 w sin^2(pi/N) / h^2, and implicit Euler with M = 0 is backward Euler:
  // R_{k+1} = R_k / (1 + dt lambda / gamma), exact to rounding (1e-13 relative per step).
  const int n = 24;
  const double tension = 0.5;
  const double gamma = 2.0;
  const NodeChain chain(n, true);
  const double h = chain.spacing();
  const double lambda = 4 * tension * std::pow(std::sin(std::numbers::pi / n), 2) / (h * h);
  const GeneralizedSpline spline(chain, circle(n, 1.0), massless_membrane(tension, gamma));
  EXPECT_EQ(spline.scalar().mass.nonZeros(), 0);
  System system(spline);
  Integrator integrator(IntegratorSettings{IntegratorScheme::kImplicitEuler});
  const double dt = 0.01;
  double radius = 1.0;
  for (int k = 0; k < 50; ++k) {
    integrator.step(system, dt);
    radius /= 1.0 + dt * lambda / gamma;
    const NodePositions r = spline.positions(system.coordinates(0));
    EXPECT_LT((r - circle(n, radius)).cwiseAbs().maxCoeff(), 1e-13 * radius) << "step " << k;
  }
  EXPECT_EQ(integrator.factorization_count(), 1);
}

TEST(GeneralizedSplineMasslessFlow, RadiusConvergesToTheExponentialAtOrderOne) {
  // At T = 0.2 the backward-Euler radius (1 + dt lambda/gamma)^(-T/dt) tends to
  // exp(-lambda T / gamma) with the error (lambda/gamma)^2 T dt / 2 exp(...): order 1 in dt.
  const int n = 24;
  const double tension = 0.5;
  const double gamma = 2.0;
  const double end = 0.2;
  const NodeChain chain(n, true);
  const double h = chain.spacing();
  const double lambda = 4 * tension * std::pow(std::sin(std::numbers::pi / n), 2) / (h * h);
  const double exact = std::exp(-lambda * end / gamma);
  std::vector<double> errors;
  for (int steps = 20; steps <= 80; steps *= 2) {
    const GeneralizedSpline spline(chain, circle(n, 1.0), massless_membrane(tension, gamma));
    System system(spline);
    Integrator integrator(IntegratorSettings{IntegratorScheme::kImplicitEuler});
    for (int k = 0; k < steps; ++k) {
      integrator.step(system, end / steps);
    }
    const NodePositions r = spline.positions(system.coordinates(0));
    errors.push_back(std::abs(r.row(0).norm() - exact));
  }
  // The leading term predicts the finest error to 1% (the next is O(dt^2), 0.5% of it here)
  const double leading = std::pow(lambda / gamma, 2) * end * (end / 80) / 2 * exact;
  EXPECT_NEAR(errors[2], leading, 0.01 * leading);
  EXPECT_NEAR(std::log2(errors[0] / errors[1]), 1.0, 0.1);
  EXPECT_NEAR(std::log2(errors[1] / errors[2]), 1.0, 0.05);
}

TEST(GeneralizedSplineMasslessFlow, SecondOrderSchemesRefuseZeroMass) {
  const GeneralizedSpline spline(NodeChain(8, true), circle(8, 1.0), massless_membrane(1.0, 1.0));
  for (const IntegratorScheme scheme : {IntegratorScheme::kCentral, IntegratorScheme::kNewmark}) {
    System system(spline);
    Integrator integrator(IntegratorSettings{scheme});
    try {
      integrator.step(system, 0.01);
      ADD_FAILURE() << "no error for " << to_string(scheme);
    } catch (const Error& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(std::string(to_string(scheme))), std::string::npos) << message;
      EXPECT_NE(message.find("mass matrix is zero"), std::string::npos) << message;
    }
  }
}

// --- the Model contract: pins, mouse springs, integrators ----------------------------------------

TEST(GeneralizedSplineModel, ClampedThinPlateSettlesUnderAMouseSpring) {
  // A thin plate under tension (eq 1.20) with its border pinned, pulled up at its centre by a
  // mouse spring: the damped massless flow (implicit Euler) reaches the static equilibrium
  // (K + k L^T L) q = k L^T target. After 400 steps of dt = 0.05 the slowest mode has decayed by
  // exp(-lambda_min t / gamma) < 1e-12 (lambda_min ~ 2 pi^2 w10 + 4 pi^4 w20 = 59; gamma = 1).
  const Grid grid(9, 9, 1.0 / 8);
  GeneralizedSplineMaterial material = thin_plate_material(1.0, 1.0, 0.1, 0.1, 0.1);
  material.mass_density = 0.0;
  material.damping_density = 1.0;
  const GeneralizedSpline plate(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()), material);
  System system(plate);
  system.fix_border(0);
  system.add_spring(0, mouse_spring(
                           Eigen::Vector2d(0.5, 0.5),
                           [](double /*t*/) { return Eigen::Vector3d(0.5, 0.5, 0.2); }, 50.0));
  System reference = system;
  solve_static_equilibrium(reference);
  Integrator integrator(IntegratorSettings{IntegratorScheme::kImplicitEuler});
  for (int k = 0; k < 400; ++k) {
    integrator.step(system, 0.05);
  }
  const NodePositions settled = plate.positions(system.coordinates(0));
  const NodePositions expected = plate.positions(reference.coordinates(0));
  EXPECT_LT((settled - expected).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_GT(expected(grid.index(4, 4), 2), 0.05);  // pulled up
  for (const int k : grid.border_nodes()) {
    EXPECT_EQ(settled.row(k), flat_grid_positions(grid, Eigen::Vector3d::Zero()).row(k));
  }
}

// --- (e) errors ----------------------------------------------------------------------------------

void expect_error(const std::function<void()>& build, const std::string& fragment) {
  try {
    build();
    ADD_FAILURE() << "no error; expected one naming '" << fragment << "'";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
  }
}

TEST(GeneralizedSplineErrors, BadMaterialsAndPositionsAreRefusedByName) {
  const NodeChain chain(8, false);
  const NodePositions initial = NodePositions::Zero(8, 3);
  const auto build = [&](const GeneralizedSplineMaterial& material) {
    return [&chain, &initial, material] { GeneralizedSpline(chain, initial, material); };
  };
  expect_error(build(order(0)), "order n = 0");
  GeneralizedSplineMaterial negative = order(2);
  negative.terms = {SplineTerm{2, 0, 1.0, Eigen::VectorXd::Constant(8, 1.0)}};
  negative.terms[0].node_weights[3] = -1.0;
  expect_error(build(negative), "w_(2,0) at node 3 is -1");
  GeneralizedSplineMaterial not_finite = order(1);
  not_finite.terms = {
      SplineTerm{1, 0, MaterialFunction([](const Eigen::Vector2d&) { return std::nan(""); }), {}}};
  expect_error(build(not_finite), "w_(1,0)");
  GeneralizedSplineMaterial infinite = order(1);
  infinite.terms = {
      SplineTerm{1, 0, 1.0, Eigen::VectorXd::Constant(8, std::numeric_limits<double>::infinity())}};
  expect_error(build(infinite), "w_(1,0) at node 0 is inf");
  GeneralizedSplineMaterial sized = order(1);
  sized.terms = {SplineTerm{1, 0, 1.0, Eigen::VectorXd::Ones(7)}};
  expect_error(build(sized), "7 node weights for 8 nodes");
  GeneralizedSplineMaterial too_high = order(2);
  too_high.terms = {SplineTerm{3, 0, 1.0, {}}};
  expect_error(build(too_high), "|j| = 3");
  GeneralizedSplineMaterial along_v = order(2);
  along_v.terms = {SplineTerm{1, 1, 1.0, {}}};
  expect_error(build(along_v), "along v on a chain");
  GeneralizedSplineMaterial twice = order(1);
  twice.terms = {SplineTerm{1, 0, 1.0, {}}, SplineTerm{1, 0, 2.0, {}}};
  expect_error(build(twice), "listed twice");
  expect_error(build(order(8)), "needs at least 9 nodes along u, not 8");
  expect_error([] { GeneralizedSpline(Grid(3, 5, 0.5), NodePositions::Zero(15, 3), order(3)); },
               "needs at least 4 nodes along u, not 3");
  expect_error([] { GeneralizedSpline(Grid(5, 3, 0.5), NodePositions::Zero(15, 3), order(3)); },
               "needs at least 4 nodes along v, not 3");
  GeneralizedSplineMaterial still = order(1);
  still.mass_density = 0.0;
  expect_error(build(still), "mu = 0 needs a damping density gamma > 0");
  GeneralizedSplineMaterial negative_mass = order(1);
  negative_mass.mass_density = -1.0;
  expect_error(build(negative_mass), "mass density mu = -1");
  NodePositions nan_positions = initial;
  nan_positions(5, 1) = std::nan("");
  expect_error([&] { GeneralizedSpline(chain, nan_positions, order(1)); }, "node 5 is not finite");
  expect_error([&] { GeneralizedSpline(chain, NodePositions::Zero(7, 3), order(1)); },
               "7 rows for 8 nodes");
  NodePositions nan_grid = NodePositions::Zero(16, 3);
  nan_grid(6, 2) = std::nan("");
  expect_error([&] { GeneralizedSpline(Grid(4, 4, 0.5), nan_grid, order(1)); },
               "generalized spline initial positions");
  expect_error([] { membrane_material(3, 1.0); }, "dimension p = 3");
}

}  // namespace
}  // namespace dnurbs
