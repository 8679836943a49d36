// Running a scene writes only into its output folder, whatever its model names are, and removes
// what a killed run left there.

#include "dnurbs/io/scene_runner.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "dnurbs/io/scene.h"
#include "tests/common/child_process.h"

namespace dnurbs {
namespace {

// A quadratic D-NURBS curve run for two steps with these output settings
std::string curve_scene(const nlohmann::json& output) {
  const nlohmann::json scene = {{"models",
                                 {{{"name", "curve"},
                                   {"type", "dnurbs_curve"},
                                   {"shape",
                                    {{"type", "nurbs_curve"},
                                     {"degree", 2},
                                     {"knots", {0, 0, 0, 1, 1, 1}},
                                     {"control_points", {{0, 0, 0}, {1, 1, 0}, {2, 0, 0}}}}}}}},
                                {"run", {{"steps", 2}}},
                                {"output", output}};
  return scene.dump();
}

// Scene files cannot name a model so (SceneFile.EveryMalformedSceneOfTheCorpusNamesItsJsonPath:
// model_name_is_a_path.json); a Scene built in C++ can, and the runner still writes inside its
// output folder.
TEST(SceneRunner, AModelNameThatIsNoPlainFileNameWritesItsShapeAsModelIndex) {
  const std::filesystem::path root = std::filesystem::temp_directory_path() / "dnurbs_runner_names";
  std::filesystem::remove_all(root);
  Scene parsed = parse_scene_json(
      curve_scene({{"shape_files", true}, {"mesh_every", 0}, {"checkpoint_every", 0}}), "<names>");
  parsed.models[0].name = "../../escaped";
  SceneSimulation simulation(std::move(parsed));
  SceneRunOptions options;
  options.output_directory = root / "out";
  const SceneRunResult result = run_scene(simulation, options);
  ASSERT_EQ(result.shape_files.size(), 1U);
  EXPECT_EQ(result.shape_files[0], root / "out" / "model0.json");
  EXPECT_TRUE(std::filesystem::is_regular_file(root / "out" / "model0.json"));
  EXPECT_FALSE(std::filesystem::exists(root / "escaped.json"));
  EXPECT_FALSE(std::filesystem::exists(root.parent_path() / "escaped.json"));
}

// A killed run can leave temporaries (io/atomic_write.h); the next run in the folder removes
// those of processes that have ended
TEST(SceneRunner, ARunRemovesTheTemporariesOfAKilledRun) {
  const std::filesystem::path root = std::filesystem::temp_directory_path() / "dnurbs_runner_stale";
  std::filesystem::remove_all(root);
  std::filesystem::create_directories(root / "frames");
  const pid_t child = testing::ended_process_id();
  const std::string stale = ".log.csv.tmp-" + std::to_string(child) + "-4";
  const std::string stale_frame = ".run_0001.obj.tmp-" + std::to_string(child) + "-9";
  std::ofstream(root / stale) << "half";
  std::ofstream(root / "frames" / stale_frame) << "half";
  SceneSimulation simulation(
      parse_scene_json(curve_scene({{"mesh_every", 1}, {"checkpoint_every", 0}}), "<stale>"));
  SceneRunOptions options;
  options.output_directory = root;
  run_scene(simulation, options);
  EXPECT_FALSE(std::filesystem::exists(root / stale));
  EXPECT_FALSE(std::filesystem::exists(root / "frames" / stale_frame));
  EXPECT_TRUE(std::filesystem::exists(root / "log.csv"));
  std::filesystem::remove_all(root);
}

}  // namespace
}  // namespace dnurbs
