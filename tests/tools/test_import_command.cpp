// `dnurbs export ... PART.step|.igs` and `dnurbs import PART OUT.json`: shape files to CAD files
// and back unchanged, several shapes to numbered files, trimmed faces refused naming the entity,
// bad command lines exit 2.
#include <cmath>
#include <filesystem>
#include <string>
#include <variant>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/io/cad_file.h"
#include "dnurbs/io/shape_file.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "dnurbs/nurbs/shape_generators.h"
#include "tests/tools/run_dnurbs.h"

namespace dnurbs {
namespace {

using testing::fresh_directory;
using ::testing::HasSubstr;
using testing::run_dnurbs;

const std::filesystem::path kData = DNURBS_TEST_DATA_DIR;

TEST(ImportCommand, ShapesGoToStepAndIgesAndComeBackUnchanged) {
  if (!cad_exchange_available()) {
    GTEST_SKIP() << "built without Open CASCADE (DNURBS_WITH_CAD=OFF)";
  }
  const auto directory = fresh_directory("import");
  const std::string ring = (directory / "ring.json").string();
  const std::string bowl = (directory / "bowl.json").string();
  // A periodic rational cubic (6 distinct control points) and a quarter turn of a half circle.
  Eigen::MatrixX3d points(6, 3);
  for (int i = 0; i < 6; ++i) {
    points.row(i) << std::cos(i / 3.0), std::sin(i / 3.0) / 3.0, 0.1 * i;
  }
  const Eigen::VectorXd weights = Eigen::VectorXd::LinSpaced(6, 0.5, 2.0);
  write_shape_file(
      ring, Shape(NurbsCurve(KnotVector::periodic_uniform(3, 6, 0.0, 2.5), points, weights)));
  write_shape_file(bowl, Shape(revolve(half_circle_xz(2.0), 1.25)));
  for (const char* format : {"step", "igs"}) {
    const std::string part = (directory / ("part." + std::string(format))).string();
    const auto exported = run_dnurbs("export " + ring + " " + bowl + " " + part);
    ASSERT_EQ(exported.exit_code, 0) << exported.err;
    EXPECT_THAT(exported.out, HasSubstr("wrote " + ring + " to " + part +
                                        " (nurbs_curve, 6 control points, degree 3, rational, "
                                        "periodic)"));
    const std::string out = (directory / "out.json").string();
    const auto imported = run_dnurbs("import " + part + " " + out);
    ASSERT_EQ(imported.exit_code, 0) << imported.err;
    // STEP lists the face first, IGES keeps the order written.
    const bool step = std::string(format) == "step";
    const std::string ring_back = (directory / (step ? "out-1.json" : "out-0.json")).string();
    const std::string bowl_back = (directory / (step ? "out-0.json" : "out-1.json")).string();
    EXPECT_EQ(testing::read_text(ring_back), testing::read_text(ring)) << format;
    EXPECT_EQ(testing::read_text(bowl_back), testing::read_text(bowl)) << format;
    EXPECT_THAT(imported.out, HasSubstr(ring_back + ": nurbs_curve"));
    // --index picks one shape into OUT.json.
    const auto one = run_dnurbs("import " + part + " " + out + " --index " + (step ? "1" : "0"));
    ASSERT_EQ(one.exit_code, 0) << one.err;
    EXPECT_EQ(testing::read_text(out), testing::read_text(ring)) << format;
    const auto beyond = run_dnurbs("import " + part + " " + out + " --index 2");
    EXPECT_EQ(beyond.exit_code, 2);
    EXPECT_THAT(beyond.err, HasSubstr("--index 2: " + part + " holds 2 shapes (0..1)"));
  }
  std::filesystem::remove_all(directory);
}

TEST(ImportCommand, NurbsGoToObjFreeFormAndComeBackUnchanged) {
  const auto directory = fresh_directory("import_obj");
  const std::string sheet = (directory / "sheet.json").string();
  const std::string bowl = (directory / "bowl.json").string();
  write_shape_file(sheet, Shape(greville_plane({2, 1}, {5, 4}, {3, 2})));
  write_shape_file(bowl, Shape(revolve(half_circle_xz(2.0), 1.25)));
  const std::string obj = (directory / "part.obj").string();
  const auto exported = run_dnurbs("export " + sheet + " " + bowl + " " + obj + " --nurbs");
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  EXPECT_THAT(testing::read_text(obj), HasSubstr("cstype rat bspline\ndeg 2 2\nsurf "));
  const auto imported = run_dnurbs("import " + obj + " " + (directory / "out.json").string());
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  EXPECT_EQ(testing::read_text(directory / "out-0.json"), testing::read_text(sheet));
  EXPECT_EQ(testing::read_text(directory / "out-1.json"), testing::read_text(bowl));
  // A mesh OBJ holds no free-form shape.
  const std::string mesh = (directory / "mesh.obj").string();
  ASSERT_EQ(run_dnurbs("export " + sheet + " " + mesh).exit_code, 0);
  const auto none = run_dnurbs("import " + mesh + " " + (directory / "none.json").string());
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_THAT(none.err, HasSubstr("mesh.obj: the OBJ file has no free-form curve or surface"));
  const auto stl =
      run_dnurbs("export " + sheet + " " + (directory / "x.stl").string() + " --nurbs");
  EXPECT_EQ(stl.exit_code, 2);
  EXPECT_THAT(stl.err, HasSubstr("--nurbs applies to a .obj file"));
  std::filesystem::remove_all(directory);
}

TEST(ImportCommand, ATrimmedFaceMadeByOpenCascadeIsRefusedNamingIt) {
  if (!cad_exchange_available()) {
    GTEST_SKIP() << "built without Open CASCADE (DNURBS_WITH_CAD=OFF)";
  }
  // tests/data/cad/disc.step: a plane bounded by a circle, written by Open CASCADE 7.6.3.
  const auto directory = fresh_directory("import_trimmed");
  const auto result = run_dnurbs("import " + (kData / "cad" / "disc.step").string() + " " +
                                 (directory / "disc.json").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, HasSubstr("disc.step: face 0 #17 (StepShape_AdvancedFace) (Geom_Plane): "
                                    "it is trimmed"));
  EXPECT_FALSE(std::filesystem::exists(directory / "disc.json"));
  std::filesystem::remove_all(directory);
}

TEST(ImportCommand, BadCommandLinesExitTwo) {
  const auto directory = fresh_directory("import_usage");
  const std::string ring = (directory / "ring.json").string();
  write_shape_file(ring, Shape(full_circle(1.0, Eigen::Vector3d::Zero())));
  EXPECT_EQ(run_dnurbs("import").exit_code, 2);
  EXPECT_EQ(run_dnurbs("import part.step").exit_code, 2);
  EXPECT_EQ(run_dnurbs("import a.step b.json --index -1").exit_code, 2);
  const auto options =
      run_dnurbs("export " + ring + " " + (directory / "x.step").string() + " --resolution 8");
  EXPECT_EQ(options.exit_code, 2);
  EXPECT_THAT(options.err,
              HasSubstr("the mesh options do not apply to NURBS in a STEP, IGES or OBJ file"));
  const auto missing = run_dnurbs("import " + (directory / "none.igs").string() + " out.json");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_THAT(missing.err,
              HasSubstr(cad_exchange_available() ? "none.igs: the IGES file does not exist"
                                                 : "none.igs: this dnurbs was built without STEP"));
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace dnurbs
