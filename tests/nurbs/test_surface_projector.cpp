#include "dnurbs/nurbs/surface_projector.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/common/error_message.h"
#include "tests/nurbs/brute_force_projection.h"
#include "tests/nurbs/random_shapes.h"

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/primitive_shapes.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

// A result farther than the brute-force reference by more than this (relative to the size of
// the control net, ~1) is a global miss: both are Newton-refined to ~1e-15, while a wrong local
// minimum is off by far more.
constexpr double kMiss = 1e-10;
// A query on the surface: the distance of the point found is round-off of coordinates of size ~1.
constexpr double kOnSurface = 1e-12;

Eigen::Vector3d random_direction(std::mt19937& generator) {
  return Eigen::Vector3d(testing::random_real(generator, -1, 1),
                         testing::random_real(generator, -1, 1),
                         testing::random_real(generator, -1, 1))
      .normalized();
}

Eigen::Vector2d random_parameters(const NurbsSurface& surface, std::mt19937& generator) {
  const KnotVector& u = surface.knots_u();
  const KnotVector& v = surface.knots_v();
  return {u.domain_start() +
              (u.domain_end() - u.domain_start()) * testing::random_real(generator, 0.0, 1.0),
          v.domain_start() +
              (v.domain_end() - v.domain_start()) * testing::random_real(generator, 0.0, 1.0)};
}

TEST(SurfaceProjector, FindsTheGlobalMinimumOfThreeThousandQueries) {
  // 300 random surfaces: degrees 1..4 in each direction, open (clamped or not) and periodic
  // (every seam multiplicity, perturbed seams), repeated knots, weights 0.05..20; 10 queries
  // each, on the surface, near it (offsets 10^-4..10^-1) and anywhere in [-3, 3]^3.
  std::mt19937 generator(8001U);
  int misses = 0;
  int reference_misses = 0;
  int queries = 0;
  double worst_on_surface = 0.0;
  for (int trial = 0; trial < 300; ++trial) {
    const int degree_u = 1 + trial % 4;
    const int degree_v = 1 + (trial / 4) % 4;
    const NurbsSurface surface = testing::random_surface(
        degree_u, degree_v, testing::trial_options(trial, degree_u, true),
        testing::trial_options(trial / 2, degree_v, true), trial % 3 != 0, generator);
    const SurfaceProjector projector(surface);
    const testing::SurfaceSamples samples = testing::sample_surface(surface, 12);
    for (int k = 0; k < 10; ++k) {
      const Eigen::Vector2d uv = random_parameters(surface, generator);
      const Eigen::Vector3d on = surface.point(uv.x(), uv.y());
      const Eigen::Vector3d query =
          k % 3 == 0 ? on
          : k % 3 == 1
              ? Eigen::Vector3d(on + std::pow(10.0, testing::random_real(generator, -4, -1)) *
                                         random_direction(generator))
              : Eigen::Vector3d(3.0 * testing::random_real(generator, 0, 1) *
                                random_direction(generator));
      const SurfaceProjection found = projector.closest_point(query);
      const double reference = testing::brute_force_distance(surface, samples, query);
      ++queries;
      misses += found.distance > reference + kMiss ? 1 : 0;
      EXPECT_LE(found.distance, reference + kMiss) << "trial " << trial << " query " << k;
      // Where the sampled reference itself misses a sliver of the surface, the projector's
      // point is nearer (it is a surface point at that distance): counted, not a failure.
      reference_misses += found.distance < reference - kMiss ? 1 : 0;
      if (k % 3 == 0) {
        worst_on_surface = std::max(worst_on_surface, found.distance);
        EXPECT_LT(found.distance, kOnSurface) << "trial " << trial;
      }
    }
  }
  EXPECT_EQ(misses, 0);
  std::cout << "[ measured ] " << misses << " misses of " << queries << " queries ("
            << reference_misses << " where the reference was farther); largest distance of a "
            << "query on the surface " << worst_on_surface << "\n";
}

TEST(SurfaceProjector, InvertsPointsOnTheSurfaceToRoundOff) {
  std::mt19937 generator(8002U);
  double worst = 0.0;
  for (int trial = 0; trial < 150; ++trial) {
    const int degree_u = 1 + trial % 4;
    const int degree_v = 1 + (trial / 4) % 4;
    testing::RandomKnotOptions options_u = testing::trial_options(trial, degree_u, true);
    testing::RandomKnotOptions options_v = testing::trial_options(trial / 2, degree_v, true);
    options_u.extra_control_points = options_v.extra_control_points = 1;
    const NurbsSurface surface = testing::random_surface(degree_u, degree_v, options_u, options_v,
                                                         trial % 3 != 0, generator);
    const SurfaceProjector projector(surface);
    for (int k = 0; k < 10; ++k) {
      const Eigen::Vector2d uv = random_parameters(surface, generator);
      const Eigen::Vector2d found = projector.invert(surface.point(uv.x(), uv.y()), 1e-9);
      double error = 0.0;
      for (int d = 0; d < 2; ++d) {
        const KnotVector& knots = d == 0 ? surface.knots_u() : surface.knots_v();
        const double length = knots.domain_end() - knots.domain_start();
        double e = std::abs(found[d] - uv[d]) / length;
        if (knots.is_periodic()) {
          e = std::min(e, std::abs(e - 1.0));  // the seam: start and end are one point
        }
        error = std::max(error, e);
      }
      worst = std::max(worst, error);
      // |du| ~ round-off of the point (1e-16) over the speeds |S_u|, |S_v|.
      EXPECT_LT(error, 1e-12) << "trial " << trial << " uv " << uv.transpose();
    }
  }
  std::cout << "[ measured ] worst relative parameter error " << worst << "\n";
}

TEST(SurfaceProjector, AgreesWithTheSphereAndTheTorus) {
  // Sphere (open in u with poles, periodic quarter arcs in v): the nearest point is radial.
  const SurfaceProjector sphere_projector(sphere(1.0));
  // Torus periodic in both directions: distance | |(x, y) - R| , z) | - r |.
  const Eigen::Vector3d centre(0.5, -0.25, 1.0);
  const SurfaceProjector torus_projector(periodic_torus(2.0, 0.5, centre));
  std::mt19937 generator(8003U);
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d direction = random_direction(generator);
    const double radius = testing::random_real(generator, 0.1, 3.0);
    const SurfaceProjection on_sphere = sphere_projector.closest_point(radius * direction);
    // Round-off of the rational quadratic sphere: ~1e-16.
    EXPECT_NEAR(on_sphere.distance, std::abs(radius - 1.0), 1e-14);
    EXPECT_NEAR((on_sphere.point - direction).norm(), 0.0, 1e-13);
    const Eigen::Vector3d query =
        centre + 3.0 * testing::random_real(generator, 0.0, 1.0) * random_direction(generator);
    const Eigen::Vector3d local = query - centre;
    const double expected =
        std::abs(std::hypot(std::hypot(local.x(), local.y()) - 2.0, local.z()) - 0.5);
    const SurfaceProjection on_torus = torus_projector.closest_point(query);
    // The rational torus and the formula agree to a few ulps of coordinates of size ~3.
    EXPECT_NEAR(on_torus.distance, expected, 1e-13) << "query " << query.transpose();
    // Periodic directions report parameters in [start, end).
    EXPECT_GE(on_torus.parameter.minCoeff(), 0.0);
    EXPECT_LT(on_torus.parameter.maxCoeff(), 1.0);
  }
}

TEST(SurfaceProjector, FindsCornersEdgesAndCreasesExactly) {
  // A bicubic patch over [0, 3]^2 with a C^0 crease (u knot 1/2 of multiplicity 3) where the
  // surface folds up into a ridge along x = 1.5.
  Eigen::MatrixX3d points(7 * 4, 3);
  const double xs[7] = {0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0};
  const double zs[7] = {0.0, 0.3, 0.6, 1.0, 0.6, 0.3, 0.0};
  for (int i = 0; i < 7; ++i) {
    for (int j = 0; j < 4; ++j) {
      points.row(i * 4 + j) << xs[i], j, zs[i];
    }
  }
  const NurbsSurface surface(KnotVector(3, {0, 0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1, 1}),
                             KnotVector::clamped_uniform(3, 4), points);
  const SurfaceProjector projector(surface);
  // Above the ridge: the crease u = 1/2 is nearest.
  const SurfaceProjection ridge = projector.closest_point(Eigen::Vector3d(1.5, 1.5, 3.0));
  EXPECT_EQ(ridge.parameter.x(), 0.5);
  EXPECT_NEAR(ridge.distance, 2.0, 1e-14);  // the crease interpolates the row z = 1: ulps
  // Beyond the corner (0, 0): the corner itself.
  const SurfaceProjection corner = projector.closest_point(Eigen::Vector3d(-1.0, -2.0, -0.5));
  EXPECT_EQ(corner.parameter, Eigen::Vector2d(0.0, 0.0));
  // Beyond the edge y = 3 (v = 1), over the flat part x in [0, 1.5]: on that edge.
  const SurfaceProjection edge = projector.closest_point(Eigen::Vector3d(0.7, 4.0, 0.0));
  EXPECT_EQ(edge.parameter.y(), 1.0);
  // There the nearest edge point is stationary along the edge: (S - Q).S_u = 0.
  const SurfaceDerivatives d = surface.derivatives(edge.parameter.x(), 1.0, 1);
  EXPECT_NEAR((d(0, 0) - Eigen::Vector3d(0.7, 4.0, 0.0)).dot(d(1, 0)), 0.0,
              1e-13);  // round-off of terms |S - Q| |S_u| ~ 10
}

TEST(SurfaceProjector, TiesGoToTheSmallestParameters) {
  // Every point of the sphere is as near to its centre: the answer is the pole (u, v) = (0, 0).
  const SurfaceProjection centre =
      SurfaceProjector(sphere(1.0)).closest_point(Eigen::Vector3d::Zero());
  EXPECT_EQ(centre.parameter, Eigen::Vector2d(0.0, 0.0));
  EXPECT_NEAR(centre.distance, 1.0, 1e-15);  // the pole of the rational sphere, to an ulp
  // On the torus's axis a whole circle is nearest; the smallest (u, v) of it.
  const NurbsSurface torus_surface = periodic_torus(2.0, 0.5);
  const SurfaceProjection axis =
      SurfaceProjector(torus_surface).closest_point(Eigen::Vector3d(0.0, 0.0, 0.3));
  // The tube's centre circle is 2 from the axis: distance hypot(2, 0.3) - 0.5.
  EXPECT_NEAR(axis.distance, std::hypot(2.0, 0.3) - 0.5, 1e-13);
}

TEST(SurfaceProjector, BadQueriesThrowErrorNamingTheValue) {
  const SurfaceProjector projector(sphere(1.0));
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THAT(testing::error_message([&] { projector.closest_point(Eigen::Vector3d(0, inf, 0)); }),
              HasSubstr("not finite"));
  EXPECT_THAT(testing::error_message([&] { projector.invert(Eigen::Vector3d(0, 0, 3), 1e-9); }),
              HasSubstr("is 2 from the surface"));
}

}  // namespace
}  // namespace dnurbs
