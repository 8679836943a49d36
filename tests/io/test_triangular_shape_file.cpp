// Shape files of triangular NURBS surfaces: exact round trips, the standard knot clouds when
// they are left out, and messages that name the JSON path of every malformed value.

#include "dnurbs/io/triangular_shape_file.h"

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/triangulation_shapes.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A rational surface of degree 2 over the L-shape with non-trivial coordinates.
TriangularNurbsSurface rational_l_shape() {
  const Triangulation triangulation = l_shape_triangulation(1);
  auto basis = std::make_shared<const TriangularBSplineBasis>(
      triangulation, standard_knot_clouds(triangulation, 2));
  const TriangularNurbsSurface flat = flat_triangular_surface(basis);
  Eigen::MatrixX3d points = flat.control_points();
  Eigen::VectorXd weights(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    points(i, 2) = std::sin(0.1 * static_cast<double>(i)) / 3.0;
    weights[i] = 0.5 + 1.0 / (1.0 + static_cast<double>(i));
  }
  return {basis, points, weights};
}

const char* const kTile = R"({"type": "triangular_nurbs", "degree": 1,
  "vertices": [[0, 0], [1, 0], [0, 1]], "triangles": [[0, 1, 2]],
  "control_points": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]})";

TEST(TriangularShapeFile, RationalSurfaceRoundTripsExactly) {
  const TriangularNurbsSurface surface = rational_l_shape();
  const std::string text = triangular_shape_to_json(surface);
  const TriangularNurbsSurface again = parse_triangular_shape_json(text, "again.json");
  EXPECT_EQ(again.basis().degree(), 2);
  EXPECT_EQ(again.basis().triangulation().vertices(), surface.basis().triangulation().vertices());
  EXPECT_EQ(again.basis().triangulation().triangles(), surface.basis().triangulation().triangles());
  EXPECT_EQ(again.basis().knot_clouds().knots(), surface.basis().knot_clouds().knots());
  EXPECT_EQ(again.control_points(), surface.control_points());
  EXPECT_EQ(again.weights(), surface.weights());
  // The same numbers give the same surface, bit for bit
  for (const Eigen::Vector2d& u : {Eigen::Vector2d(0.3, 0.2), Eigen::Vector2d(1.7, 0.6)}) {
    EXPECT_EQ(again.point(u), surface.point(u));
  }
  // Writing is stable, and through a file too
  EXPECT_EQ(triangular_shape_to_json(again), text);
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "dnurbs_test_triangular_shape.json";
  write_triangular_shape_file(file, surface);
  EXPECT_TRUE(is_triangular_shape_file(file));
  EXPECT_EQ(triangular_shape_to_json(read_triangular_shape_file(file)), text);
  std::filesystem::remove(file);
}

TEST(TriangularShapeFile, KnotCloudsAndWeightsAreOptional) {
  const TriangularNurbsSurface tile = parse_triangular_shape_json(kTile);
  // The standard placement, and unit weights: the tile is the identity map of its triangle
  const Triangulation& triangulation = tile.basis().triangulation();
  const TriangularKnotClouds standard = standard_knot_clouds(triangulation, 1);
  EXPECT_EQ(tile.basis().knot_clouds().knots(), standard.knots());
  EXPECT_EQ(tile.weights(), Eigen::VectorXd::Ones(3));
  // Degree 1 reproduces the affine map of its control points (rounding: 1e-15)
  EXPECT_LT((tile.point(Eigen::Vector2d(0.25, 0.5)) - Eigen::Vector3d(0.25, 0.5, 0)).norm(), 1e-15);
  // Weights are omitted from the written form when all are 1, the clouds always written
  const std::string written = triangular_shape_to_json(tile);
  EXPECT_THAT(written, Not(HasSubstr("weights")));
  EXPECT_THAT(written, HasSubstr("knot_clouds"));
}

// Found by fuzz/fuzz_shape_reader.cpp: a vertex 1e43 away from the others made the point
// location grid's bin count a double beyond int, converted anyway (undefined behaviour, caught by
// the sanitized run of this test). Now the bin counts are clamped and the file gets its Error.
TEST(TriangularShapeFile, FarAwayVertexGivesAnErrorNotUndefinedBehaviour) {
  try {
    parse_triangular_shape_json(
        R"({"type": "triangular_nurbs", "degree": 1,
            "vertices": [[5, 0], [1, 2e43], [1, 5], [0, 1]],
            "triangles": [[3, 0, 2]], "control_points": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]})",
        "far.json");
    ADD_FAILURE() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("far.json: triangles:"));
  }
}

TEST(TriangularShapeFile, OtherTypesAndUnreadableFilesAreNotTriangular) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "dnurbs_test_not_triangular.json";
  std::ofstream(file) << R"({"type": "nurbs_curve"})";
  EXPECT_FALSE(is_triangular_shape_file(file));
  std::ofstream(file) << "{ not json";
  EXPECT_FALSE(is_triangular_shape_file(file));
  std::filesystem::remove(file);
  EXPECT_FALSE(is_triangular_shape_file(file));
  try {
    read_triangular_shape_file(file);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("the shape file does not exist"));
  }
}

TEST(TriangularShapeFile, MalformedShapesGiveMessagesNamingTheKey) {
  // Each: a replacement of one piece of kTile and the substrings of the message
  const std::vector<std::pair<std::pair<std::string, std::string>, std::vector<std::string>>>
      cases = {
          {{"\"degree\": 1", "\"degree\": 7"}, {"tile.json: degree: expected an integer in 1..6"}},
          {{"\"degree\": 1,", ""}, {"tile.json: degree: missing key"}},
          {{"triangular_nurbs", "nurbs_surface"},
           {"tile.json: type: expected \"triangular_nurbs\""}},
          {{"[[0, 1, 2]]", "[[0, 2, 1]]"}, {"tile.json: triangles: invalid triangulation"}},
          {{"[[0, 1, 2]]", "[[0, 1]]"}, {"tile.json: triangles[0]: expected three vertex indices"}},
          {{"[[0, 0], [1, 0]", "[[0, 0], [1, \"a\"]"}, {"tile.json: vertices[1][1]"}},
          {{"[1, 0, 0], [0, 1, 0]]", "[1, 0, 0]]"},
           {"tile.json: control_points: expected 3 control points"}},
          {{"[0, 1, 0]]", "[0, 1, 0]], \"weights\": [1, 0, 1]"},
           {"tile.json: weights[1]: expected a number > 0, got 0"}},
          {{"[0, 1, 0]]", "[0, 1, 0]], \"knot_clouds\": [[[0, 0]]]"},
           {"tile.json: knot_clouds: expected 3 knot clouds (one per vertex)"}},
          {{"[0, 1, 0]]", "[0, 1, 0]], \"knot_clouds\": [[[0.1, 0.1]], [[1.1, 0]], [[0, 1.1]]]"},
           {"tile.json: knot_clouds: invalid knot clouds"}},
          {{"[0, 1, 0]]", "[0, 1, 0]], \"colour\": 1"}, {"tile.json: colour: unknown key"}},
          {{"\"type\"", "\"typ\""}, {"tile.json: typ: unknown key"}},
      };
  for (const auto& [replacement, expected] : cases) {
    std::string text = kTile;
    const auto at = text.find(replacement.first);
    ASSERT_NE(at, std::string::npos) << replacement.first;
    text.replace(at, replacement.first.size(), replacement.second);
    try {
      parse_triangular_shape_json(text, "tile.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& error) {
      for (const std::string& part : expected) {
        EXPECT_THAT(error.what(), HasSubstr(part)) << text;
      }
    }
  }
  EXPECT_THROW(parse_triangular_shape_json("{\"type\": ", "broken.json"), Error);
}

}  // namespace
}  // namespace dnurbs
