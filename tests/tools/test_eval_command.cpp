// Runs the built dnurbs command: eval output, error messages and exit codes, the default demo.

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include "tests/tools/run_dnurbs.h"

#include "dnurbs/core/version.h"
#include "dnurbs/io/mesh_import.h"
#include "dnurbs/io/shape_file.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;
using Json = nlohmann::json;

const std::string kData = DNURBS_TEST_DATA_DIR;

using Result = testing::CommandResult;
using testing::fresh_directory;
using testing::kDnurbs;
using testing::read_text;

Result run(const std::string& arguments) {
  return testing::run_dnurbs(arguments);
}

Eigen::Vector3d vector_of(const Json& value) {
  return {value.at(0).get<double>(), value.at(1).get<double>(), value.at(2).get<double>()};
}

TEST(EvalCommand, RationalCircleFilePrintsPointsOfRadiusOne) {
  const Result result =
      run("eval " + kData + "/circle.json --at 0.3 --at 0.8 --at 1 --derivatives 2");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const Json output = Json::parse(result.out);
  EXPECT_EQ(output.at("type"), "nurbs_curve");
  EXPECT_EQ(output.at("derivative_order"), 2);
  ASSERT_EQ(output.at("evaluations").size(), 3u);
  const NurbsCurve circle = std::get<NurbsCurve>(read_shape_file(kData + "/circle.json"));
  for (const Json& evaluation : output.at("evaluations")) {
    const double u = evaluation.at("u").get<double>();
    const Eigen::Vector3d point = vector_of(evaluation.at("point"));
    // Exact rational circle: only rounding in the evaluation remains
    EXPECT_NEAR(point.norm(), 1.0, 1e-14) << "u = " << u;
    ASSERT_EQ(evaluation.at("derivatives").size(), 3u);
    // 17 significant digits: the printed numbers read back as the library's exact doubles
    const CurveDerivatives expected = circle.derivatives(u, 2);
    for (int k = 0; k <= 2; ++k) {
      EXPECT_EQ(vector_of(evaluation.at("derivatives").at(static_cast<size_t>(k))),
                expected.row(k).transpose())
          << "u = " << u << ", order " << k;
    }
    // On a circle the tangent is perpendicular to the radius (rounding of |C'| ~ 6)
    EXPECT_NEAR(point.dot(vector_of(evaluation.at("derivatives").at(1))), 0.0, 1e-13);
  }
  EXPECT_EQ(output.at("evaluations").at(0).at("u").get<double>(), 0.3);
}

TEST(EvalCommand, PeriodicTorusFilePrintsNamedPartialDerivatives) {
  const Result result =
      run("eval " + kData + "/torus_periodic.json --at 0.1,0.7 --at 0.95,0.05 --derivatives 2");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const Json output = Json::parse(result.out);
  EXPECT_EQ(output.at("type"), "nurbs_surface");
  const NurbsSurface torus =
      std::get<NurbsSurface>(read_shape_file(kData + "/torus_periodic.json"));
  for (const Json& evaluation : output.at("evaluations")) {
    const double u = evaluation.at("u").get<double>();
    const double v = evaluation.at("v").get<double>();
    const Json& derivatives = evaluation.at("derivatives");
    EXPECT_EQ(derivatives.size(), 6u);
    const SurfaceDerivatives expected = torus.derivatives(u, v, 2);
    EXPECT_EQ(vector_of(derivatives.at("S")), expected(0, 0));
    EXPECT_EQ(vector_of(derivatives.at("Su")), expected(1, 0));
    EXPECT_EQ(vector_of(derivatives.at("Sv")), expected(0, 1));
    EXPECT_EQ(vector_of(derivatives.at("Suu")), expected(2, 0));
    EXPECT_EQ(vector_of(derivatives.at("Suv")), expected(1, 1));
    EXPECT_EQ(vector_of(derivatives.at("Svv")), expected(0, 2));
    // The point is at distance 0.5 from the tube's centre circle of radius 2
    const Eigen::Vector3d p = vector_of(evaluation.at("point"));
    const Eigen::Vector3d centre = 2.0 * Eigen::Vector3d(p.x(), p.y(), 0.0).normalized();
    EXPECT_NEAR((p - centre).norm(), 0.5, 1e-14);
  }
}

struct BadFile {
  const char* name;
  const char* contents;
  const char* message;
};

TEST(EvalCommand, MalformedFilesExitOneNamingFileAndKey) {
  const auto directory = fresh_directory("malformed");
  const BadFile files[] = {
      {"syntax.json", "{\"type\": \"nurbs_curve\",\n  \"degree\": 2\n  \"knots\": []}",
       "syntax.json: (document): expected valid JSON at line 3, column"},
      {"weight.json",
       R"({"type": "nurbs_curve", "degree": 1, "knots": [0, 0, 1, 1],
           "control_points": [[0, 0, 0], [1, 0, 0]], "weights": [1, -2]})",
       "weight.json: weights[1]: expected a weight > 0, got -2"},
      {"coordinate.json",
       R"({"type": "nurbs_curve", "degree": 1, "knots": [0, 0, 1, 1],
           "control_points": [[0, 0, 0], [1, "one", 0]]})",
       R"(coordinate.json: control_points[1][1]: expected a finite number, got string "one")"},
      {"count.json",
       R"({"type": "nurbs_curve", "degree": 1, "knots": [0, 0, 0.5, 1, 1],
           "control_points": [[0, 0, 0], [1, 0, 0]]})",
       "count.json: control_points: expected 3 control points"},
      {"type.json", R"({"type": 7})", "type.json: type: expected \"nurbs_curve\""},
      // Finite coordinates whose derivative overflows: an error, never "inf" in the JSON
      {"overflow.json",
       R"({"type": "nurbs_curve", "degree": 1, "knots": [0, 0, 1, 1],
           "control_points": [[-1e308, 0, 0], [1e308, 0, 0]]})",
       "overflow.json: --at 0.5: the derivative of order 1 = (inf, 0, 0) is not finite"},
  };
  for (const auto& file : files) {
    SCOPED_TRACE(file.name);
    { std::ofstream(directory / file.name) << file.contents; }
    const Result result = run("eval " + (directory / file.name).string() + " --at 0.5");
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_THAT(result.err, HasSubstr(file.message));
    EXPECT_EQ(result.out, "");  // nothing half-printed
  }
  const Result missing = run("eval " + (directory / "none.json").string() + " --at 0.5");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_THAT(missing.err, HasSubstr("none.json: the shape file does not exist"));
  std::filesystem::remove_all(directory);
}

TEST(EvalCommand, BadParametersExitOneAndBadCommandLinesExitTwo) {
  const std::string circle = kData + "/circle.json";
  const Result outside = run("eval " + circle + " --at 1.5");
  EXPECT_EQ(outside.exit_code, 1);
  EXPECT_THAT(outside.err, HasSubstr("--at 1.5"));
  const Result two = run("eval " + circle + " --at 0.2,0.3");
  EXPECT_EQ(two.exit_code, 1);
  EXPECT_THAT(two.err, HasSubstr("a curve takes one parameter u"));
  const Result one = run("eval " + kData + "/torus_periodic.json --at 0.2");
  EXPECT_EQ(one.exit_code, 1);
  EXPECT_THAT(one.err, HasSubstr("a surface takes two parameters u,v"));

  EXPECT_EQ(run("eval " + circle).exit_code, 2);  // no --at
  EXPECT_EQ(run("eval " + circle + " --at abc").exit_code, 2);
  EXPECT_EQ(run("eval " + circle + " --at 0.5 --derivatives 99").exit_code, 2);
  EXPECT_EQ(run("eval " + circle + " --at 0.5 --frobnicate").exit_code, 2);
  const Result unknown = run("frobnicate");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_THAT(unknown.err, HasSubstr("unknown command \"frobnicate\""));
  EXPECT_EQ(run("").exit_code, 2);
}

TEST(DnurbsCommand, HelpForProgramAndEachSubcommandExitsZero) {
  const Result help = run("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.out, HasSubstr("usage: dnurbs COMMAND"));
  for (const std::string command :
       {"eval", "run", "info", "make", "export", "import", "preview", "fit", "design", "serve"}) {
    const Result sub = run(command + " --help");
    EXPECT_EQ(sub.exit_code, 0) << command;
    EXPECT_THAT(sub.out, HasSubstr("usage: dnurbs " + command)) << command;
  }
}

TEST(DnurbsCommand, VersionPrintsTheProjectVersion) {
  for (const std::string option : {"--version", "version"}) {
    const Result version = run(option);
    EXPECT_EQ(version.exit_code, 0) << option;
    EXPECT_EQ(version.out, std::string("dnurbs ") + kVersion + "\n") << option;
  }
  EXPECT_EQ(std::to_string(kVersionMajor) + "." + std::to_string(kVersionMinor) + "." +
                std::to_string(kVersionPatch),
            kVersion);
}

TEST(RunCommand, DefaultDemoWritesObjAndPng) {
  const auto directory = fresh_directory("demo");
  const Result result = run("run --out " + directory.string() + " --resolution 24");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("demo.obj"));
  EXPECT_THAT(result.out, HasSubstr("demo.png"));
  // The OBJ holds the hat (open: 25 x 25 vertices), the periodic torus (24 x 12, no seams) and
  // the superquadric pendulum's link and bob
  const std::vector<TriangleMesh> meshes = import_meshes(directory / "demo.obj");
  ASSERT_EQ(meshes.size(), 4u);
  EXPECT_EQ(meshes[0].name, "hat");
  EXPECT_EQ(meshes[0].triangle_count(), 2 * 24 * 24);
  EXPECT_EQ(meshes[1].name, "torus");
  EXPECT_EQ(meshes[1].triangle_count(), 2 * 24 * 12);
  EXPECT_EQ(meshes[1].vertex_count(), 24 * 12);
  EXPECT_EQ(meshes[2].name, "link");
  EXPECT_EQ(meshes[3].name, "bob");
  // A PNG file: its signature and a non-trivial size
  const std::string png = read_text(directory / "demo.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // And the energies of its log over time next to log.csv
  EXPECT_THAT(result.out, HasSubstr("energy.png (energies over time)"));
  EXPECT_EQ(read_text(directory / "energy.png").substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // The shape files it wrote read back
  EXPECT_TRUE(std::holds_alternative<NurbsSurface>(read_shape_file(directory / "torus.json")));
  EXPECT_TRUE(std::holds_alternative<NurbsSurface>(read_shape_file(directory / "hat.json")));
  std::filesystem::remove_all(directory);
}

TEST(ExportCommand, ShapeFileBecomesAMeshInTheFormatOfTheExtension) {
  const auto directory = fresh_directory("export");
  const Result stl = run("export " + kData + "/torus_periodic.json " +
                         (directory / "torus.stl").string() + " --resolution 16");
  ASSERT_EQ(stl.exit_code, 0) << stl.err;
  const std::vector<TriangleMesh> torus = import_meshes(directory / "torus.stl");
  ASSERT_EQ(torus.size(), 1u);
  EXPECT_EQ(torus[0].triangle_count(), 2 * 16 * 16);
  const Result tube = run("export " + kData + "/circle.json " +
                          (directory / "circle.obj").string() + " --resolution 40 --radius 0.05");
  ASSERT_EQ(tube.exit_code, 0) << tube.err;
  const std::vector<TriangleMesh> circle = import_meshes(directory / "circle.obj");
  ASSERT_EQ(circle.size(), 1u);
  EXPECT_EQ(circle[0].triangle_count(), 2 * 40 * 12);
  for (int r = 0; r < circle[0].vertex_count(); ++r) {
    const Eigen::Vector3d p = circle[0].vertices.row(r);
    const Eigen::Vector3d centre = Eigen::Vector3d(p.x(), p.y(), 0.0).normalized();
    EXPECT_NEAR((p - centre).norm(), 0.05, 1e-6);  // single precision in the OBJ
  }
  const Result bad = run("export " + kData + "/circle.json " + (directory / "c.xyz").string());
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_THAT(bad.err, HasSubstr("unknown mesh file extension \".xyz\""));
  EXPECT_EQ(run("export " + kData + "/circle.json").exit_code, 2);
  std::filesystem::remove_all(directory);
}

// The number after `label` in `text` (e.g. "adaptive (...): 123 vertices": label ": ")
double number_after(const std::string& text, const std::string& label) {
  const size_t at = text.find(label);
  EXPECT_NE(at, std::string::npos) << label << " not in " << text;
  return at == std::string::npos ? 0.0 : std::stod(text.substr(at + label.size()));
}

TEST(ExportCommand, AdaptiveMeshMeetsTheBoundWithFewerVerticesThanUniformAndIsClosed) {
  const auto directory = fresh_directory("export_adaptive");
  const double bound = 1e-3;
  const Result result = run("export " + kData + "/torus_periodic.json " +
                            (directory / "torus.obj").string() + " --max-error 0.001 --compare");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const double adaptive_vertices = number_after(result.out, "criterion): ");
  const double uniform_vertices = number_after(result.out, "cells, ");
  EXPECT_LE(number_after(result.out, "sampled max error "), bound);
  EXPECT_LT(adaptive_vertices, uniform_vertices) << result.out;
  const std::vector<TriangleMesh> torus = import_meshes(directory / "torus.obj");
  ASSERT_EQ(torus.size(), 1u);
  EXPECT_EQ(torus[0].vertex_count(), adaptive_vertices);
  // Closed and crack-free: every undirected edge in exactly two triangles
  std::map<std::pair<int, int>, int> edges;
  for (int f = 0; f < torus[0].triangle_count(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = torus[0].triangles(f, k);
      const int b = torus[0].triangles(f, (k + 1) % 3);
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  }
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 2) << edge.first << "-" << edge.second;
  }
  const Result angle = run("export " + kData + "/torus_periodic.json " +
                           (directory / "normals.obj").string() + " --max-angle 10");
  EXPECT_EQ(angle.exit_code, 0) << angle.err;
  EXPECT_THAT(angle.out, HasSubstr("normals criterion"));
  // Bad combinations and values: exit 2 naming the option
  const std::string surface_export =
      "export " + kData + "/torus_periodic.json " + (directory / "x.obj").string();
  EXPECT_EQ(run(surface_export + " --max-error 0").exit_code, 2);
  EXPECT_EQ(run(surface_export + " --max-error nan").exit_code, 2);
  EXPECT_EQ(run(surface_export + " --max-angle 200").exit_code, 2);
  const Result both = run(surface_export + " --max-error 0.01 --resolution 8");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_THAT(both.err, HasSubstr("exclude each other"));
  EXPECT_EQ(run(surface_export + " --compare").exit_code, 2);
  const Result curve = run("export " + kData + "/circle.json " + (directory / "c.obj").string() +
                           " --max-error 0.01");
  EXPECT_EQ(curve.exit_code, 2);
  EXPECT_THAT(curve.err, HasSubstr("is a curve"));
  std::filesystem::remove_all(directory);
}

TEST(PreviewCommand, MissingMeshExitsOne) {
  const auto directory = fresh_directory("preview");
  const Result result =
      run("preview " + (directory / "none.obj").string() + " " + (directory / "x.png").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, HasSubstr("none.obj"));
  EXPECT_FALSE(std::filesystem::exists(directory / "x.png"));
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace dnurbs
