#include "dnurbs/nurbs/nurbs_surface.h"

#include <cmath>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "sample_shapes.h"

namespace dnurbs {
namespace {

TEST(RationalSphere, RadiusIsOneEverywhere) {
  const NurbsSurface unit_sphere = sphere(1.0);
  double worst = 0.0;
  for (int i = 0; i <= 200; ++i) {
    for (int j = 0; j <= 200; ++j) {
      worst = std::max(worst, std::abs(unit_sphere.point(i / 200.0, j / 200.0).norm() - 1.0));
    }
  }
  EXPECT_LT(worst, 1e-13);  // exact up to rounding in the tensor-product quotient
}

TEST(RationalSphere, NormalsAreRadialIncludingThePoles) {
  const NurbsSurface unit_sphere = sphere(1.0);
  for (int i = 0; i <= 40; ++i) {
    for (int j = 0; j <= 40; ++j) {
      const double u = i / 40.0;
      const double v = j / 40.0;
      const Eigen::Vector3d x = unit_sphere.point(u, v);
      // u runs from the south to the north pole and v counter-clockwise: Su x Sv points inward.
      EXPECT_NEAR(unit_sphere.unit_normal(u, v).dot(-x), 1.0, 1e-12) << u << " " << v;
    }
  }
}

TEST(RationalSphere, CurvaturesAreInverseRadius) {
  const double radius = 2.5;
  const NurbsSurface shape = sphere(radius);
  for (int i = 1; i < 20; ++i) {
    for (int j = 0; j < 20; ++j) {
      const SurfaceCurvature curvature = shape.curvature(i / 20.0, j / 20.0);
      // With the inward normal the sphere curves towards the normal: k1 = k2 = 1/r.
      EXPECT_NEAR(curvature.principal_min, 1.0 / radius, 1e-12);
      EXPECT_NEAR(curvature.principal_max, 1.0 / radius, 1e-12);
      EXPECT_NEAR(curvature.gaussian, 1.0 / (radius * radius), 1e-12);
      EXPECT_NEAR(curvature.mean, 1.0 / radius, 1e-12);
    }
  }
}

TEST(RationalTorus, PrincipalCurvaturesMatchTheAnalyticOnes) {
  const double major = 3.0;
  const double minor = 1.0;
  const NurbsSurface shape = torus(major, minor);
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      const double u = (i + 0.3) / 16.0;
      const double v = (j + 0.6) / 16.0;
      const Eigen::Vector3d x = shape.point(u, v);
      const double distance_to_axis = std::hypot(x.x(), x.y());
      // On a torus, K = cos(theta) / (r (R + r cos(theta))) with cos(theta) = (rho - R)/r.
      const double cos_theta = (distance_to_axis - major) / minor;
      const SurfaceCurvature curvature = shape.curvature(u, v);
      EXPECT_NEAR(curvature.gaussian, cos_theta / (minor * (major + minor * cos_theta)), 1e-11);
      // One principal curvature is the tube's, 1/r in magnitude.
      const double tube =
          std::max(std::abs(curvature.principal_min), std::abs(curvature.principal_max));
      EXPECT_NEAR(tube, 1.0 / minor, 1e-11);
      // The principal directions are orthogonal tangents.
      EXPECT_NEAR(curvature.direction_min.dot(curvature.direction_max), 0.0, 1e-10);
    }
  }
}

// Checks Su, Sv (from S), Suu, Suv (from Su) and Svv (from Sv) against differences. Parameters
// sit at and between repeated knots; at a knot the difference is one-sided into the span the
// evaluator uses.
void expect_surface_derivatives_match_differences(const NurbsSurface& surface) {
  const double h = 1e-6;
  const auto difference = [&](double u, double v, int k, int l, bool along_u) {
    const double at = along_u ? u : v;
    const bool at_knot = (along_u ? surface.knots_u() : surface.knots_v()).multiplicity(at) > 0;
    const auto value = [&](double step) {
      return along_u ? surface.derivatives(u + step, v, 2)(k, l)
                     : surface.derivatives(u, v + step, 2)(k, l);
    };
    if (at_knot) {
      return Eigen::Vector3d((-3.0 * value(0.0) + 4.0 * value(h) - value(2 * h)) / (2 * h));
    }
    return Eigen::Vector3d((value(h) - value(-h)) / (2 * h));
  };
  for (double u : {0.0, 0.12, 0.25, 0.5, 0.61, 0.93}) {
    for (double v : {0.0, 0.2, 0.3, 0.65, 0.77}) {
      const SurfaceDerivatives d = surface.derivatives(u, v, 2);
      const std::array<std::array<int, 5>, 5> checks = {{
          {1, 0, 0, 0, 1},  // Su from S along u
          {0, 1, 0, 0, 0},  // Sv from S along v
          {2, 0, 1, 0, 1},  // Suu from Su along u
          {1, 1, 1, 0, 0},  // Suv from Su along v
          {0, 2, 0, 1, 0},  // Svv from Sv along v
      }};
      for (const auto& check : checks) {
        const Eigen::Vector3d expected = difference(u, v, check[2], check[3], check[4] == 1);
        const Eigen::Vector3d& actual = d(check[0], check[1]);
        // Truncation h^2 times third derivatives (~1e4 on these rational patches) plus
        // rounding eps |S| / h.
        EXPECT_LT((actual - expected).norm(), 1e-5 * (1.0 + actual.norm()))
            << "S(" << check[0] << "," << check[1] << ") at (" << u << ", " << v << ")";
      }
    }
  }
}

TEST(NurbsSurface, DerivativesMatchFiniteDifferences) {
  expect_surface_derivatives_match_differences(testing::random_rational_surface(2, 3, 1));
  expect_surface_derivatives_match_differences(testing::random_rational_surface(3, 2, 2));
  expect_surface_derivatives_match_differences(
      testing::random_rational_surface(3, 3, 3, false, true));
  expect_surface_derivatives_match_differences(sphere(1.0));
}

TEST(PeriodicSurface, IsCpMinusOneAcrossBothSeams) {
  const NurbsSurface closed = testing::random_rational_surface(3, 3, 4, true, true);
  for (double t : {0.0, 0.13, 0.5, 0.87}) {
    const SurfaceDerivatives left_u = closed.derivatives(1.0, t, 2);
    const SurfaceDerivatives right_u = closed.derivatives(0.0, t, 2);
    const SurfaceDerivatives left_v = closed.derivatives(t, 1.0, 2);
    const SurfaceDerivatives right_v = closed.derivatives(t, 0.0, 2);
    for (int k = 0; k <= 2; ++k) {
      for (int l = 0; k + l <= 2; ++l) {
        EXPECT_LT((left_u(k, l) - right_u(k, l)).norm(), 1e-12 * (1.0 + left_u(k, l).norm()));
        EXPECT_LT((left_v(k, l) - right_v(k, l)).norm(), 1e-12 * (1.0 + left_v(k, l).norm()));
      }
    }
  }
}

TEST(NurbsSurface, PolynomialSurfaceHasZeroCurvatureWhenFlat) {
  const KnotVector knots = KnotVector::clamped_uniform(3, 5);
  Eigen::MatrixX3d points(25, 3);
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      points.row(i * 5 + j) << i * i * 0.1 + j, j * 0.5 + i, 0.0;  // a distorted flat patch
    }
  }
  const NurbsSurface flat(knots, knots, points);
  const SurfaceCurvature curvature = flat.curvature(0.4, 0.7);
  EXPECT_NEAR(curvature.gaussian, 0.0, 1e-12);
  EXPECT_NEAR(curvature.mean, 0.0, 1e-12);
  EXPECT_NEAR(std::abs(flat.unit_normal(0.4, 0.7).z()), 1.0, 1e-14);
}

TEST(NurbsSurface, RejectsMismatchedControlPointCount) {
  const KnotVector knots = KnotVector::clamped_uniform(2, 4);
  EXPECT_THROW(NurbsSurface(knots, knots, Eigen::MatrixX3d::Zero(15, 3)), Error);
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(16);
  weights[7] = -1.0;
  EXPECT_THROW(NurbsSurface(knots, knots, Eigen::MatrixX3d::Zero(16, 3), weights), Error);
}

}  // namespace
}  // namespace dnurbs
