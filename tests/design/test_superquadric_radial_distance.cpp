#include "dnurbs/design/superquadric_radial_distance.h"

#include <cmath>
#include <iostream>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

using P = SuperquadricShapeParameter;

// Sizes (1.1, 0.7, 1.6), e = (0.8, 1.3) and every global deformation non-zero.
SuperquadricShapeParameters deformed_shape() {
  SuperquadricShapeParameters shape;
  shape << 1.0, 1.1, 0.7, 1.6, 0.8, 1.3,  // a, a1, a2, a3, e1, e2
      0.3, -0.2,                          // t1, t2
      0.15, 0.2, 0.6,                     // b1, b2, b3
      0.7,                                // tau
      0.25, -0.15;                        // sx, sy
  return shape;
}

// Points of s(u, v) lie at distance 0 and project back to their own (u, v): T^-1 undoes shear,
// twist, bend and taper exactly.
TEST(SuperquadricRadialDistance, VanishesOnTheDeformedSurfaceAndProjectsToItsParameters) {
  const SuperquadricShapeParameters shape = deformed_shape();
  const DeformableSuperquadricShape surface(shape);
  double worst_distance = 0.0;
  double worst_parameter = 0.0;
  for (int i = 1; i < 12; ++i) {
    for (int j = 0; j < 16; ++j) {
      const double u = -std::numbers::pi / 2 + std::numbers::pi * i / 12.0;
      const double v = -std::numbers::pi + 2.0 * std::numbers::pi * (j + 0.3) / 16.0;
      const Eigen::Vector3d p = surface.point(u, v);
      const double d = superquadric_body_radial_distance(
          shape.segment<3>(P::kAspect1), shape[P::kSquareness1], shape[P::kSquareness2],
          shape.tail<kGlobalDeformationParameterCount>(), p);
      worst_distance = std::max(worst_distance, std::abs(d));
      const Eigen::Vector2d uv = superquadric_radial_projection(shape, p);
      worst_parameter =
          std::max(worst_parameter, (uv - Eigen::Vector2d(u, v)).cwiseAbs().maxCoeff());
    }
  }
  std::cout << "on the surface: |d| <= " << worst_distance
            << ", parameter error <= " << worst_parameter << "\n";
  // Round-off of the powers |x|^(2/e) and the inverse steps on coordinates ~1: a few 1e-16,
  // amplified by 1/e <= 1.25 in the parameters.
  EXPECT_LT(worst_distance, 1e-14);
  EXPECT_LT(worst_parameter, 1e-12);
}

// Without deformation the distance of (1 + t) e for a surface point e is exactly t |e|.
TEST(SuperquadricRadialDistance, IsTheOffsetAlongTheRayWithoutDeformation) {
  SuperquadricShapeParameters shape = deformed_shape();
  shape.tail<kGlobalDeformationParameterCount>().setZero();
  const DeformableSuperquadricShape surface(shape);
  const Eigen::Vector3d e = surface.point(0.4, -2.0);
  for (const double t : {-0.3, 0.1, 0.5}) {
    const double d = superquadric_radial_distance(shape, Eigen::Vector3d::Zero(),
                                                  Eigen::Matrix3d::Identity(), (1.0 + t) * e);
    EXPECT_NEAR(d, t * e.norm(), 1e-14);
  }
}

TEST(SuperquadricRadialDistance, GradientMatchesCentralDifferences) {
  const SuperquadricShapeParameters shape = deformed_shape();
  const DeformableSuperquadricShape surface(shape);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Arguments: p (3), sizes (3), e1, e2, deformation (8): 16 partial derivatives.
  const auto distance = [](const Eigen::Matrix<double, 16, 1>& x,
                           SuperquadricRadialDistanceGradient* gradient) {
    return superquadric_body_radial_distance(x.segment<3>(3), x[6], x[7],
                                             x.tail<kGlobalDeformationParameterCount>(),
                                             x.head<3>(), gradient);
  };
  double worst = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    const double u = 1.3 * unit(random);
    const double v = std::numbers::pi * unit(random);
    Eigen::Matrix<double, 16, 1> x;
    x.head<3>() = surface.point(u, v) * (1.0 + 0.2 * unit(random));  // off the surface
    x.segment<3>(3) = shape.segment<3>(P::kAspect1);
    x[6] = shape[P::kSquareness1];
    x[7] = shape[P::kSquareness2];
    x.tail<kGlobalDeformationParameterCount>() = shape.tail<kGlobalDeformationParameterCount>();
    SuperquadricRadialDistanceGradient gradient;
    const double value = distance(x, &gradient);
    EXPECT_DOUBLE_EQ(value, distance(x, nullptr));
    Eigen::Matrix<double, 16, 1> analytic;
    analytic << gradient.point, gradient.size, gradient.e1, gradient.e2, gradient.deformation;
    Eigen::Matrix<double, 16, 1> difference;
    for (int i = 0; i < 16; ++i) {
      const double h = 1e-6;
      Eigen::Matrix<double, 16, 1> plus = x;
      Eigen::Matrix<double, 16, 1> minus = x;
      plus[i] += h;
      minus[i] -= h;
      difference[i] = (distance(plus, nullptr) - distance(minus, nullptr)) / (2.0 * h);
    }
    worst = std::max(worst, (analytic - difference).cwiseAbs().maxCoeff() /
                                std::max(1.0, analytic.cwiseAbs().maxCoeff()));
  }
  std::cout << "largest difference to central differences " << worst << "\n";
  // Central differences with h = 1e-6: O(h^2 d''') truncation ~1e-12 plus O(eps d / h)
  // round-off ~1e-10 for d ~ 1.
  EXPECT_LT(worst, 1e-8);
}

// The body origin of an undeformed shape has no ray.
TEST(SuperquadricRadialDistance, ProjectionOfTheOriginThrows) {
  SuperquadricShapeParameters shape = deformed_shape();
  shape.tail<kGlobalDeformationParameterCount>().setZero();
  EXPECT_THROW(superquadric_radial_projection(shape, Eigen::Vector3d::Zero()), Error);
}

}  // namespace
}  // namespace dnurbs
