// NURBS curves and surfaces in Wavefront OBJ free-form geometry: exact round trips of random
// shapes (open, clamped or not, periodic, rational or not), files written by hand as another
// tool would write them, mixed mesh and free-form files, and every malformed input refused
// with its line and value.
#include "dnurbs/io/obj_freeform.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/io/shape_file.h"
#include "tests/common/error_message.h"
#include "tests/nurbs/random_shapes.h"

namespace dnurbs {
namespace {

using testing::error_message;
using ::testing::HasSubstr;
using testing::random_curve;
using testing::random_surface;
using ::testing::StartsWith;
using testing::test_parameters;
using testing::trial_options;

TEST(ObjFreeform, RandomCurvesRoundTripExactly) {
  std::mt19937 generator(73);
  std::vector<Shape> shapes;
  for (int trial = 0; trial < 60; ++trial) {
    const int degree = 1 + trial % 5;
    testing::RandomKnotOptions options = trial_options(trial, degree, true);
    options.extra_control_points = trial % 3;
    shapes.emplace_back(random_curve(degree, options, trial % 3 != 1, generator));
  }
  // All in one file: the vertex numbering runs on from shape to shape.
  const std::vector<Shape> read = parse_obj_freeform(shapes_to_obj(shapes));
  ASSERT_EQ(read.size(), shapes.size());
  int periodic = 0;
  int unclamped = 0;
  int rational = 0;
  for (size_t k = 0; k < shapes.size(); ++k) {
    const auto& curve = std::get<NurbsCurve>(shapes[k]);
    ASSERT_TRUE(std::holds_alternative<NurbsCurve>(read[k])) << "curve " << k;
    const auto& back = std::get<NurbsCurve>(read[k]);
    periodic += curve.is_periodic() ? 1 : 0;
    unclamped += !curve.is_periodic() && curve.knots()[0] < curve.knots().domain_start() ? 1 : 0;
    rational += curve.is_rational() ? 1 : 0;
    EXPECT_EQ(back.is_periodic(), curve.is_periodic()) << "curve " << k;
    EXPECT_EQ(back.knots(), curve.knots()) << "curve " << k;
    EXPECT_EQ(back.control_points(), curve.control_points()) << "curve " << k;
    EXPECT_EQ(back.weights(), curve.weights()) << "curve " << k;
    for (const double u : test_parameters(curve.knots(), 16)) {
      EXPECT_EQ(back.point(u), curve.point(u)) << "curve " << k << " at u = " << u;
    }
  }
  EXPECT_EQ(periodic, 30);
  EXPECT_GT(unclamped, 0);
  EXPECT_EQ(rational, 40);
}

TEST(ObjFreeform, RandomSurfacesRoundTripExactly) {
  std::mt19937 generator(74);
  std::vector<Shape> shapes;
  for (int trial = 0; trial < 30; ++trial) {
    // Different degrees, counts and kinds along u and v: a transposed net cannot pass.
    const int degree_u = 1 + trial % 5;
    const int degree_v = 1 + (trial + 2) % 5;
    testing::RandomKnotOptions options_u = trial_options(trial, degree_u, true);
    testing::RandomKnotOptions options_v = trial_options(trial / 2 + 1, degree_v, true);
    options_u.extra_control_points = 1;
    options_v.extra_control_points = 2 + trial % 2;
    shapes.emplace_back(
        random_surface(degree_u, degree_v, options_u, options_v, trial % 2 == 0, generator));
  }
  const std::vector<Shape> read = parse_obj_freeform(shapes_to_obj(shapes));
  ASSERT_EQ(read.size(), shapes.size());
  int periodic_u = 0;
  int periodic_v = 0;
  for (size_t k = 0; k < shapes.size(); ++k) {
    const auto& surface = std::get<NurbsSurface>(shapes[k]);
    ASSERT_TRUE(std::holds_alternative<NurbsSurface>(read[k])) << "surface " << k;
    const auto& back = std::get<NurbsSurface>(read[k]);
    periodic_u += surface.knots_u().is_periodic() ? 1 : 0;
    periodic_v += surface.knots_v().is_periodic() ? 1 : 0;
    EXPECT_EQ(back.knots_u(), surface.knots_u()) << "surface " << k;
    EXPECT_EQ(back.knots_v(), surface.knots_v()) << "surface " << k;
    EXPECT_EQ(back.control_points(), surface.control_points()) << "surface " << k;
    EXPECT_EQ(back.weights(), surface.weights()) << "surface " << k;
    for (const double u : test_parameters(surface.knots_u(), 5)) {
      for (const double v : test_parameters(surface.knots_v(), 5)) {
        EXPECT_EQ(back.point(u, v), surface.point(u, v))
            << "surface " << k << " at " << u << ", " << v;
      }
    }
  }
  EXPECT_GT(periodic_u, 0);
  EXPECT_GT(periodic_v, 0);
  EXPECT_LT(periodic_u + periodic_v, 60);
}

TEST(ObjFreeform, WritesTheStatementsOfTheSpecification) {
  // A rational quarter circle, a bilinear surface with 2 x 3 control points, and a periodic
  // quadratic curve (written open: its first 2 control points repeated, the extended knots).
  Eigen::MatrixX3d arc(3, 3);
  arc << 1, 0, 0, 1, 1, 0, 0, 1, 0;
  const NurbsCurve quarter(KnotVector(2, {0, 0, 0, 1, 1, 1}), arc,
                           Eigen::Vector3d(1, std::sqrt(0.5), 1));
  Eigen::MatrixX3d net(6, 3);  // (i, j) at row 3 i + j
  net << 0, 0, 0, 0, 1, 0, 0, 2, 1, 1, 0, 0, 1, 1, 0, 1, 2, 1;
  const NurbsSurface sheet(KnotVector(1, {0, 0, 1, 1}), KnotVector(1, {0, 0, 0.5, 1, 1}), net);
  Eigen::MatrixX3d triangle(3, 3);
  triangle << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  const NurbsCurve loop(KnotVector::periodic_uniform(2, 3, 0, 3), triangle);
  EXPECT_EQ(shapes_to_obj({quarter, sheet, loop}),
            "# NURBS curves and surfaces as OBJ free-form geometry, written by dnurbs\n"
            "v 1 0 0 1\n"
            "v 1 1 0 0.7071067811865476\n"
            "v 0 1 0 1\n"
            "cstype rat bspline\n"
            "deg 2\n"
            "curv 0 1 1 2 3\n"
            "parm u 0 0 0 1 1 1\n"
            "end\n"
            // u fastest: (0, 0) (1, 0) (0, 1) (1, 1) (0, 2) (1, 2)
            "v 0 0 0\n"
            "v 1 0 0\n"
            "v 0 1 0\n"
            "v 1 1 0\n"
            "v 0 2 1\n"
            "v 1 2 1\n"
            "cstype bspline\n"
            "deg 1 1\n"
            "surf 0 1 0 1 4 5 6 7 8 9\n"
            "parm u 0 0 1 1\n"
            "parm v 0 0 0.5 1 1\n"
            "end\n"
            "v 0 0 0\n"
            "v 1 0 0\n"
            "v 0 1 0\n"
            "v 0 0 0\n"
            "v 1 0 0\n"
            "cstype bspline\n"
            "deg 2\n"
            "curv 0 3 10 11 12 13 14\n"
            "parm u -2 -1 0 1 2 3 4 5\n"
            "end\n");
}

TEST(ObjFreeform, ReadsAHandWrittenRationalCircle) {
  // The unit circle as 4 rational quadratic quarters (weights cos 45 degrees at the corners),
  // referenced backwards from the curv statement, its parm line continued with a backslash.
  const std::string text =
      "# unit circle\n"
      "o circle\n"
      "v 1.0 0.0 0.0\n"
      "v 1.0 1.0 0.0 0.70710678118654752\n"
      "v 0.0 1.0 0.0\n"
      "v -1.0 1.0 0.0 0.70710678118654752\n"
      "v -1.0 0.0 0.0\n"
      "v -1.0 -1.0 0.0 0.70710678118654752\n"
      "v 0.0 -1.0 0.0\n"
      "v 1.0 -1.0 0.0 0.70710678118654752\n"
      "v 1.0 0.0 0.0\n"
      "\n"
      "cstype rat bspline\n"
      "deg 2\n"
      "curv 0.0 4.0 -9 -8 -7 -6 -5 -4 -3 -2 -1\n"
      "parm u 0.0 0.0 0.0 1.0 1.0 2.0 2.0 3.0 3.0 \\\n"
      "       4.0 4.0 4.0\n"
      "end\n";
  ASSERT_TRUE(has_obj_freeform(text));
  const std::vector<Shape> shapes = parse_obj_freeform(text, "circle.obj");
  ASSERT_EQ(shapes.size(), 1U);
  const auto& circle = std::get<NurbsCurve>(shapes[0]);
  EXPECT_EQ(circle.degree(), 2);
  EXPECT_EQ(circle.control_point_count(), 9);
  EXPECT_FALSE(circle.is_periodic());  // clamped ends: closed, not periodic
  EXPECT_TRUE(circle.is_rational());
  EXPECT_EQ(circle.weights()(1), std::sqrt(0.5));
  EXPECT_EQ(circle.knots().knots(), std::vector<double>({0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4}));
  for (int k = 0; k <= 400; ++k) {
    const double u = k / 100.0;
    const Eigen::Vector3d point = circle.point(u);
    EXPECT_NEAR(point.norm(), 1.0, 1e-15) << "u = " << u;
    EXPECT_EQ(point.z(), 0.0);
  }
  // Quarter points and the middle of the first quarter (at 45 degrees)
  EXPECT_LT((circle.point(1.0) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-15);
  EXPECT_LT((circle.point(2.0) - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((circle.point(3.0) - Eigen::Vector3d(0, -1, 0)).norm(), 1e-15);
  EXPECT_LT((circle.point(0.5) - Eigen::Vector3d(std::sqrt(0.5), std::sqrt(0.5), 0)).norm(), 1e-15);
}

TEST(ObjFreeform, ReadsAHandWrittenBicubicPatchWithUFastestVertices) {
  // Control point (i, j) = (x_i, y_j, x_i y_j) with x_i six times the Greville abscissae of the
  // u knots (0 1/6 1/2 5/6 1) and y_j three times those of the v knots, so by linear precision
  // S(u, v) = (6u, 3v, 18uv). 5 x 4 vertices listed with i (u) varying fastest (Appendix B1,
  // "Surface vertex data"), referenced backwards.
  const std::string text =
      "g patch\n"
      "v 0 0 0\nv 1 0 0\nv 3 0 0\nv 5 0 0\nv 6 0 0\n"
      "v 0 1 0\nv 1 1 1\nv 3 1 3\nv 5 1 5\nv 6 1 6\n"
      "v 0 2 0\nv 1 2 2\nv 3 2 6\nv 5 2 10\nv 6 2 12\n"
      "v 0 3 0\nv 1 3 3\nv 3 3 9\nv 5 3 15\nv 6 3 18\n"
      "cstype bspline\n"
      "deg 3 3\n"
      "surf 0.0 1.0 0.0 1.0 -20 -19 -18 -17 -16 -15 -14 -13 -12 -11 \\\n"
      "  -10 -9 -8 -7 -6 -5 -4 -3 -2 -1\n"
      "parm u 0 0 0 0 0.5 1 1 1 1\n"
      "parm v 0 0 0 0 1 1 1 1\n"
      "end\n";
  const std::vector<Shape> shapes = parse_obj_freeform(text);
  ASSERT_EQ(shapes.size(), 1U);
  const auto& patch = std::get<NurbsSurface>(shapes[0]);
  ASSERT_EQ(patch.control_point_count_u(), 5);
  ASSERT_EQ(patch.control_point_count_v(), 4);
  EXPECT_FALSE(patch.is_rational());
  const double x[] = {0, 1, 3, 5, 6};
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 4; ++j) {
      EXPECT_EQ(Eigen::Vector3d(patch.control_points().row(patch.control_point_index(i, j))),
                Eigen::Vector3d(x[i], j, x[i] * j))
          << "control point " << i << ", " << j;
    }
  }
  for (int a = 0; a <= 10; ++a) {
    for (int b = 0; b <= 10; ++b) {
      const double u = a / 10.0;
      const double v = b / 10.0;
      EXPECT_LT((patch.point(u, v) - Eigen::Vector3d(6 * u, 3 * v, 18 * u * v)).norm(), 1e-13)
          << "at " << u << ", " << v;
    }
  }
}

TEST(ObjFreeform, MixedMeshAndFreeFormFileGivesOnlyTheFreeFormShapes) {
  const std::string mesh =
      "mtllib scene.mtl\n"
      "o part\n"
      "g side\n"
      "v 0 0 0\n"
      "v 1 0 0\n"
      "v 1 1 0 \n"
      "v 0 1 0 0.2 0.4 0.6\n"  // vertex colour extension
      "vt 0 0\n"
      "vt 1 0\n"
      "vt 1 1\n"
      "vn 0 0 1\n"
      "usemtl red\n"
      "s 1\n"
      "f 1/1/1 2/2/1 3/3/1\n"
      "f -4 -2 -1\n"
      "l 1 2 \\\n"
      "  curv 0 1 1 2 3\n"  // continues the l statement: no curv
      "p 3\n"
      "# curv 0 1 1 2 3\n";
  EXPECT_FALSE(has_obj_freeform(mesh));
  EXPECT_TRUE(parse_obj_freeform(mesh).empty());
  const std::string mixed = mesh +
                            "cstype bspline\n"
                            "ctech cparm 1.0\n"
                            "deg 2\n"
                            "curv 0 1 1/1 2/2/1 3//1\n"
                            "parm u 0 0 0 1 1 1\n"
                            "end\n"
                            "f 1 2 3 4\n"
                            "parm u 5 6\n"  // outside a block: no effect
                            "end\n";
  EXPECT_TRUE(has_obj_freeform(mixed));
  const std::vector<Shape> shapes = parse_obj_freeform(mixed);
  ASSERT_EQ(shapes.size(), 1U);
  const auto& curve = std::get<NurbsCurve>(shapes[0]);
  Eigen::MatrixX3d expected(3, 3);
  expected << 0, 0, 0, 1, 0, 0, 1, 1, 0;
  EXPECT_EQ(curve.control_points(), expected);
  EXPECT_EQ(curve.weights(), Eigen::Vector3d::Ones());
  EXPECT_EQ(curve.point(0.5), Eigen::Vector3d(0.75, 0.25, 0));
}

TEST(ObjFreeform, WeightsAreReadForRationalShapesOnly) {
  const std::string vertices = "v 0 0 0 2\nv 1 0 0 3\nv 1 1 0\n";
  const std::string body = "deg 2\ncurv 0 1 1 2 3\nparm u 0 0 0 1 1 1\nend\n";
  const auto rational =
      std::get<NurbsCurve>(parse_obj_freeform(vertices + "cstype rat bspline\n" + body).at(0));
  EXPECT_EQ(rational.weights(), Eigen::Vector3d(2, 3, 1));
  // "w ... is not required for non-rational curves and surfaces" (Appendix B1): ignored
  const auto polynomial =
      std::get<NurbsCurve>(parse_obj_freeform(vertices + "cstype bspline\n" + body).at(0));
  EXPECT_EQ(polynomial.weights(), Eigen::Vector3d::Ones());
}

TEST(ObjFreeform, ParameterRangeMayDifferFromTheDomainByRoundOffOnly) {
  const auto text = [](const std::string& range) {
    return "v 0 0 0\nv 1 0 0\nv 1 1 0\ncstype bspline\ndeg 2\ncurv " + range +
           " 1 2 3\nparm u 10 10 10 11 11 11\nend\n";
  };
  EXPECT_EQ(parse_obj_freeform(text("10.000000000001 11")).size(), 1U);
  EXPECT_EQ(parse_obj_freeform(text("10 10.99999999999999")).size(), 1U);
  EXPECT_THAT(error_message([&] { parse_obj_freeform(text("10 10.9999999999")); }),
              HasSubstr("line 6: curv parameter range 10 10.9999999999 in u is not the domain 10 "
                        "11 of parm u: trimming is not supported"));
}

// Three vertices (lines 1-3), then cstype and deg (lines 4-5) and a curv block (lines 6-8).
const std::string kVertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\n";
const std::string kHeader = kVertices + "cstype bspline\ndeg 2\n";
const std::string kKnots = "parm u 0 0 0 1 1 1\n";

struct MalformedCase {
  std::string text;
  std::vector<std::string> expected;  // substrings of the message
};

TEST(ObjFreeform, MalformedTextIsRefusedNamingTheLineAndValue) {
  const std::string surface_head = kVertices + "v 0 1 0\ncstype bspline\ndeg 1 1\n";  // 1-6
  const std::vector<MalformedCase> cases = {
      // cstype
      {kVertices + "cstype nurbs\n", {"line 4: unknown cstype \"nurbs\""}},
      {kVertices + "cstype bezier\n", {"line 4: cstype bezier is not supported"}},
      {kVertices + "cstype rat cardinal\n", {"line 4: cstype cardinal is not supported"}},
      {kVertices + "cstype taylor\n", {"line 4: cstype taylor is not supported"}},
      {kVertices + "cstype bmatrix\n", {"line 4: cstype bmatrix is not supported"}},
      {kVertices + "deg 2\ncurv 0 1 1 2 3\n", {"line 5: curv without a cstype"}},
      // deg
      {kVertices + "cstype bspline\ncurv 0 1 1 2 3\n", {"line 5: curv without a deg"}},
      {kHeader + "surf 0 1 0 1 1 2 3 1\n", {"line 6: surf without a deg", "deg p q"}},
      {kVertices + "deg 16\n", {"line 4: expected a degree in 1..15, got 16"}},
      {kVertices + "deg 0\n", {"line 4:", "got 0"}},
      {kVertices + "deg 2.5\n", {"line 4: expected an integer degree, got \"2.5\""}},
      {kVertices + "deg 1 2 3\n", {"line 4:", "deg 1 2 3"}},
      // vertex indices: 1-based, negative ones counted back from the statement
      {kHeader + "curv 0 1 1 2 4\n", {"line 6: vertex index 4 is out of range (3 v statements"}},
      {kHeader + "curv 0 1 -4 2 3\n", {"line 6: vertex index -4 is out of range"}},
      {kHeader + "curv 0 1 0 1 2\n", {"line 6: vertex index 0 is out of range"}},
      {kHeader + "curv 0 1 1 2 x\n", {"line 6: expected a vertex index, got \"x\""}},
      {kHeader + "curv 0 1 1 2 99999999999999999999\n",
       {"line 6: expected a vertex index, got \"99999999999999999999\""}},
      {kHeader + "curv 0 1 1\n", {"line 6:", "at least two vertices"}},
      // knots
      {kHeader + "curv 0 1 1 2 3\nparm u 0 0 0 1 1\nend\n",
       {"line 7: parm u has 5 knots, expected 6 (3 control points + degree 2 + 1)"}},
      {kHeader + "curv 0 1 1 2 3\nparm u 0 0 1 0 1 1\nend\n", {"line 7: invalid knots in parm u:"}},
      {surface_head + "surf 0 1 0 1 1 2 3 4\nparm u 0 0 1 1\nparm v 0 0 0.5 1 1\nend\n",
       {"line 7: surf has 4 control vertices", "parm u (4 knots", "parm v (5 knots", "give 2 x 3"}},
      {kHeader + "curv 0 1 1 2 3\nend\n", {"line 6: curv has no parm u statement"}},
      {surface_head + "surf 0 1 0 1 1 2 3 4\nparm u 0 0 1 1\nend\n",
       {"line 7: surf has no parm v statement"}},
      {kHeader + "curv 0 1 1 2 3\nparm v 0 0 0 1 1 1\n", {"line 7: expected parm u in a curv"}},
      {kHeader + "curv 0 1 1 2 3\n" + kKnots + kKnots,
       {"line 8: a second parm u (the first is on line 7)"}},
      // numbers
      {"v 0 0 0\nv 1 nan 0\n", {"line 2: expected a finite number, got nan"}},
      {"v 0 0 0\nv 1 0 -inf\n", {"line 2: expected a finite number, got -inf"}},
      {"v 1e999 0 0\n", {"line 1: the number 1e999 is out of the range of doubles"}},
      {"v 1 abc 0\n", {"line 1: expected a number, got \"abc\""}},
      {"v 1 0\n", {"line 1: expected v x y z [w], got \"v 1 0\""}},
      {kHeader + "curv 0 1 1 2 3\nparm u 0 0 0 1 1 inf\nend\n",
       {"line 7: expected a finite number, got inf"}},
      {kHeader + "curv 0 nan 1 2 3\n", {"line 6: expected a finite number, got nan"}},
      // weights
      {"v 0 0 0\nv 1 0 0 0\n", {"line 2: expected a weight w > 0, got 0"}},
      {"v 1 0 0 -2\n", {"line 1: expected a weight w > 0, got -2"}},
      // parameter ranges other than the domain: trimming
      {kHeader + "curv 0 0.5 1 2 3\n" + kKnots + "end\n",
       {"line 6: curv parameter range 0 0.5 in u is not the domain 0 1",
        "trimming is not supported"}},
      {surface_head + "surf 0 1 0 2 1 2 3 4\nparm u 0 0 1 1\nparm v 0 0 1 1\nend\n",
       {"line 7: surf parameter range 0 2 in v", "trimming is not supported"}},
      // trimming loops, special curves and points, 2-D curves
      {surface_head + "surf 0 1 0 1 1 2 3 4\nparm u 0 0 1 1\nparm v 0 0 1 1\ntrim 0 1 1\n",
       {"line 10: trimmed surfaces are not supported (a trim statement in the surf of line 7)"}},
      {surface_head + "surf 0 1 0 1 1 2 3 4\nhole 0 1 1\n",
       {"line 8: trimmed surfaces are not supported (a hole"}},
      {surface_head + "surf 0 1 0 1 1 2 3 4\nscrv 0 1 1\n",
       {"line 8: trimmed surfaces are not supported (a scrv"}},
      {surface_head + "surf 0 1 0 1 1 2 3 4\nsp 1\n",
       {"line 8: trimmed surfaces are not supported (a sp"}},
      {"vp 0 0\nvp 1 1\ncstype bspline\ndeg 1\ncurv2 1 2\n", {"line 5: curv2", "not supported"}},
      // blocks without end
      {kHeader + "curv 0 1 1 2 3\n" + kKnots, {"line 6: curv has no end statement"}},
      {kHeader + "curv 0 1 1 2 3\n" + kKnots + "curv 0 1 1 2 3\n",
       {"line 6: curv has no end statement (line 8 starts a curv)"}},
      // a statement continued over lines is named by its first line
      {"v 0 0 0\nv 1 \\\n  0 \\\n  0\nv 1 1 nan\n", {"line 5: expected a finite number"}},
      {"v 0 0 0\n\\\nv 1 \\\n  x 0\n", {"line 3: expected a number, got \"x\""}},
  };
  for (const MalformedCase& malformed : cases) {
    SCOPED_TRACE(malformed.text);
    const std::string message =
        error_message([&] { parse_obj_freeform(malformed.text, "part.obj"); });
    EXPECT_THAT(message, StartsWith("part.obj: line "));
    for (const std::string& expected : malformed.expected) {
      EXPECT_THAT(message, HasSubstr(expected));
    }
  }
}

TEST(ObjFreeform, HostileStatementsAreRefusedQuickly) {
  std::string knots = "parm u";
  std::string vertices = "curv 0 1";
  for (int k = 0; k <= kObjMaxValues; ++k) {
    knots += " 0";
    vertices += " 1";
  }
  EXPECT_THAT(error_message([&] { parse_obj_freeform(kHeader + "curv 0 1 1 2 3\n" + knots); }),
              HasSubstr("line 7: parm u has more than 10000000 knots (the limit)"));
  EXPECT_THAT(error_message([&] { parse_obj_freeform(kHeader + vertices); }),
              HasSubstr("line 6: curv has more than 10000000 vertices (the limit)"));
  // Two million empty continued lines are read in linear time; the statement after them is
  // named by its own line.
  std::string continued;
  for (int k = 0; k < 2'000'000; ++k) {
    continued += "\\\n";
  }
  EXPECT_THAT(error_message([&] { parse_obj_freeform(continued + "v 1 x 0\n"); }),
              HasSubstr("line 2000001: expected a number, got \"x\""));
}

TEST(ObjFreeform, FilesRoundTrip) {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("dnurbs_test_obj_freeform_" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  std::mt19937 generator(75);
  const NurbsCurve curve = random_curve(3, trial_options(0, 3, false), true, generator);
  const NurbsSurface surface = random_surface(2, 3, trial_options(1, 2, false),
                                              trial_options(2, 3, false), false, generator);
  const auto path = directory / "shapes.obj";
  write_obj_freeform_file(path, {curve, surface});
  const std::vector<Shape> read = read_obj_freeform_file(path);
  ASSERT_EQ(read.size(), 2U);
  EXPECT_EQ(std::get<NurbsCurve>(read[0]).control_points(), curve.control_points());
  EXPECT_EQ(std::get<NurbsCurve>(read[0]).knots(), curve.knots());
  EXPECT_EQ(std::get<NurbsSurface>(read[1]).control_points(), surface.control_points());
  EXPECT_EQ(std::get<NurbsSurface>(read[1]).knots_v(), surface.knots_v());
  // Errors name the file
  const auto bad = directory / "bad.obj";
  std::ofstream(bad) << "v 0 0 0\nv 1 0 0 -1\n";
  EXPECT_THAT(error_message([&] { read_obj_freeform_file(bad); }),
              StartsWith(bad.string() + ": line 2: expected a weight w > 0, got -1"));
  EXPECT_THAT(error_message([&] { read_obj_freeform_file(directory / "missing.obj"); }),
              HasSubstr("missing.obj"));
  // A shape file may be an OBJ of one free-form shape; exchange files of several are split.
  write_obj_freeform_file(directory / "one.obj", {surface});
  EXPECT_EQ(std::get<NurbsSurface>(read_shape_file(directory / "one.obj")).control_points(),
            surface.control_points());
  EXPECT_EQ(read_exchange_shapes(path).size(), 2U);
  EXPECT_THAT(error_message([&] { read_shape_file(path); }),
              HasSubstr("shapes.obj: the file holds 2 curves and surfaces, and a shape file is "
                        "one"));
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace dnurbs
