// Exact conversion to and from Open CASCADE's B-spline geometry: both libraries evaluate the
// same points, and the conversion back gives the same knots, weights and control points.
#include "dnurbs/cad/occt_nurbs.h"

#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <GeomConvert.hxx>
#include <Geom_BezierCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>

#include "dnurbs/core/error.h"
#include "tests/cad/cad_test_shapes.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

using testing::relative_difference;

Eigen::Vector3d vector(const gp_Pnt& point) {
  return {point.X(), point.Y(), point.Z()};
}

TEST(OcctNurbs, RandomCurvesEvaluateAlikeAndConvertBackExactly) {
  // Periodic curves with the seam copies anywhere in their period list: they come back in the
  // seam-first form Open CASCADE keeps, the same curve with its control points renumbered.
  std::mt19937 generator(2611);
  for (int trial = 0; trial < 60; ++trial) {
    const int degree = 1 + trial % 5;
    testing::RandomKnotOptions options = testing::trial_options(trial, degree, true);
    options.extra_control_points = 2;
    const Shape shape(testing::random_curve(degree, options, trial % 3 != 1, generator));
    const NurbsCurve& curve = std::get<NurbsCurve>(shape);
    const Handle(Geom_BSplineCurve) occt = to_occt(curve);
    EXPECT_EQ(occt->IsPeriodic(), curve.is_periodic());
    EXPECT_EQ(occt->IsRational(), curve.is_rational());
    EXPECT_DOUBLE_EQ(occt->FirstParameter(), curve.knots().domain_start());
    EXPECT_DOUBLE_EQ(occt->LastParameter(), curve.knots().domain_end());
    double error = 0.0;
    for (const double u : testing::test_parameters(curve.knots(), 32)) {
      error = std::max(error, relative_difference(curve.point(u), vector(occt->Value(u))));
    }
    // Two evaluations of one rational sum in different orders: round-off only.
    EXPECT_LT(error, 1e-13) << "degree " << curve.degree() << " periodic " << curve.is_periodic();
    EXPECT_EQ(
        testing::shape_difference(testing::seam_first_form(shape), Shape(from_occt(*occt))).data,
        0.0);
  }
}

TEST(OcctNurbs, RandomSurfacesEvaluateAlikeAndConvertBackExactly) {
  std::mt19937 generator(2612);
  for (int trial = 0; trial < 24; ++trial) {
    const int degree_u = 1 + trial % 4;
    const int degree_v = 1 + (trial + 2) % 5;
    testing::RandomKnotOptions options_u = testing::trial_options(trial, degree_u, true);
    testing::RandomKnotOptions options_v = testing::trial_options(trial / 2 + 1, degree_v, true);
    options_u.extra_control_points = 1;
    options_v.extra_control_points = 2;
    const Shape shape(testing::random_surface(degree_u, degree_v, options_u, options_v,
                                              trial % 2 == 0, generator));
    const NurbsSurface& surface = std::get<NurbsSurface>(shape);
    const Handle(Geom_BSplineSurface) occt = to_occt(surface);
    EXPECT_EQ(occt->IsUPeriodic(), surface.knots_u().is_periodic());
    EXPECT_EQ(occt->IsVPeriodic(), surface.knots_v().is_periodic());
    double error = 0.0;
    for (const double u : testing::test_parameters(surface.knots_u(), 8)) {
      for (const double v : testing::test_parameters(surface.knots_v(), 8)) {
        error =
            std::max(error, relative_difference(surface.point(u, v), vector(occt->Value(u, v))));
      }
    }
    EXPECT_LT(error, 1e-13);
    EXPECT_EQ(
        testing::shape_difference(testing::seam_first_form(shape), Shape(from_occt(*occt))).data,
        0.0);
  }
}

TEST(OcctNurbs, AnOpenFormFromAnotherToolComesBackPeriodic) {
  // A closed unclamped cubic as a STEP or IGES file carries it: 5 distinct points, the first 3
  // repeated, uniform knots. Open CASCADE keeps it open; dnurbs reads it periodic.
  TColgp_Array1OfPnt poles(1, 8);
  for (int i = 1; i <= 8; ++i) {
    const int k = (i - 1) % 5;
    poles(i) = gp_Pnt(std::cos(1.2566 * k), std::sin(1.2566 * k), 0.1 * k);
  }
  TColStd_Array1OfReal knots(1, 12);
  TColStd_Array1OfInteger multiplicities(1, 12);
  for (int i = 1; i <= 12; ++i) {
    knots(i) = 0.25 * (i - 4);
    multiplicities(i) = 1;
  }
  const Geom_BSplineCurve occt(poles, knots, multiplicities, 3, false);
  const NurbsCurve curve = from_occt(occt);
  ASSERT_TRUE(curve.is_periodic());
  EXPECT_EQ(curve.control_point_count(), 5);
  for (const double u : {0.0, 0.3, 0.77, 1.1, 1.25}) {
    EXPECT_LT(relative_difference(curve.point(u), vector(occt.Value(u))), 1e-14) << u;
  }
}

TEST(OcctNurbs, ADegreeAboveTheLimitIsNamed) {
  TColgp_Array1OfPnt poles(1, 21);
  for (int i = 1; i <= 21; ++i) {
    poles(i) = gp_Pnt(i, std::sin(i), 0.0);
  }
  const Handle(Geom_BSplineCurve) occt =
      GeomConvert::CurveToBSplineCurve(new Geom_BezierCurve(poles));
  EXPECT_THAT(testing::error_message([&] { from_occt(*occt); }),
              ::testing::HasSubstr("degree 20 is above the highest dnurbs supports (15)"));
}

}  // namespace
}  // namespace dnurbs
