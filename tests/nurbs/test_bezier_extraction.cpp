#include "dnurbs/nurbs/bezier_extraction.h"

#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/common/error_message.h"
#include "tests/nurbs/random_shapes.h"

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/bernstein.h"
#include "dnurbs/nurbs/knot_insertion.h"

namespace dnurbs {
namespace {

// The Bezier form and de Boor's algorithm evaluate the same polynomial from convex combinations
// of homogeneous points of size up to 20: a few ulps of that.
constexpr double kRoundOff = 1e-13;

// Point of a homogeneous Bezier segment ((p + 1) by 4) at t.
Eigen::Vector3d bezier_point(const Eigen::MatrixXd& bezier, double t) {
  std::array<double, kMaxBernsteinDegree + 1> basis{};
  bernstein_values(static_cast<int>(bezier.rows()) - 1, t, basis.data());
  Eigen::Vector4d h = Eigen::Vector4d::Zero();
  for (Eigen::Index i = 0; i < bezier.rows(); ++i) {
    h += basis[static_cast<size_t>(i)] * bezier.row(i).transpose();
  }
  return h.head<3>() / h[3];
}

Eigen::MatrixXd homogeneous(const Eigen::MatrixX3d& points, const Eigen::VectorXd& weights) {
  Eigen::MatrixXd rows(points.rows(), 4);
  rows.leftCols<3>() = points.array().colwise() * weights.array();
  rows.col(3) = weights;
  return rows;
}

TEST(BezierExtraction, SegmentsReproduceRandomCurvesOnEverySpan) {
  std::mt19937 generator(6001U);
  for (int trial = 0; trial < 1000; ++trial) {
    const int degree = 1 + trial % 7;
    const NurbsCurve curve = testing::random_curve(
        degree, testing::trial_options(trial, degree, true), trial % 3 != 0, generator);
    const Eigen::MatrixXd rows = homogeneous(curve.control_points(), curve.weights());
    for (const int span : curve.knots().non_empty_spans()) {
      const Eigen::MatrixXd bezier = bezier_segment(curve.knots(), rows, span);
      const double start = curve.knots()[span];
      const double end = curve.knots()[span + 1];
      for (const double t : {0.0, 0.25, 0.6, 1.0}) {
        EXPECT_LT((bezier_point(bezier, t) - curve.point(start + t * (end - start))).norm(),
                  kRoundOff)
            << "trial " << trial << " span " << span << " t " << t;
      }
    }
  }
}

TEST(BezierExtraction, PatchesReproduceRandomSurfaces) {
  std::mt19937 generator(6002U);
  for (int trial = 0; trial < 200; ++trial) {
    const int degree_u = 1 + trial % 5;
    const int degree_v = 1 + (trial / 5) % 4;
    const NurbsSurface surface = testing::random_surface(
        degree_u, degree_v, testing::trial_options(trial, degree_u, true),
        testing::trial_options(trial / 2, degree_v, true), trial % 3 != 0, generator);
    const Eigen::MatrixXd rows = homogeneous(surface.control_points(), surface.weights());
    for (const int span_u : surface.knots_u().non_empty_spans()) {
      for (const int span_v : surface.knots_v().non_empty_spans()) {
        const Eigen::MatrixXd patch =
            bezier_patch(surface.knots_u(), surface.knots_v(), rows, span_u, span_v);
        // Along v = v0 + 0.3 (v1 - v0): the u-columns blended in v give a Bezier curve in u.
        const double v = surface.knots_v()[span_v] +
                         0.3 * (surface.knots_v()[span_v + 1] - surface.knots_v()[span_v]);
        std::array<double, kMaxBernsteinDegree + 1> basis{};
        bernstein_values(degree_v, 0.3, basis.data());
        Eigen::MatrixXd iso = Eigen::MatrixXd::Zero(degree_u + 1, 4);
        for (int a = 0; a <= degree_u; ++a) {
          for (int b = 0; b <= degree_v; ++b) {
            iso.row(a) += basis[static_cast<size_t>(b)] * patch.row(a * (degree_v + 1) + b);
          }
        }
        for (const double t : {0.0, 0.5, 1.0}) {
          const double u = surface.knots_u()[span_u] +
                           t * (surface.knots_u()[span_u + 1] - surface.knots_u()[span_u]);
          EXPECT_LT((bezier_point(iso, t) - surface.point(u, v)).norm(), kRoundOff)
              << "trial " << trial;
        }
      }
    }
  }
}

TEST(BezierExtraction, RejectsEmptyOrOutsideSpans) {
  const KnotVector knots(2, {0, 0, 0, 0.5, 0.5, 1, 1, 1});
  const Eigen::MatrixXd rows = Eigen::MatrixXd::Random(5, 4);
  EXPECT_THAT(testing::error_message([&] { bezier_segment(knots, rows, 3); }),
              ::testing::HasSubstr("span 3 is not a non-empty span"));
  EXPECT_THAT(testing::error_message([&] { bezier_segment(knots, rows, 5); }),
              ::testing::HasSubstr("span 5"));
}

}  // namespace
}  // namespace dnurbs
