// Running a scene writes only into its output folder, whatever its model names are.

#include "io/scene_runner.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/scene.h"

namespace dnurbs {
namespace {

TEST(SceneRunner, AModelNameThatIsNoPlainFileNameWritesItsShapeAsModelIndex) {
  const std::filesystem::path root = std::filesystem::temp_directory_path() / "dnurbs_runner_names";
  std::filesystem::remove_all(root);
  const nlohmann::json scene = {
      {"models",
       {{{"name", "../../escaped"},
         {"type", "dnurbs_curve"},
         {"shape",
          {{"type", "nurbs_curve"},
           {"degree", 2},
           {"knots", {0, 0, 0, 1, 1, 1}},
           {"control_points", {{0, 0, 0}, {1, 1, 0}, {2, 0, 0}}}}}}}},
      {"run", {{"steps", 2}}},
      {"output", {{"shape_files", true}, {"mesh_every", 0}, {"checkpoint_every", 0}}}};
  SceneSimulation simulation(parse_scene_json(scene.dump(), "<names>"));
  SceneRunOptions options;
  options.output_directory = root / "out";
  const SceneRunResult result = run_scene(simulation, options);
  ASSERT_EQ(result.shape_files.size(), 1U);
  EXPECT_EQ(result.shape_files[0], root / "out" / "model0.json");
  EXPECT_TRUE(std::filesystem::is_regular_file(root / "out" / "model0.json"));
  EXPECT_FALSE(std::filesystem::exists(root / "escaped.json"));
  EXPECT_FALSE(std::filesystem::exists(root.parent_path() / "escaped.json"));
}

}  // namespace
}  // namespace dnurbs
