#include "dnurbs/nurbs/span_cached_surface_evaluator.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "sample_shapes.h"

namespace dnurbs {
namespace {

/// Degrees (p, q) with knots u = {0 x(p+1), 0.2, 0.5 x p, 0.7, 1 x(p+1)} (a C^0 interior knot of
/// multiplicity p) and v with a knot of multiplicity max(1, q - 1); random points and weights.
NurbsSurface repeated_knot_surface(int degree_u, int degree_v, bool rational, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  std::uniform_real_distribution<double> weight(0.4, 2.5);
  const auto knots = [](int degree, int repeated) {
    std::vector<double> values(static_cast<size_t>(degree + 1), 0.0);
    values.push_back(0.2);
    values.insert(values.end(), static_cast<size_t>(repeated), 0.5);
    values.push_back(0.7);
    values.insert(values.end(), static_cast<size_t>(degree + 1), 1.0);
    return KnotVector(degree, values);
  };
  const KnotVector knots_u = knots(degree_u, degree_u);
  const KnotVector knots_v = knots(degree_v, std::max(1, degree_v - 1));
  const int count = knots_u.control_point_count() * knots_v.control_point_count();
  Eigen::MatrixX3d points(count, 3);
  Eigen::VectorXd weights = Eigen::VectorXd::Constant(count, 1.7);  // equal: non-rational
  for (int i = 0; i < count; ++i) {
    points.row(i) << coordinate(generator), coordinate(generator), coordinate(generator);
    if (rational) {
      weights[i] = weight(generator);
    }
  }
  return NurbsSurface(knots_u, knots_v, std::move(points), std::move(weights));
}

/// Parameters along one direction: every distinct knot (span boundaries and both domain ends),
/// points a relative 1e-9 either side of each, and random interior values.
std::vector<double> sample_parameters(const KnotVector& knots, unsigned seed) {
  std::vector<double> values;
  for (int k = knots.degree(); k < knots.size() - knots.degree(); ++k) {
    const double knot = knots[k];
    values.push_back(knot);
    if (knot > knots.domain_start()) {
      values.push_back(knot - 1e-9);
    }
    if (knot < knots.domain_end()) {
      values.push_back(knot + 1e-9);
    }
  }
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> parameter(knots.domain_start(), knots.domain_end());
  for (int i = 0; i < 12; ++i) {
    values.push_back(parameter(generator));
  }
  return values;
}

/// Largest |cached - reference| of S^(k,l) over all samples, relative to the largest |S^(k,l)|.
double worst_relative_difference(const NurbsSurface& surface) {
  const SpanCachedSurfaceEvaluator cached(surface);
  const std::vector<double> us = sample_parameters(surface.knots_u(), 1);
  const std::vector<double> vs = sample_parameters(surface.knots_v(), 2);
  std::array<double, 9> difference{};
  std::array<double, 9> magnitude{};
  SurfaceDerivatives expected;
  SurfaceDerivatives actual;
  for (const double u : us) {
    for (const double v : vs) {
      surface.derivatives(u, v, 2, expected);
      cached.derivatives(u, v, 2, actual);
      for (int k = 0; k <= 2; ++k) {
        for (int l = 0; k + l <= 2; ++l) {
          const auto slot = static_cast<size_t>(3 * k + l);
          difference[slot] = std::max(difference[slot], (actual(k, l) - expected(k, l)).norm());
          magnitude[slot] = std::max(magnitude[slot], expected(k, l).norm());
        }
      }
      difference[0] = std::max(difference[0], (cached.point(u, v) - expected(0, 0)).norm());
    }
  }
  double worst = 0.0;
  for (size_t slot = 0; slot < difference.size(); ++slot) {
    if (magnitude[slot] > 0.0) {
      worst = std::max(worst, difference[slot] / magnitude[slot]);
    }
  }
  return worst;
}

TEST(SpanCachedSurfaceEvaluator, AgreesWithDeBoorEvaluationForDegreesOneToFive) {
  for (int degree_u = 1; degree_u <= 5; ++degree_u) {
    for (int degree_v = 1; degree_v <= 5; ++degree_v) {
      for (const bool rational : {false, true}) {
        const NurbsSurface surface =
            repeated_knot_surface(degree_u, degree_v, rational, 10U * degree_u + degree_v);
        ASSERT_EQ(surface.is_rational(), rational);
        // Both evaluators are exact up to rounding; the power-basis conversion on [-1, 1] and
        // Horner's rule lose a few ulps per degree (measured worst over all 50 surfaces: 4.3e-15).
        EXPECT_LT(worst_relative_difference(surface), 1e-12)
            << "degrees " << degree_u << ", " << degree_v << (rational ? " rational" : "");
      }
    }
  }
}

TEST(SpanCachedSurfaceEvaluator, AgreesOnPeriodicSurfaces) {
  const NurbsSurface surface = testing::random_rational_surface(3, 4, 7, true, true);
  EXPECT_LT(worst_relative_difference(surface), 1e-12);  // rounding only, as above
  // Periodic parameters wrap like the reference evaluator's.
  const SpanCachedSurfaceEvaluator cached(surface);
  EXPECT_LT((cached.point(1.3, -0.4) - surface.point(0.3, 0.6)).norm(), 1e-12);
}

TEST(SpanCachedSurfaceEvaluator, RejectsBadOrderAndParameters) {
  const SpanCachedSurfaceEvaluator cached(repeated_knot_surface(3, 2, true, 5));
  SurfaceDerivatives result;
  EXPECT_THROW(cached.derivatives(0.5, 0.5, 3, result), Error);
  EXPECT_THROW(cached.derivatives(0.5, 0.5, -1, result), Error);
  EXPECT_THROW(cached.point(1.5, 0.5), Error);
  EXPECT_THROW(cached.point(0.5, -0.1), Error);
  EXPECT_THROW(cached.point(std::numeric_limits<double>::quiet_NaN(), 0.5), Error);
  EXPECT_THROW(cached.derivatives(0.5, std::numeric_limits<double>::infinity(), 2, result), Error);
}

}  // namespace
}  // namespace dnurbs
