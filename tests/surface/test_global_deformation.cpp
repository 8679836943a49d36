#include "dnurbs/surface/global_deformation.h"

#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/surface/deformable_superquadric_shape.h"
#include "dnurbs/surface/signed_power.h"
#include "tests/common/superquadric_test_support.h"

namespace dnurbs {
namespace {

using testing::all_finite;
using testing::central_difference;
using testing::kExponents;
using testing::kGenericParameters;
using testing::kSpecialAngles;

constexpr double kPi = std::numbers::pi;
using Q = SuperquadricShapeParameter;

/// Points at which the deformations are checked: off-axis, both signs of z.
const std::array<Eigen::Vector3d, 4> sample_points = {
    Eigen::Vector3d(0.6, -0.4, 0.9), Eigen::Vector3d(-1.1, 0.3, -1.4),
    Eigen::Vector3d(0.2, 0.8, 0.1), Eigen::Vector3d(-0.5, -0.7, 1.7)};
constexpr double kHalfHeight = 1.9;

/// Every deformation active with moderate values.
GlobalDeformationParameters sample_deformation() {
  GlobalDeformationParameters parameters;
  parameters << 0.3, -0.4, 0.25, 0.35, 0.8, 0.9, 0.15, -0.2;
  return parameters;
}

SuperquadricShapeParameters sample_shape_parameters(double e1, double e2) {
  SuperellipsoidParameters superellipsoid;
  superellipsoid << 1.3, 0.8, 1.2, 1.5, e1, e2;
  return DeformableSuperquadricShape::combine(superellipsoid, sample_deformation());
}

/// Checks one step's d_point, d_parameters and d_half_height against central differences of
/// its point; `evaluate(p, theta, h)` returns the step.
template <int K, typename Step>
void expect_step_derivatives(const Step& evaluate, const Eigen::Matrix<double, K, 1>& theta,
                             const std::string& name) {
  const double step = 1e-6;
  // The steps are trigonometric or polynomial in every argument with O(1) third derivatives at
  // these O(1) points: truncation 1e-12, rounding 1e-16/h = 1e-10.
  const double tolerance = 1e-9;
  for (const Eigen::Vector3d& p : sample_points) {
    const auto analytic = evaluate(p, theta, kHalfHeight);
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d fd = central_difference(
          [&](double x) {
            Eigen::Vector3d shifted = p;
            shifted[c] = x;
            return evaluate(shifted, theta, kHalfHeight).point;
          },
          p[c], step);
      EXPECT_LT((analytic.d_point.col(c) - fd).norm(), tolerance) << name << " d/dp" << c;
    }
    for (int k = 0; k < K; ++k) {
      const Eigen::Vector3d fd = central_difference(
          [&](double x) {
            Eigen::Matrix<double, K, 1> shifted = theta;
            shifted[k] = x;
            return evaluate(p, shifted, kHalfHeight).point;
          },
          theta[k], step);
      EXPECT_LT((analytic.d_parameters.col(k) - fd).norm(), tolerance) << name << " param " << k;
    }
    const Eigen::Vector3d fd_h = central_difference(
        [&](double x) { return evaluate(p, theta, x).point; }, kHalfHeight, step);
    EXPECT_LT((analytic.d_half_height - fd_h).norm(), tolerance) << name << " d/dh";
  }
}

TEST(GlobalDeformation, TaperDerivativesMatchCentralDifferences) {
  expect_step_derivatives<2>([](const Eigen::Vector3d& p, const Eigen::Vector2d& t,
                                double h) { return taper(p, t[0], t[1], h); },
                             Eigen::Vector2d(0.3, -0.4), "taper");
}

TEST(GlobalDeformation, BendDerivativesMatchCentralDifferences) {
  expect_step_derivatives<3>([](const Eigen::Vector3d& p, const Eigen::Vector3d& b,
                                double h) { return bend(p, b[0], b[1], b[2], h); },
                             Eigen::Vector3d(0.25, 0.35, 0.8), "bend");
}

TEST(GlobalDeformation, TwistDerivativesMatchCentralDifferences) {
  expect_step_derivatives<1>([](const Eigen::Vector3d& p, const Eigen::Matrix<double, 1, 1>& tau,
                                double h) { return twist(p, tau[0], h); },
                             Eigen::Matrix<double, 1, 1>(0.9), "twist");
}

TEST(GlobalDeformation, ShearDerivativesMatchCentralDifferences) {
  expect_step_derivatives<2>([](const Eigen::Vector3d& p, const Eigen::Vector2d& s,
                                double) { return shear(p, s[0], s[1]); },
                             Eigen::Vector2d(0.15, -0.2), "shear");
}

TEST(GlobalDeformation, CompositeDerivativesMatchCentralDifferences) {
  expect_step_derivatives<kGlobalDeformationParameterCount>(
      [](const Eigen::Vector3d& p, const GlobalDeformationParameters& theta, double h) {
        return apply_global_deformation(theta, h, p);
      },
      sample_deformation(), "composite");
}

TEST(GlobalDeformation, DisabledStepsAreTheIdentityExactly) {
  for (const Eigen::Vector3d& p : sample_points) {
    EXPECT_EQ(taper(p, 0, 0, kHalfHeight).point, p);
    EXPECT_EQ(taper(p, 0, 0, kHalfHeight).d_point, Eigen::Matrix3d::Identity());
    // Zero amplitude disables bending whatever its offset and frequency.
    EXPECT_EQ(bend(p, 0, 0.4, 1.3, kHalfHeight).point, p);
    EXPECT_EQ(bend(p, 0, 0.4, 1.3, kHalfHeight).d_point, Eigen::Matrix3d::Identity());
    EXPECT_EQ(twist(p, 0, kHalfHeight).point, p);
    EXPECT_EQ(twist(p, 0, kHalfHeight).d_point, Eigen::Matrix3d::Identity());
    EXPECT_EQ(shear(p, 0, 0).point, p);
    const auto total =
        apply_global_deformation(GlobalDeformationParameters::Zero(), kHalfHeight, p);
    EXPECT_EQ(total.point, p);
    EXPECT_EQ(total.d_point, Eigen::Matrix3d::Identity());
    EXPECT_EQ(total.d_half_height, Eigen::Vector3d::Zero());
  }
}

TEST(GlobalDeformation, TaperAndBendFollowTheDesignFormula) {
  // DESIGN.md: s = [(t1 z/h + 1) x + b1 cos((z + b2)/h pi b3), (t2 z/h + 1) y, z].
  GlobalDeformationParameters parameters = GlobalDeformationParameters::Zero();
  parameters.head<5>() << 0.3, -0.4, 0.25, 0.35, 0.8;
  const Eigen::Vector3d p(0.6, -0.4, 0.9);
  const double h = kHalfHeight;
  const Eigen::Vector3d expected(
      (0.3 * p.z() / h + 1) * p.x() + 0.25 * std::cos((p.z() + 0.35) / h * kPi * 0.8),
      (-0.4 * p.z() / h + 1) * p.y(), p.z());
  // Same operations in a different order: a few ulps.
  EXPECT_LT((apply_global_deformation(parameters, h, p).point - expected).norm(), 1e-15);
}

TEST(GlobalDeformation, TwistRotatesByTauTimesNormalizedHeight) {
  const Eigen::Vector3d p(0.6, -0.4, 0.9);
  const auto twisted = twist(p, 0.9, kHalfHeight);
  const double angle = 0.9 * p.z() / kHalfHeight;
  // Rotation keeps the radius and turns the polar angle: rounding only.
  EXPECT_NEAR(twisted.point.head<2>().norm(), p.head<2>().norm(), 1e-15);
  EXPECT_NEAR(std::atan2(twisted.point.y(), twisted.point.x()) - std::atan2(p.y(), p.x()), angle,
              1e-15);
}

TEST(GlobalDeformation, RejectsNonFiniteParametersNamingThem) {
  GlobalDeformationParameters parameters = sample_deformation();
  parameters[GlobalDeformationParameter::kTwist] = std::nan("");
  try {
    validate_global_deformation_parameters(parameters);
    ADD_FAILURE() << "NaN twist accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("twist tau"), std::string::npos) << error.what();
  }
}

/// Checks a step's rates against central differences in time of its value and derivatives
/// along the motion: evaluate(p + t p_dot, theta + t theta_dot, h + t h_dot) at t = 0.
template <int K, typename Step, typename Rate>
void expect_step_rates(const Step& evaluate, const Rate& evaluate_rate,
                       const Eigen::Matrix<double, K, 1>& theta, const std::string& name) {
  const double step = 1e-6;
  DeformationMotion<K> motion;
  motion.point << 0.3, -0.5, 0.7;
  for (int k = 0; k < K; ++k) {
    motion.parameters[k] = 0.4 - 0.15 * k;
  }
  motion.half_height = -0.6;
  for (const Eigen::Vector3d& p : sample_points) {
    const auto at = [&](double t) {
      return evaluate((p + t * motion.point).eval(), (theta + t * motion.parameters).eval(),
                      kHalfHeight + t * motion.half_height);
    };
    const auto plus = at(step);
    const auto minus = at(-step);
    const auto rate = evaluate_rate(p, theta, kHalfHeight, motion);
    // Second derivatives of smooth O(1) functions: truncation 1e-12, rounding 1e-10.
    const double tolerance = 1e-9;
    EXPECT_LT((rate.point - (plus.point - minus.point) / (2 * step)).norm(), tolerance) << name;
    EXPECT_LT((rate.d_point - (plus.d_point - minus.d_point) / (2 * step)).norm(), tolerance)
        << name;
    EXPECT_LT((rate.d_parameters - (plus.d_parameters - minus.d_parameters) / (2 * step)).norm(),
              tolerance)
        << name;
    EXPECT_LT((rate.d_half_height - (plus.d_half_height - minus.d_half_height) / (2 * step)).norm(),
              tolerance)
        << name;
  }
}

TEST(GlobalDeformation, StepRatesMatchCentralDifferencesOfTheDerivatives) {
  expect_step_rates<2>(
      [](const Eigen::Vector3d& p, const Eigen::Vector2d& t, double h) {
        return taper(p, t[0], t[1], h);
      },
      [](const Eigen::Vector3d& p, const Eigen::Vector2d& t, double h,
         const DeformationMotion<2>& m) { return taper_rate(p, t[0], t[1], h, m); },
      Eigen::Vector2d(0.3, -0.4), "taper");
  expect_step_rates<3>(
      [](const Eigen::Vector3d& p, const Eigen::Vector3d& b, double h) {
        return bend(p, b[0], b[1], b[2], h);
      },
      [](const Eigen::Vector3d& p, const Eigen::Vector3d& b, double h,
         const DeformationMotion<3>& m) { return bend_rate(p, b[0], b[1], b[2], h, m); },
      Eigen::Vector3d(0.25, 0.35, 0.8), "bend");
  expect_step_rates<1>(
      [](const Eigen::Vector3d& p, const Eigen::Matrix<double, 1, 1>& tau, double h) {
        return twist(p, tau[0], h);
      },
      [](const Eigen::Vector3d& p, const Eigen::Matrix<double, 1, 1>& tau, double h,
         const DeformationMotion<1>& m) { return twist_rate(p, tau[0], h, m); },
      Eigen::Matrix<double, 1, 1>(0.9), "twist");
  expect_step_rates<2>([](const Eigen::Vector3d& p, const Eigen::Vector2d& s,
                          double) { return shear(p, s[0], s[1]); },
                       [](const Eigen::Vector3d& p, const Eigen::Vector2d& s, double,
                          const DeformationMotion<2>& m) { return shear_rate(p, s[0], s[1], m); },
                       Eigen::Vector2d(0.15, -0.2), "shear");
}

TEST(GlobalDeformation, CompositeRatesMatchCentralDifferencesOfTheDerivatives) {
  expect_step_rates<kGlobalDeformationParameterCount>(
      [](const Eigen::Vector3d& p, const GlobalDeformationParameters& theta, double h) {
        return apply_global_deformation(theta, h, p);
      },
      [](const Eigen::Vector3d& p, const GlobalDeformationParameters& theta, double h,
         const DeformationMotion<kGlobalDeformationParameterCount>& m) {
        const GlobalDeformationWithRate both = apply_global_deformation_with_rate(theta, h, p, m);
        // The value part is apply_global_deformation itself.
        const auto plain = apply_global_deformation(theta, h, p);
        EXPECT_EQ(both.value.point, plain.point);
        EXPECT_EQ(both.value.d_parameters, plain.d_parameters);
        return both.rate;
      },
      sample_deformation(), "composite");
}

// --- The deformable superquadric's reference shape s = T(e) --------------------------------

TEST(DeformableSuperquadricShape, TangentsMatchCentralDifferences) {
  const double step = 1e-6;
  for (const double e1 : kExponents) {
    for (const double e2 : kExponents) {
      const DeformableSuperquadricShape shape(sample_shape_parameters(e1, e2));
      for (const auto& uv : kGenericParameters) {
        const double u = uv[0];
        const double v = uv[1];
        const SuperquadricShapeEvaluation s = shape.evaluate(u, v);
        const Eigen::Vector3d fd_u =
            central_difference([&](double x) { return shape.point(x, v); }, u, step);
        const Eigen::Vector3d fd_v =
            central_difference([&](double x) { return shape.point(u, x); }, v, step);
        // As for the superellipsoid: truncation and rounding near 1e-10, relative to size.
        const double tolerance = 1e-8 * (1.0 + s.d_u.norm() + s.d_v.norm());
        EXPECT_LT((s.d_u - fd_u).norm(), tolerance) << e1 << " " << e2 << " " << u << " " << v;
        EXPECT_LT((s.d_v - fd_v).norm(), tolerance) << e1 << " " << e2 << " " << u << " " << v;
      }
    }
  }
}

TEST(DeformableSuperquadricShape, JacobianMatchesCentralDifferencesForAllFourteenParameters) {
  const double step = 1e-6;
  double worst = 0.0;
  for (const double e1 : kExponents) {
    for (const double e2 : kExponents) {
      const SuperquadricShapeParameters q_s = sample_shape_parameters(e1, e2);
      const DeformableSuperquadricShape shape(q_s);
      for (const auto& uv : kGenericParameters) {
        const double u = uv[0];
        const double v = uv[1];
        const SuperquadricShapeEvaluation s = shape.evaluate(u, v);
        for (int k = 0; k < kSuperquadricShapeParameterCount; ++k) {
          const Eigen::Vector3d fd = central_difference(
              [&](double x) {
                SuperquadricShapeParameters shifted = q_s;
                shifted[k] = x;
                return DeformableSuperquadricShape(shifted).point(u, v);
              },
              q_s[k], step);
          const double error = (s.jacobian.col(k) - fd).norm();
          worst = std::max(worst, error);
          // Smooth in every parameter with O(1) third derivatives here (|x|^e ln^3|x| < 5 for
          // the exponents): truncation 1e-12, rounding 1e-16 |s| / h = 1e-10.
          EXPECT_LT(error, 1e-8) << "q_s[" << k << "] e " << e1 << " " << e2 << " at " << u << " "
                                 << v;
        }
      }
    }
  }
  std::cout << "worst |J - central difference| over 14 parameters: " << worst << "\n";
}

TEST(DeformableSuperquadricShape, JacobianRateMatchesCentralDifferencesOfTheJacobian) {
  const double step = 1e-6;
  SuperquadricShapeParameters q_s_dot;
  q_s_dot << 0.2, -0.3, 0.25, 0.4, -0.35, 0.3, 0.5, -0.2, 0.3, -0.4, 0.6, -0.5, 0.35, 0.45;
  double worst = 0.0;
  for (const double e1 : kExponents) {
    for (const double e2 : kExponents) {
      const SuperquadricShapeParameters q_s = sample_shape_parameters(e1, e2);
      const DeformableSuperquadricShape shape(q_s);
      for (const auto& uv : kGenericParameters) {
        const double u = uv[0];
        const double v = uv[1];
        const auto analytic = shape.jacobian_rate(u, v, q_s_dot);
        const auto jacobian_at = [&](double t) {
          return DeformableSuperquadricShape((q_s + t * q_s_dot).eval()).evaluate(u, v).jacobian;
        };
        const Eigen::Matrix<double, 3, kSuperquadricShapeParameterCount> fd =
            (jacobian_at(step) - jacobian_at(-step)) / (2 * step);
        const double error = (analytic - fd).norm();
        worst = std::max(worst, error);
        // Third derivatives of s are O(10) here (ln^3|x| |x|^e for e = 0.1 reaches 5 at
        // |x| = 0.2, times the deformation factors): truncation 1e-11, rounding 1e-10.
        EXPECT_LT(error, 1e-8 * (1.0 + analytic.norm())) << e1 << " " << e2 << " " << u << " " << v;
      }
    }
  }
  std::cout << "worst |Jdot - central difference of J|: " << worst << "\n";
}

TEST(DeformableSuperquadricShape, JacobianRateIsFiniteWhereCosineOrSineVanish) {
  const SuperquadricShapeParameters q_s_dot = SuperquadricShapeParameters::Constant(0.3);
  for (const double e1 : kExponents) {
    for (const double e2 : kExponents) {
      const DeformableSuperquadricShape shape(sample_shape_parameters(e1, e2));
      for (const double u : kSpecialAngles) {
        if (std::abs(u) > kPi / 2) {
          continue;
        }
        for (const double v : kSpecialAngles) {
          EXPECT_TRUE(all_finite(shape.jacobian_rate(u, v, q_s_dot)))
              << e1 << " " << e2 << " " << u << " " << v;
        }
      }
    }
  }
}

TEST(DeformableSuperquadricShape, JacobianRateOfARestingShapeIsZero) {
  const DeformableSuperquadricShape shape(sample_shape_parameters(0.5, 2.0));
  EXPECT_EQ(shape.jacobian_rate(0.4, -1.2, SuperquadricShapeParameters::Zero()),
            (Eigen::Matrix<double, 3, kSuperquadricShapeParameterCount>::Zero()));
}

TEST(DeformableSuperquadricShape, UndeformedShapeIsTheSuperellipsoid) {
  SuperellipsoidParameters superellipsoid;
  superellipsoid << 1.3, 0.8, 1.2, 1.5, 0.5, 2.0;
  const DeformableSuperquadricShape shape(
      DeformableSuperquadricShape::combine(superellipsoid, GlobalDeformationParameters::Zero()));
  for (const auto& uv : kGenericParameters) {
    const double u = uv[0];
    const double v = uv[1];
    const SuperquadricShapeEvaluation s = shape.evaluate(u, v);
    const SuperellipsoidEvaluation e = evaluate_superellipsoid(superellipsoid, u, v);
    EXPECT_EQ(s.point, e.point);
    EXPECT_EQ(s.d_u, e.d_u);
    EXPECT_EQ(s.jacobian.leftCols<6>(), e.jacobian);
  }
}

TEST(DeformableSuperquadricShape, IsFiniteWhereCosineOrSineVanish) {
  for (const double e1 : kExponents) {
    for (const double e2 : kExponents) {
      const DeformableSuperquadricShape shape(sample_shape_parameters(e1, e2));
      for (const double u : kSpecialAngles) {
        if (std::abs(u) > kPi / 2) {
          continue;
        }
        for (const double v : kSpecialAngles) {
          const SuperquadricShapeEvaluation s = shape.evaluate(u, v);
          EXPECT_TRUE(all_finite(s.point) && all_finite(s.d_u) && all_finite(s.d_v) &&
                      all_finite(s.jacobian))
              << e1 << " " << e2 << " " << u << " " << v;
          const Eigen::Vector3d normal = shape.unit_normal(u, v);
          EXPECT_TRUE(all_finite(normal)) << e1 << " " << e2 << " " << u << " " << v;
          // Normalized by its own length: one rounding.
          EXPECT_NEAR(normal.norm(), 1.0, 1e-15);
        }
      }
    }
  }
}

TEST(DeformableSuperquadricShape, SphereLiesOnItsSphereWithRadialNormals) {
  const double radius = 2.5;
  const DeformableSuperquadricShape sphere = DeformableSuperquadricShape::sphere(radius);
  double worst_radius = 0.0;
  double worst_normal = 0.0;
  for (int i = 0; i <= 24; ++i) {
    const double u = -kPi / 2 + i * kPi / 24;
    for (int j = 0; j <= 48; ++j) {
      const double v = -kPi + j * kPi / 24;
      const Eigen::Vector3d point = sphere.point(u, v);
      worst_radius = std::max(worst_radius, std::abs(point.norm() - radius));
      worst_normal = std::max(worst_normal, (sphere.unit_normal(u, v) - point / radius).norm());
    }
  }
  // A few ulps of the radius 2.5 (4.4e-16 each).
  EXPECT_LT(worst_radius, 1e-14);
  // The normal is a normalized cross product of exact-to-rounding tangents: a few ulps too;
  // the pole rows use the fallback (+-z exactly).
  EXPECT_LT(worst_normal, 1e-14);
  std::cout << "sphere: worst |r - R| " << worst_radius << ", worst |n - p/R| " << worst_normal
            << "\n";
}

TEST(DeformableSuperquadricShape, NormalIsOrthogonalToTheTangentsAndOutward) {
  for (const double e1 : {0.5, 1.0, 1.5}) {
    for (const double e2 : {0.5, 1.0, 1.5}) {
      const DeformableSuperquadricShape shape(sample_shape_parameters(e1, e2));
      for (const auto& uv : kGenericParameters) {
        const double u = uv[0];
        const double v = uv[1];
        const SuperquadricShapeEvaluation s = shape.evaluate(u, v);
        const Eigen::Vector3d normal = shape.unit_normal(u, v);
        // Cross product then normalization: rounding relative to the tangents' size.
        EXPECT_LT(std::abs(normal.dot(s.d_u)), 1e-14 * s.d_u.norm());
        EXPECT_LT(std::abs(normal.dot(s.d_v)), 1e-14 * s.d_v.norm());
      }
    }
  }
  // Outward for a convex shape: the normal points away from the centre.
  SuperquadricShapeParameters convex = sample_shape_parameters(1.0, 1.0);
  convex.tail<kGlobalDeformationParameterCount>().setZero();
  const DeformableSuperquadricShape convex_shape(convex);
  for (const auto& uv : kGenericParameters) {
    const double u = uv[0];
    const double v = uv[1];
    EXPECT_GT(convex_shape.unit_normal(u, v).dot(convex_shape.point(u, v)), 0.0);
  }
}

TEST(DeformableSuperquadricShape, PoleNormalIsTheLimitOfNearbyNormals) {
  // Where the pole has a tangent plane (e1 < 2) the fallback F^-T (+-z) is the limit of the
  // normals at u = +-(pi/2 - delta), for every v and with every deformation active.
  const double delta = 1e-7;
  double worst = 0.0;
  for (const double e1 : {0.5, 1.0}) {
    for (const double e2 : kExponents) {
      const DeformableSuperquadricShape shape(sample_shape_parameters(e1, e2));
      for (const double side : {-1.0, 1.0}) {
        const Eigen::Vector3d pole = shape.unit_normal(side * kPi / 2, 0.3);
        for (const double v : {-2.9, -1.0, 0.4, 2.2}) {
          const Eigen::Vector3d near = shape.unit_normal(side * (kPi / 2 - delta), v);
          worst = std::max(worst, (near - pole).norm());
          // The normal converges like C delta^(2/e1 - 1) for e1 = 1 (measured: C up to 36, for
          // e2 = 4 whose star-shaped sections bend fastest) and like delta^1.5 for e1 = 0.5.
          EXPECT_LT((near - pole).norm(), 1e-5) << e1 << " " << e2 << " " << side << " " << v;
        }
      }
    }
  }
  std::cout << "worst pole normal vs nearby normal: " << worst << "\n";
}

TEST(DeformableSuperquadricShape, NormalOfDisplacedSurfaceUsesDisplacementTangents) {
  const DeformableSuperquadricShape sphere = DeformableSuperquadricShape::sphere(1.0);
  const double u = 0.3;
  const double v = 0.8;
  const SuperquadricShapeEvaluation s = sphere.evaluate(u, v);
  // d = s (a uniform radial stretch by 2) keeps the normal.
  EXPECT_LT((sphere.unit_normal(u, v, s.d_u, s.d_v) - sphere.unit_normal(u, v)).norm(), 1e-15);
  // d_u = -s_u collapses the tangent plane: undefined, reported.
  EXPECT_THROW(sphere.unit_normal(u, v, -s.d_u, Eigen::Vector3d::Zero()), Error);
}

TEST(DeformableSuperquadricShape, RejectsBadParametersNamingThem) {
  SuperquadricShapeParameters q_s = sample_shape_parameters(1.0, 1.0);
  q_s[Q::kAspect3] = -2.0;
  try {
    DeformableSuperquadricShape shape(q_s);
    ADD_FAILURE() << "negative a3 accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("aspect a3 is -2"), std::string::npos) << error.what();
  }
  DeformableSuperquadricShape shape = DeformableSuperquadricShape::sphere(1.0);
  q_s = shape.parameters();
  q_s[Q::kShearY] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(shape.set_parameters(q_s), Error);
  // Unchanged after a rejected update.
  EXPECT_EQ(shape.parameters(), DeformableSuperquadricShape::sphere(1.0).parameters());
}

}  // namespace
}  // namespace dnurbs
