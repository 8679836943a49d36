// A scene whose model is fitted to points ("fit") through the built binary: `dnurbs run` writes
// the OBJ and, with output.shape_files, the final shape, which is the surface the points were
// sampled from (tests/data/generate_fit_points.py) when nothing moves it.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <utility>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/tools/run_dnurbs.h"

#include "dnurbs/io/mesh_import.h"
#include "dnurbs/io/shape_file.h"
#include "tests/common/surface_comparison.h"

namespace dnurbs {
namespace {

using testing::fresh_directory;
using testing::run_dnurbs;

const std::filesystem::path kData = DNURBS_TEST_DATA_DIR;

TEST(FitScene, RunWritesTheFittedShapeAndItsMesh) {
  const auto directory = fresh_directory("fit_scene");
  // No stiffness, force or damping: the fitted surface rests, so the final shape is the fit
  std::ofstream(directory / "scene.json")
      << R"({"models": [{"name": "scan", "type": "dnurbs_surface",
                         "fit": {"points": ")"
      << (kData / "fit_surface_points.xyz").string() << R"(", "degree": 3, "spans": 2}}],
             "run": {"steps": 3}, "output": {"name": "fitted", "shape_files": true}})";
  const auto result = run_dnurbs("run " + (directory / "scene.json").string() + " --out " +
                                 (directory / "out").string() + " --no-preview");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::vector<TriangleMesh> meshes = import_meshes(directory / "out" / "fitted.obj");
  ASSERT_EQ(meshes.size(), 1u);
  EXPECT_GT(meshes[0].vertex_count(), 0);
  const Shape written = read_shape_file(directory / "out" / "scan.json");
  const Shape source = read_shape_file(kData / "fit_surface_source.json");
  ASSERT_TRUE(std::holds_alternative<NurbsSurface>(written));
  // The points lie on the source with the same degree and knots: the fit recovers it to
  // rounding (1e-15 measured), and three steps at rest do not move it
  EXPECT_LT(testing::control_point_distance_up_to_symmetry(std::get<NurbsSurface>(written),
                                                           std::get<NurbsSurface>(source)),
            1e-8);
  std::filesystem::remove_all(directory);
}

TEST(FitScene, MissingPointsFileIsNamed) {
  const auto directory = fresh_directory("fit_scene_missing");
  std::ofstream(directory / "scene.json") << R"({"models": [{"type": "superquadric",
      "fit": {"points": "nowhere.xyz"}}], "run": {"steps": 1}})";
  const auto result = run_dnurbs("run " + (directory / "scene.json").string() + " --out " +
                                 (directory / "out").string() + " --no-preview");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, ::testing::HasSubstr("models[0].fit.points"));
  EXPECT_THAT(result.err, ::testing::HasSubstr("nowhere.xyz"));
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace dnurbs
