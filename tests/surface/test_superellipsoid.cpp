#include "dnurbs/surface/superellipsoid.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "tests/common/superquadric_test_support.h"

namespace dnurbs {
namespace {

using testing::all_finite;
using testing::central_difference;
using testing::kExponents;
using testing::kGenericParameters;
using testing::kSpecialAngles;

constexpr double kPi = std::numbers::pi;

SuperellipsoidParameters sample_parameters(double e1, double e2) {
  SuperellipsoidParameters parameters;
  parameters << 1.3, 0.8, 1.2, 1.5, e1, e2;
  return parameters;
}

TEST(Superellipsoid, TangentsMatchCentralDifferences) {
  const double step = 1e-6;
  for (const double e1 : kExponents) {
    for (const double e2 : kExponents) {
      const SuperellipsoidParameters parameters = sample_parameters(e1, e2);
      for (const auto& uv : kGenericParameters) {
        const double u = uv[0];
        const double v = uv[1];
        const SuperellipsoidEvaluation evaluation = evaluate_superellipsoid(parameters, u, v);
        const Eigen::Vector3d fd_u = central_difference(
            [&](double x) { return superellipsoid_point(parameters, x, v); }, u, step);
        const Eigen::Vector3d fd_v = central_difference(
            [&](double x) { return superellipsoid_point(parameters, u, x); }, v, step);
        // Truncation h^2 |e'''|/6 with |e'''| < 1e3 for e = 0.1 at |cos|, |sin| >= 0.2 (1e-10)
        // plus rounding 1e-16 |e| / h (1e-10): relative to the tangent's size.
        const double tolerance = 1e-8 * (1.0 + evaluation.d_u.norm() + evaluation.d_v.norm());
        EXPECT_LT((evaluation.d_u - fd_u).norm(), tolerance) << e1 << " " << e2 << " " << u;
        EXPECT_LT((evaluation.d_v - fd_v).norm(), tolerance) << e1 << " " << e2 << " " << v;
      }
    }
  }
}

TEST(Superellipsoid, ParameterJacobianMatchesCentralDifferences) {
  const double step = 1e-6;
  for (const double e1 : kExponents) {
    for (const double e2 : kExponents) {
      const SuperellipsoidParameters parameters = sample_parameters(e1, e2);
      for (const auto& uv : kGenericParameters) {
        const double u = uv[0];
        const double v = uv[1];
        const SuperellipsoidEvaluation evaluation = evaluate_superellipsoid(parameters, u, v);
        for (int k = 0; k < kSuperellipsoidParameterCount; ++k) {
          const Eigen::Vector3d fd = central_difference(
              [&](double x) {
                SuperellipsoidParameters shifted = parameters;
                shifted[k] = x;
                return superellipsoid_point(shifted, u, v);
              },
              parameters[k], step);
          // e is linear in a, a1..a3 (only rounding, 1e-10); smooth in e1, e2 with third
          // derivative |x|^e ln^3|x| < 5 (truncation 1e-12).
          EXPECT_LT((evaluation.jacobian.col(k) - fd).norm(), 1e-8)
              << "parameter " << k << " e " << e1 << " " << e2 << " at " << u << " " << v;
        }
      }
    }
  }
}

TEST(Superellipsoid, JacobianRateMatchesCentralDifferencesOfTheJacobian) {
  const double step = 1e-6;
  SuperellipsoidParameters parameters_dot;
  parameters_dot << 0.2, -0.3, 0.25, 0.4, -0.35, 0.3;
  for (const double e1 : kExponents) {
    for (const double e2 : kExponents) {
      const SuperellipsoidParameters parameters = sample_parameters(e1, e2);
      for (const auto& uv : kGenericParameters) {
        const double u = uv[0];
        const double v = uv[1];
        const auto analytic = superellipsoid_jacobian_rate(parameters, u, v, parameters_dot);
        const auto jacobian_at = [&](double t) {
          return evaluate_superellipsoid((parameters + t * parameters_dot).eval(), u, v).jacobian;
        };
        const Eigen::Matrix<double, 3, kSuperellipsoidParameterCount> fd =
            (jacobian_at(step) - jacobian_at(-step)) / (2 * step);
        // Third derivatives |x|^e ln^3|x| < 5: truncation 1e-12, rounding 1e-10.
        EXPECT_LT((analytic - fd).norm(), 1e-8) << e1 << " " << e2 << " " << u << " " << v;
      }
    }
  }
}

TEST(Superellipsoid, IsFiniteWhereCosineOrSineVanish) {
  for (const double e1 : kExponents) {
    for (const double e2 : kExponents) {
      const SuperellipsoidParameters parameters = sample_parameters(e1, e2);
      for (const double u : kSpecialAngles) {
        if (std::abs(u) > kPi / 2) {
          continue;  // u lives in [-pi/2, pi/2]
        }
        for (const double v : kSpecialAngles) {
          const SuperellipsoidEvaluation evaluation = evaluate_superellipsoid(parameters, u, v);
          EXPECT_TRUE(all_finite(evaluation.point)) << e1 << " " << e2 << " " << u << " " << v;
          EXPECT_TRUE(all_finite(evaluation.d_u)) << e1 << " " << e2 << " " << u << " " << v;
          EXPECT_TRUE(all_finite(evaluation.d_v)) << e1 << " " << e2 << " " << u << " " << v;
          EXPECT_TRUE(all_finite(evaluation.jacobian)) << e1 << " " << e2 << " " << u << " " << v;
        }
      }
    }
  }
}

TEST(Superellipsoid, PolesAreSinglePointsOnTheZAxis) {
  for (const double e1 : kExponents) {
    const SuperellipsoidParameters parameters = sample_parameters(e1, 0.7);
    for (const double v : {-kPi, -1.0, 0.0, 2.0}) {
      // The snapped zero of cos(pi/2) makes x and y exactly 0.
      EXPECT_EQ(superellipsoid_point(parameters, kPi / 2, v), Eigen::Vector3d(0, 0, 1.3 * 1.5));
      EXPECT_EQ(superellipsoid_point(parameters, -kPi / 2, v), Eigen::Vector3d(0, 0, -1.3 * 1.5));
    }
  }
}

TEST(Superellipsoid, SphereCaseLiesOnTheSphere) {
  const double radius = 2.5;
  const SuperellipsoidParameters sphere = sphere_superellipsoid_parameters(radius);
  double worst = 0.0;
  for (int i = 0; i <= 24; ++i) {
    const double u = -kPi / 2 + i * kPi / 24;
    for (int j = 0; j <= 48; ++j) {
      const double v = -kPi + j * kPi / 24;
      worst = std::max(worst, std::abs(superellipsoid_point(sphere, u, v).norm() - radius));
    }
  }
  // cos and sin are correctly rounded and products and the norm add a few ulps of 2.5 (4e-16).
  EXPECT_LT(worst, 1e-14);
}

TEST(Superellipsoid, SatisfiesItsInsideOutsideFunction) {
  double worst = 0.0;
  for (const double e1 : kExponents) {
    for (const double e2 : kExponents) {
      const SuperellipsoidParameters parameters = sample_parameters(e1, e2);
      for (int i = 0; i <= 12; ++i) {
        const double u = -kPi / 2 + i * kPi / 12;
        for (int j = 0; j <= 24; ++j) {
          const double v = -kPi + j * kPi / 12;
          const double f =
              superellipsoid_inside_outside(parameters, superellipsoid_point(parameters, u, v));
          worst = std::max(worst, std::abs(f - 1.0));
        }
      }
    }
  }
  // F raises coordinates to powers up to 2/0.1 = 20 and back by e2/e1 up to 40: relative
  // rounding of 1e-16 in a coordinate grows to about 40 * 20 * 1e-16 = 1e-13 at worst.
  EXPECT_LT(worst, 1e-12);
  std::cout << "worst |F - 1| over the exponent grid: " << worst << "\n";
}

TEST(Superellipsoid, InsideOutsideFunctionSeparatesInsideFromOutside) {
  const SuperellipsoidParameters parameters = sample_parameters(0.5, 2.0);
  const Eigen::Vector3d surface = superellipsoid_point(parameters, 0.4, 1.1);
  EXPECT_LT(superellipsoid_inside_outside(parameters, 0.9 * surface), 1.0);
  EXPECT_GT(superellipsoid_inside_outside(parameters, 1.1 * surface), 1.0);
}

TEST(Superellipsoid, RejectsNonPositiveOrNonFiniteParametersNamingThem) {
  const SuperellipsoidParameters good = sample_parameters(1.0, 1.0);
  EXPECT_NO_THROW(validate_superellipsoid_parameters(good));
  const std::pair<int, std::string> cases[] = {
      {SuperellipsoidParameter::kScale, "scale a"},
      {SuperellipsoidParameter::kAspect2, "aspect a2"},
      {SuperellipsoidParameter::kSquareness1, "squareness e1"}};
  for (const auto& [index, name] : cases) {
    for (const double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
      SuperellipsoidParameters parameters = good;
      parameters[index] = bad;
      try {
        validate_superellipsoid_parameters(parameters);
        ADD_FAILURE() << name << " = " << bad << " accepted";
      } catch (const Error& error) {
        EXPECT_NE(std::string(error.what()).find(name), std::string::npos) << error.what();
      }
    }
  }
}

}  // namespace
}  // namespace dnurbs
