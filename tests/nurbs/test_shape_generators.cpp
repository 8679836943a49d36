// The shape generators: linear parametrization of the Greville rods and sheets, exact boxes,
// cylinders, cones and revolutions, extrusions, lofts through their sections, span splitting.

#include "dnurbs/nurbs/shape_generators.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "tests/common/error_message.h"
#include "tests/nurbs/random_shapes.h"

namespace dnurbs {
namespace {

using testing::error_message;
using ::testing::HasSubstr;
using testing::random_curve;
using testing::random_real;
using testing::RandomKnotOptions;

constexpr double kPi = std::numbers::pi;

TEST(ShapeGenerators, GrevilleAbscissaeReproduceTheIdentity) {
  for (int degree = 1; degree <= 5; ++degree) {
    const KnotVector knots = KnotVector::clamped_uniform(degree, degree + 4, -1.0, 2.0);
    const std::vector<double> xi = greville_abscissae(knots);
    Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(static_cast<int>(xi.size()), 3);
    for (size_t i = 0; i < xi.size(); ++i) {
      points(static_cast<int>(i), 0) = xi[i];
    }
    const NurbsCurve identity(knots, points);
    for (int k = 0; k <= 30; ++k) {
      const double u = -1.0 + 3.0 * k / 30;
      EXPECT_NEAR(identity.point(u).x(), u, 1e-14) << "degree " << degree << ", u " << u;
    }
  }
  EXPECT_THROW(greville_abscissae(KnotVector::periodic_uniform(2, 5)), Error);
}

TEST(ShapeGenerators, LineAndPlaneAreLinearInTheirParameters) {
  const Eigen::Vector3d start(1, -2, 0.5);
  const Eigen::Vector3d end(4, 2, 0.5);  // length 5
  const NurbsCurve line = greville_line(start, end, 7, 3);
  EXPECT_DOUBLE_EQ(line.knots().domain_end(), 5.0);
  for (int k = 0; k <= 20; ++k) {
    const double u = 5.0 * k / 20;
    EXPECT_LT((line.point(u) - (start + u * (end - start) / 5.0)).norm(), 1e-14) << u;
    EXPECT_NEAR(line.derivatives(u, 1).row(1).norm(), 1.0, 1e-14);  // unit speed
  }
  const Eigen::Vector3d origin(0.5, 0.25, -1);
  const NurbsSurface sheet = greville_plane({3, 2}, {8, 6}, {3, 2}, origin);
  EXPECT_EQ(sheet.control_point_count_u(), 8);
  EXPECT_EQ(sheet.control_point_count_v(), 6);
  EXPECT_EQ(sheet.degree_v(), 2);
  std::mt19937 generator(7);
  for (int k = 0; k < 50; ++k) {
    const double u = random_real(generator, 0, 3);
    const double v = random_real(generator, 0, 2);
    EXPECT_LT((sheet.point(u, v) - (origin + Eigen::Vector3d(u, v, 0))).norm(), 1e-14);
  }
}

TEST(ShapeGenerators, BoxIsExactlyTheSurfaceOfTheBox) {
  const Eigen::Vector3d size(2, 3, 1.5);
  const NurbsSurface b = box(size);
  std::mt19937 generator(3);
  for (int k = 0; k < 200; ++k) {
    const double u = random_real(generator, 0, 3);
    const double v = random_real(generator, 0, 4);
    const Eigen::Vector3d x = b.point(u, v);
    // On a face: one coordinate at its bound, the others within theirs
    const double on_x = std::abs(std::abs(x.x()) - 1.0);
    const double on_y = std::abs(std::abs(x.y()) - 1.5);
    const double on_z = std::min(std::abs(x.z()), std::abs(x.z() - 1.5));
    EXPECT_LT(std::min({on_x, on_y, on_z}), 1e-14) << u << ", " << v;
    EXPECT_LE(std::abs(x.x()), 1.0 + 1e-14);
    EXPECT_LE(std::abs(x.y()), 1.5 + 1e-14);
    EXPECT_GE(x.z(), -1e-14);
    EXPECT_LE(x.z(), 1.5 + 1e-14);
  }
  EXPECT_LT((b.point(0.0, 1.3) - Eigen::Vector3d::Zero()).norm(), 1e-15);        // bottom centre
  EXPECT_LT((b.point(1.5, 0.0) - Eigen::Vector3d(1, 1.5, 0.75)).norm(), 1e-15);  // side edge
  EXPECT_THAT(error_message([] { box({1, 0, 1}); }), HasSubstr("box size y must be"));
}

TEST(ShapeGenerators, CylinderAndConeAreExact) {
  const NurbsSurface tube = cylinder(0.7, 2.0, 5);
  const NurbsSurface spike = cone(0.7, 2.0);
  std::mt19937 generator(11);
  for (int k = 0; k < 200; ++k) {
    const double u =
        random_real(generator, tube.knots_u().domain_start(), tube.knots_u().domain_end());
    const double v = random_real(generator, 0, 1);
    const Eigen::Vector3d x = tube.point(u, v);
    EXPECT_NEAR(std::hypot(x.x(), x.y()), 0.7, 1e-14);
    EXPECT_NEAR(x.z(), u, 1e-14);  // the profile's parameter is the height
    const double w = random_real(generator, 0, spike.knots_u().domain_end());
    const Eigen::Vector3d y = spike.point(w, v);
    EXPECT_NEAR(std::hypot(y.x(), y.y()), 0.7 * (1 - y.z() / 2.0), 1e-14);
  }
  EXPECT_EQ(tube.control_point_count_u(), 5);
  EXPECT_THAT(error_message([] { cylinder(-1, 2); }), HasSubstr("cylinder radius must be"));
  EXPECT_THAT(error_message([] { cone(1, 2, 1); }), HasSubstr("at least 2 control points, got 1"));
}

TEST(ShapeGenerators, RevolutionKeepsRadiusAndHeightAndSweepsTheAngle) {
  std::mt19937 generator(5);
  RandomKnotOptions options;
  options.extra_control_points = 2;
  for (const double angle : {0.3, kPi / 2, 2.0, kPi, 4.5, 2 * kPi}) {
    const NurbsCurve profile = random_curve(3, options, true, generator);
    const NurbsSurface s = revolve(profile, angle);
    for (int k = 0; k < 40; ++k) {
      const double u =
          random_real(generator, profile.knots().domain_start(), profile.knots().domain_end());
      const double v = random_real(generator, 0, 1);
      const Eigen::Vector3d c = profile.point(u);
      const Eigen::Vector3d x = s.point(u, v);
      EXPECT_NEAR(std::hypot(x.x(), x.y()), std::hypot(c.x(), c.y()), 1e-13);
      EXPECT_NEAR(x.z(), c.z(), 1e-13);
      EXPECT_LT((s.point(u, 0.0) - c).norm(), 1e-13);
      const Eigen::Vector3d turned(std::cos(angle) * c.x() - std::sin(angle) * c.y(),
                                   std::sin(angle) * c.x() + std::cos(angle) * c.y(), c.z());
      EXPECT_LT((s.point(u, 1.0) - turned).norm(), 1e-13) << "angle " << angle;
    }
  }
  const NurbsCurve profile = half_circle_xz(1.0);
  EXPECT_THAT(error_message([&] { revolve(profile, 0.0); }), HasSubstr("angle must be in"));
  EXPECT_THAT(error_message([&] { revolve(profile, 7.0); }), HasSubstr("got 7"));
}

TEST(ShapeGenerators, ExtrusionTranslatesTheCurve) {
  std::mt19937 generator(9);
  for (const bool periodic : {false, true}) {
    RandomKnotOptions options;
    options.periodic = periodic;
    options.extra_control_points = 2;
    const NurbsCurve curve = random_curve(2, options, true, generator);
    const Eigen::Vector3d d(0.3, -1.2, 2.0);
    const NurbsSurface s = extrude(curve, d);
    for (int k = 0; k < 40; ++k) {
      const double u =
          random_real(generator, curve.knots().domain_start(), curve.knots().domain_end());
      const double v = random_real(generator, 0, d.norm());
      EXPECT_LT((s.point(u, v) - (curve.point(u) + v * d.normalized())).norm(), 1e-13);
    }
  }
  EXPECT_THAT(error_message([] { extrude(half_circle_xz(1), Eigen::Vector3d::Zero()); }),
              HasSubstr("extrusion length must be"));
}

TEST(ShapeGenerators, LoftPassesThroughEverySection) {
  std::mt19937 generator(13);
  RandomKnotOptions options;
  options.extra_control_points = 1;
  // Sections of different degrees, domains, knots and weights (within a factor 4: interpolated
  // weights of sections whose weights differ by far more can become negative, which loft refuses)
  NurbsCurve rational = random_curve(2, options, false, generator);
  Eigen::VectorXd weights(rational.control_point_count());
  for (int i = 0; i < weights.size(); ++i) {
    weights[i] = random_real(generator, 0.5, 2.0);
  }
  rational.set_weights(weights);
  std::vector<NurbsCurve> sections = {rational, random_curve(3, options, false, generator),
                                      full_circle(0.8, {0, 0, 1}),
                                      random_curve(1, options, false, generator)};
  for (const int degree : {1, 2, 3, 5}) {
    std::vector<double> parameters;
    const NurbsSurface s = loft(sections, degree, &parameters);
    EXPECT_EQ(s.degree_v(), std::min(degree, 3));
    ASSERT_EQ(parameters.size(), sections.size());
    EXPECT_EQ(parameters.front(), 0.0);
    EXPECT_EQ(parameters.back(), 1.0);
    for (size_t k = 0; k < sections.size(); ++k) {
      const KnotVector& knots = sections[k].knots();
      for (int j = 0; j <= 20; ++j) {
        const double t = j / 20.0;
        const double u_section =
            knots.domain_start() + t * (knots.domain_end() - knots.domain_start());
        const double u = s.knots_u().domain_start() +
                         t * (s.knots_u().domain_end() - s.knots_u().domain_start());
        EXPECT_LT((s.point(u, parameters[k]) - sections[k].point(u_section)).norm(), 1e-12)
            << "degree " << degree << ", section " << k << ", t " << t;
      }
    }
  }
  RandomKnotOptions periodic;
  periodic.periodic = true;
  EXPECT_THAT(error_message([&] {
                loft({sections[0], random_curve(2, periodic, false, generator)}, 3);
              }),
              HasSubstr("loft section 1 is periodic"));
  EXPECT_THAT(error_message([&] { loft({sections[0]}, 3); }), HasSubstr("at least 2 sections"));
}

TEST(ShapeGenerators, SplitSpansKeepsTheShapeAndAddsControlPoints) {
  const NurbsSurface s = sphere(1.5);
  const NurbsSurface finer = split_spans(s, {3, 2});
  EXPECT_EQ(finer.control_point_count_u(), s.control_point_count_u() + 2 * 2);
  EXPECT_EQ(finer.control_point_count_v(), s.control_point_count_v() + 4 * 1);
  std::mt19937 generator(17);
  for (int k = 0; k < 100; ++k) {
    const double u = random_real(generator, 0, 1);
    const double v = random_real(generator, 0, 1);
    EXPECT_LT((finer.point(u, v) - s.point(u, v)).norm(), 1e-14);
    EXPECT_NEAR(finer.point(u, v).norm(), 1.5, 1e-14);
  }
  const NurbsCurve line = greville_line({0, 0, 0}, {1, 0, 0}, 4, 3);
  EXPECT_EQ(split_spans(line, 4).control_point_count(), 7);
  EXPECT_THAT(error_message([&] { split_spans(line, 0); }), HasSubstr("parts must be >= 1"));
}

}  // namespace
}  // namespace dnurbs
