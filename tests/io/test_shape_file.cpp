#include "dnurbs/io/shape_file.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/primitive_shapes.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

void expect_same_curve(const NurbsCurve& a, const NurbsCurve& b) {
  EXPECT_EQ(a.knots(), b.knots());
  EXPECT_EQ(a.control_points(), b.control_points());
  EXPECT_EQ(a.weights(), b.weights());
}

void expect_same_surface(const NurbsSurface& a, const NurbsSurface& b) {
  EXPECT_EQ(a.knots_u(), b.knots_u());
  EXPECT_EQ(a.knots_v(), b.knots_v());
  EXPECT_EQ(a.control_points(), b.control_points());
  EXPECT_EQ(a.weights(), b.weights());
}

// A fresh empty directory under the system temporary directory
std::filesystem::path fresh_directory(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("dnurbs_test_shape_file_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory;
}

TEST(ShapeFile, RationalCurveRoundTripsExactly) {
  // Irrational weights and coordinates: the text must keep all 17 significant digits
  NurbsCurve curve = full_circle(1.0 / 3.0, Eigen::Vector3d(0.1, -2.0 / 7.0, 1e-300));
  const Shape read = parse_shape_json(shape_to_json(curve), "circle");
  ASSERT_TRUE(std::holds_alternative<NurbsCurve>(read));
  expect_same_curve(std::get<NurbsCurve>(read), curve);
  EXPECT_EQ(std::get<NurbsCurve>(read).point(0.3), curve.point(0.3));
}

TEST(ShapeFile, PeriodicCurveAndSurfaceRoundTripThroughFiles) {
  const auto directory = fresh_directory("round_trip");
  const NurbsCurve circle = periodic_circle(std::sqrt(2.0));
  write_shape_file(directory / "circle.json", circle);
  const Shape curve = read_shape_file(directory / "circle.json");
  ASSERT_TRUE(std::holds_alternative<NurbsCurve>(curve));
  EXPECT_TRUE(std::get<NurbsCurve>(curve).is_periodic());
  expect_same_curve(std::get<NurbsCurve>(curve), circle);

  const NurbsSurface torus = periodic_torus(2.0, std::sqrt(0.1));
  write_shape_file(directory / "torus.json", torus);
  const Shape surface = read_shape_file(directory / "torus.json");
  ASSERT_TRUE(std::holds_alternative<NurbsSurface>(surface));
  expect_same_surface(std::get<NurbsSurface>(surface), torus);
  EXPECT_TRUE(std::get<NurbsSurface>(surface).knots_u().is_periodic());

  // A clamped surface of revolution with different degrees in u and v
  const NurbsSurface sphere_surface = sphere(1.5);
  write_shape_file(directory / "sphere.json", sphere_surface);
  expect_same_surface(std::get<NurbsSurface>(read_shape_file(directory / "sphere.json")),
                      sphere_surface);
  // Only the three files: no temporary file is left behind
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    EXPECT_THAT(entry.path().filename().string(), ::testing::Not(HasSubstr(".tmp")));
    ++files;
  }
  EXPECT_EQ(files, 3);
  std::filesystem::remove_all(directory);
}

TEST(ShapeFile, WeightsAreOptionalAndDefaultToOne) {
  const Shape shape = parse_shape_json(R"({"type": "nurbs_curve", "degree": 1,
      "knots": [0, 0, 1, 1], "control_points": [[0, 0, 0], [2, 4, 6]]})");
  const auto& curve = std::get<NurbsCurve>(shape);
  EXPECT_EQ(curve.weights(), Eigen::VectorXd::Ones(2));
  EXPECT_EQ(curve.point(0.5), Eigen::Vector3d(1, 2, 3));
}

TEST(ShapeFile, SurfaceControlPointsRunAlongUOuter) {
  const Shape shape = parse_shape_json(R"({"type": "nurbs_surface", "degree_u": 1,
      "degree_v": 1, "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1],
      "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 5]]]})");
  const auto& surface = std::get<NurbsSurface>(shape);
  EXPECT_EQ(surface.point(1.0, 0.0), Eigen::Vector3d(1, 0, 0));  // (i, j) = (1, 0)
  EXPECT_EQ(surface.point(0.0, 1.0), Eigen::Vector3d(0, 1, 0));  // (i, j) = (0, 1)
  EXPECT_EQ(surface.point(1.0, 1.0), Eigen::Vector3d(1, 1, 5));
}

TEST(ShapeFile, MissingFileNamesTheFile) {
  try {
    read_shape_file("/nonexistent/dir/shape.json");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), StartsWith("/nonexistent/dir/shape.json: "));
    EXPECT_THAT(error.what(), HasSubstr("does not exist"));
  }
}

struct MalformedCase {
  const char* label;
  std::string json;
  std::string message;  // the message must contain this
};

const std::string kCurveHead = R"({"type": "nurbs_curve", "degree": 2, )";
const std::string kKnots = R"("knots": [0, 0, 0, 1, 1, 1], )";
const std::string kPoints = R"("control_points": [[0, 0, 0], [1, 1, 0], [2, 0, 0]])";
const std::string kSurfaceHead =
    R"({"type": "nurbs_surface", "degree_u": 1, "degree_v": 2, "knots_u": [0, 0, 1, 1], )"
    R"("knots_v": [0, 0, 0, 1, 1, 1], )";
const std::string kRow = "[[0, 0, 0], [0, 1, 0], [0, 2, 0]]";

std::vector<MalformedCase> malformed_cases() {
  return {
      {"unterminated", "{\"type\": \"nurbs_curve\",",
       "bad.json: (document): expected valid JSON at line 1, column 24"},
      {"nan literal", kCurveHead + kKnots + R"("control_points": [[0, 0, 0], [NaN, 1, 0]]})",
       "bad.json: (document): expected valid JSON at line 1, column"},
      {"error on line 3", "{\n  \"type\": \"nurbs_curve\",\n  \"degree\": 2,,\n}",
       "bad.json: (document): expected valid JSON at line 3, column"},
      {"empty text", "", "bad.json: (document): expected valid JSON at line 1, column 1"},
      {"overflowing number", kCurveHead + R"("knots": [0, 0, 0, 1e999, 1, 1]})",
       "bad.json: (document): expected valid JSON at line 1, column 57: number overflow parsing "
       "'1e999'"},
      {"root is an array", "[1, 2]", "bad.json: <root>: expected a JSON object"},
      {"missing type", R"({"degree": 2})", "bad.json: type: missing key"},
      {"unknown type", R"({"type": "nurbs_volume"})",
       R"(bad.json: type: expected "nurbs_curve" or "nurbs_surface", got string "nurbs_volume")"},
      {"degree as string", R"({"type": "nurbs_curve", "degree": "2"})",
       R"(bad.json: degree: expected an integer in 1..15, got string "2")"},
      {"degree zero", R"({"type": "nurbs_curve", "degree": 0})",
       "bad.json: degree: expected an integer in 1..15, got number 0"},
      {"fractional degree", R"({"type": "nurbs_curve", "degree": 2.5})",
       "bad.json: degree: expected an integer in 1..15, got number 2.5"},
      {"missing knots", kCurveHead + kPoints + "}", "bad.json: knots: missing key"},
      {"knots not an array", kCurveHead + R"("knots": 3, )" + kPoints + "}",
       "bad.json: knots: expected an array of numbers, got number 3"},
      {"string knot", kCurveHead + R"("knots": [0, 0, "a", 1, 1, 1], )" + kPoints + "}",
       R"(bad.json: knots[2]: expected a finite number, got string "a")"},
      {"decreasing knots", kCurveHead + R"("knots": [0, 0, 0, 1, 0.5, 1, 1], )" + kPoints + "}",
       "bad.json: knots: invalid knots: "},
      {"string coordinate",
       kCurveHead + R"("knots": [0, 0, 0, 0.5, 1, 1, 1], )" +
           R"("control_points": [[0, 0, 0], [1, 1, 0], [2, 0, 0], [3, "x", 0]]})",
       R"(bad.json: control_points[3][1]: expected a finite number, got string "x")"},
      {"null coordinate",
       kCurveHead + kKnots + R"("control_points": [[0, 0, null], [1, 1, 0], [2, 0, 0]]})",
       "bad.json: control_points[0][2]: expected a finite number, got null"},
      {"two coordinates",
       kCurveHead + kKnots + R"("control_points": [[0, 0, 0], [1, 1], [2, 0, 0]]})",
       "bad.json: control_points[1]: expected a point [x, y, z], got an array of 2 values"},
      {"too few control points",
       kCurveHead + kKnots + R"("control_points": [[0, 0, 0], [1, 1, 0]]})",
       "bad.json: control_points: expected 3 control points for degree 2 and 6 knots "
       "(knots - degree - 1), got 2"},
      {"periodic count",
       R"({"type": "nurbs_curve", "degree": 2, "periodic": true, )"
       R"("knots": [0, 1, 2, 3, 4], )" +
           kPoints + "}",
       "bad.json: control_points: expected 4 control points for 5 periodic knots"},
      {"zero weight", kCurveHead + kKnots + kPoints + R"(, "weights": [1, 0, 1]})",
       "bad.json: weights[1]: expected a weight > 0, got 0"},
      {"negative weight", kCurveHead + kKnots + kPoints + R"(, "weights": [1, 1, -1]})",
       "bad.json: weights[2]: expected a weight > 0, got -1"},
      {"weight count", kCurveHead + kKnots + kPoints + R"(, "weights": [1, 1]})",
       "bad.json: weights: expected 3 weights (one per control point), got 2"},
      {"string weight", kCurveHead + kKnots + kPoints + R"(, "weights": [1, "heavy", 1]})",
       R"(bad.json: weights[1]: expected a finite number, got string "heavy")"},
      {"misspelt key", kCurveHead + kKnots + kPoints + R"(, "weight": [1, 1, 1]})",
       "bad.json: weight: unknown key (expected only type, degree, knots, control_points, "
       "weights, periodic)"},
      {"periodic not a boolean", kCurveHead + kKnots + kPoints + R"(, "periodic": "yes"})",
       R"(bad.json: periodic: expected true or false, got string "yes")"},
      {"periodic knots too few",
       R"({"type": "nurbs_curve", "degree": 2, "periodic": true, )"
       R"("knots": [0, 1], "control_points": [[0, 0, 0]]})",
       "bad.json: knots: invalid periodic knots"},
      {"surface missing knots_v",
       R"({"type": "nurbs_surface", "degree_u": 1, "degree_v": 2, "knots_u": [0, 0, 1, 1]})",
       "bad.json: knots_v: missing key"},
      {"surface wrong row count", kSurfaceHead + R"("control_points": [)" + kRow + "]}",
       "bad.json: control_points: expected 2 rows along u for degree_u 1 and 4 knots_u "
       "(knots - degree - 1), got 1"},
      {"surface ragged rows",
       kSurfaceHead + R"("control_points": [)" + kRow + R"(, [[1, 0, 0], [1, 1, 0]]]})",
       "bad.json: control_points[1]: expected 3 points along v for degree_v 2 and 6 knots_v "
       "(knots - degree - 1), got 2"},
      {"surface deep coordinate",
       kSurfaceHead + R"("control_points": [)" + kRow +
           R"(, [[1, 0, 0], [1, 1, 0], [1, 2, true]]]})",
       "bad.json: control_points[1][2][2]: expected a finite number, got true"},
      {"surface ragged weights",
       kSurfaceHead + R"("control_points": [)" + kRow + ", " + kRow +
           R"(], "weights": [[1, 1, 1], [1, 1]]})",
       "bad.json: weights[1]: expected 3 weights (one per control point of the row), got 2"},
      {"surface flat weights",
       kSurfaceHead + R"("control_points": [)" + kRow + ", " + kRow +
           R"(], "weights": [1, 1, 1, 1, 1, 1]})",
       "bad.json: weights: expected 2 rows along u (one per row of control_points), got 6"},
      {"surface negative weight",
       kSurfaceHead + R"("control_points": [)" + kRow + ", " + kRow +
           R"(], "weights": [[1, 1, 1], [1, -0.5, 1]]})",
       "bad.json: weights[1][1]: expected a weight > 0, got -0.5"},
      {"surface unknown key", kSurfaceHead + R"("periodic": true})",
       "bad.json: periodic: unknown key (expected only type, degree_u, degree_v"},
  };
}

TEST(ShapeFile, MalformedShapesGiveMessagesNamingTheKey) {
  const auto cases = malformed_cases();
  ASSERT_GE(cases.size(), 15u);
  for (const auto& c : cases) {
    SCOPED_TRACE(c.label);
    try {
      parse_shape_json(c.json, "bad.json");
      ADD_FAILURE() << "no error for: " << c.json;
    } catch (const Error& error) {
      EXPECT_THAT(error.what(), HasSubstr(c.message));
    }
  }
}

}  // namespace
}  // namespace dnurbs
