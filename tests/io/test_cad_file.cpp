// CAD files through the io layer: formats by extension, exact round trips of shapes through
// STEP and IGES files, shape files and scenes that name a CAD file, and the messages for
// everything that cannot be read or written.
#include "dnurbs/io/cad_file.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/io/models/dnurbs_scene.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_runner.h"
#include "dnurbs/io/shape_file.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

std::filesystem::path fresh_directory(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("dnurbs_test_cad_file_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory;
}

/// A rational quadratic quarter circle of radius 2 and a bicubic sheet with an interior knot.
std::vector<Shape> sample_shapes() {
  Eigen::MatrixX3d arc(3, 3);
  arc << 2, 0, 0, 2, 2, 0, 0, 2, 0;
  const NurbsCurve quarter(KnotVector::clamped_uniform(2, 3), arc,
                           Eigen::Vector3d(1, std::sqrt(0.5), 1));
  Eigen::MatrixX3d net(25, 3);
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      net.row(i * 5 + j) << i / 3.0, j / 7.0, 0.1 * std::sin(i + 2.0 * j);
    }
  }
  const NurbsSurface sheet(KnotVector(3, {0, 0, 0, 0, 0.4, 1, 1, 1, 1}),
                           KnotVector(3, {0, 0, 0, 0, 0.7, 1, 1, 1, 1}), net);
  return {Shape(quarter), Shape(sheet)};
}

TEST(CadFile, FormatsAreNamedByTheExtensionInAnyCase) {
  EXPECT_EQ(cad_format_of("part.step"), CadFormat::step);
  EXPECT_EQ(cad_format_of("PART.STP"), CadFormat::step);
  EXPECT_EQ(cad_format_of("a/b.iges"), CadFormat::iges);
  EXPECT_EQ(cad_format_of("b.IGS"), CadFormat::iges);
  EXPECT_FALSE(cad_format_of("b.json"));
  EXPECT_FALSE(cad_format_of("step"));
}

TEST(CadFile, StepAndIgesFilesRoundTripExactly) {
  if (!cad_exchange_available()) {
    GTEST_SKIP() << "built without Open CASCADE (DNURBS_WITH_CAD=OFF)";
  }
  const std::vector<Shape> shapes = sample_shapes();
  const auto directory = fresh_directory("round_trip");
  for (const char* name : {"both.step", "both.igs"}) {
    write_cad_file(directory / name, shapes);
    const std::vector<Shape> read = read_cad_file(directory / name);
    ASSERT_EQ(read.size(), 2U) << name;
    // STEP lists faces before free edges; IGES keeps the file's order.
    const bool step = cad_format_of(name) == CadFormat::step;
    const NurbsCurve& curve = std::get<NurbsCurve>(read[step ? 1 : 0]);
    const NurbsSurface& surface = std::get<NurbsSurface>(read[step ? 0 : 1]);
    EXPECT_EQ(curve.knots(), std::get<NurbsCurve>(shapes[0]).knots()) << name;
    EXPECT_EQ(curve.weights(), std::get<NurbsCurve>(shapes[0]).weights()) << name;
    EXPECT_EQ(curve.control_points(), std::get<NurbsCurve>(shapes[0]).control_points()) << name;
    EXPECT_EQ(surface.knots_u(), std::get<NurbsSurface>(shapes[1]).knots_u()) << name;
    EXPECT_EQ(surface.knots_v(), std::get<NurbsSurface>(shapes[1]).knots_v()) << name;
    EXPECT_EQ(surface.control_points(), std::get<NurbsSurface>(shapes[1]).control_points()) << name;
    // The quarter circle stays on its circle.
    for (const double u : {0.0, 0.2, 0.5, 0.9, 1.0}) {
      EXPECT_NEAR(curve.point(u).norm(), 2.0, 1e-15) << name;
    }
  }
  // Nothing but the two files: no temporary file is left behind.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(directory),
                          std::filesystem::directory_iterator()),
            2);
}

TEST(CadFile, AShapeFileMayBeACadFileOfOneShape) {
  if (!cad_exchange_available()) {
    GTEST_SKIP() << "built without Open CASCADE (DNURBS_WITH_CAD=OFF)";
  }
  const std::vector<Shape> shapes = sample_shapes();
  const auto directory = fresh_directory("shape_file");
  write_cad_file(directory / "sheet.stp", {shapes[1]});
  const Shape read = read_shape_file(directory / "sheet.stp");
  EXPECT_EQ(std::get<NurbsSurface>(read).control_points(),
            std::get<NurbsSurface>(shapes[1]).control_points());
  write_cad_file(directory / "both.igs", shapes);
  EXPECT_THAT(testing::error_message([&] { read_shape_file(directory / "both.igs"); }),
              HasSubstr("both.igs: the file holds 2 curves and surfaces, and a shape file is "
                        "one; `dnurbs import both.igs shape.json` writes each"));
}

TEST(CadFile, AScenesShapeFileMayBeAStepFile) {
  if (!cad_exchange_available()) {
    GTEST_SKIP() << "built without Open CASCADE (DNURBS_WITH_CAD=OFF)";
  }
  const auto directory = fresh_directory("scene");
  write_cad_file(directory / "sheet.step", {sample_shapes()[1]});
  std::ofstream(directory / "scene.json") << R"json({"models": [
    {"name": "sheet", "type": "dnurbs_surface", "shape_file": "sheet.step",
     "material": {"mass_density": 1, "a10": 1, "a01": 1}}],
    "run": {"steps": 1}})json";
  const Scene scene = read_scene_file(directory / "scene.json");
  const auto& spec = dynamic_cast<const SceneDNurbsSurface&>(*scene.models.at(0).spec.get());
  ASSERT_TRUE(spec.surface);
  EXPECT_EQ(spec.surface->control_points(),
            std::get<NurbsSurface>(sample_shapes()[1]).control_points());
  EXPECT_EQ(spec.shape_file, "sheet.step");
}

TEST(CadFile, ARunWritesItsFinalShapesToOneCadFile) {
  if (!cad_exchange_available()) {
    GTEST_SKIP() << "built without Open CASCADE (DNURBS_WITH_CAD=OFF)";
  }
  const auto directory = fresh_directory("run");
  write_shape_file(directory / "sheet.json", sample_shapes()[1]);
  write_shape_file(directory / "arc.json", sample_shapes()[0]);
  for (const std::string format : {"step", "iges", "obj"}) {
    std::ofstream(directory / "scene.json") << R"json({"models": [
      {"name": "sheet", "type": "dnurbs_surface", "shape_file": "sheet.json",
       "material": {"mass_density": 1, "a10": 1, "a01": 1}},
      {"name": "arc", "type": "dnurbs_curve", "shape_file": "arc.json",
       "material": {"mass_density": 1, "tension": 1}}],
      "run": {"steps": 3}, "output": {"name": "part", "cad_format": ")json"
                                            << format << R"json("}})json";
    SceneSimulation simulation(read_scene_file(directory / "scene.json"));
    SceneRunOptions options;
    options.output_directory = directory / ("out_" + format);
    const SceneRunResult result = run_scene(simulation, options);
    const std::string name = format == "step"   ? "part.step"
                             : format == "iges" ? "part.igs"
                                                : "part_nurbs.obj";
    ASSERT_EQ(result.cad_file, options.output_directory / name);
    const std::vector<Shape> shapes = read_exchange_shapes(result.cad_file);
    ASSERT_EQ(shapes.size(), 2U) << format;
    // The models' final shapes, moved by 3 steps of tension, exactly.
    const NurbsSurface final_sheet = std::get<NurbsSurface>(*simulation.shape(0));
    const NurbsCurve final_arc = std::get<NurbsCurve>(*simulation.shape(1));
    EXPECT_NE(final_arc.control_points(),
              std::get<NurbsCurve>(sample_shapes()[0]).control_points());
    EXPECT_EQ(std::get<NurbsSurface>(shapes[0]).control_points(), final_sheet.control_points());
    EXPECT_EQ(std::get<NurbsCurve>(shapes[1]).control_points(), final_arc.control_points());
    EXPECT_EQ(std::get<NurbsCurve>(shapes[1]).weights(), final_arc.weights());
  }
  std::ofstream(directory / "bad.json") << R"json({"models": [
      {"name": "arc", "type": "dnurbs_curve", "shape_file": "arc.json"}],
    "run": {"steps": 1}, "output": {"cad_format": "dxf"}})json";
  EXPECT_THAT(testing::error_message([&] { read_scene_file(directory / "bad.json"); }),
              HasSubstr("output.cad_format: expected one of"));
}

TEST(CadFile, BadNamesAndFilesAreRefusedWithTheirName) {
  if (!cad_exchange_available()) {
    GTEST_SKIP() << "built without Open CASCADE (DNURBS_WITH_CAD=OFF)";
  }
  const auto directory = fresh_directory("errors");
  EXPECT_THAT(testing::error_message([&] { read_cad_file(directory / "part.obj"); }),
              HasSubstr("part.obj: not a CAD file name (the extension must be .step, .stp, "
                        ".iges or .igs, not \".obj\")"));
  EXPECT_THAT(testing::error_message([&] { read_cad_file(directory / "missing.step"); }),
              HasSubstr("missing.step: the STEP file does not exist"));
  EXPECT_THAT(testing::error_message([&] { write_cad_file(directory / "empty.igs", {}); }),
              HasSubstr("empty.igs: nothing to write (no shapes)"));
  EXPECT_FALSE(std::filesystem::exists(directory / "empty.igs"));
  std::ofstream(directory / "empty.step") << "";
  EXPECT_THAT(testing::error_message([&] { read_cad_file(directory / "empty.step"); }),
              HasSubstr("empty.step: not a readable STEP file"));
}

}  // namespace
}  // namespace dnurbs
