// Scenes too large for the machine are refused before anything is allocated, naming the key to
// lower (core/memory_budget.h): a mesh whose resolution_scale would need more memory than
// there is (or overflow an int), a Terzopoulos grid of too many nodes.

#include <cstdlib>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

std::string sheet_scene(const std::string& scale) {
  return R"({"models": [{"name": "sheet", "type": "dnurbs_surface", "resolution_scale": )" + scale +
         R"(, "shape": {"type": "nurbs_surface", "degree_u": 1, "degree_v": 1,
         "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1],
         "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 0]]]},
         "material": {"a10": 1, "a01": 1}}], "run": {"steps": 1}})";
}

std::string mesh_refusal(const std::string& scale, int resolution) {
  const SceneSimulation simulation(parse_scene_json(sheet_scene(scale), "big.json"));
  try {
    simulation.mesh(0, resolution);
  } catch (const Error& error) {
    return error.what();
  }
  return "meshed";
}

TEST(SceneMemory, AMeshBeyondTheMemoryIsRefusedNamingTheKeys) {
  // 1e6 and 1e9 times 48 cells a side: 2.3e15 and 2.3e21 vertices, beyond any machine (1e9 x 48
  // also beyond an int, which used to wrap into a 4-vertex mesh)
  for (const char* scale : {"[1e6, 1e6]", "[1e9, 1e9]", "[1, 1e12]"}) {
    const std::string message = mesh_refusal(scale, 48);
    EXPECT_THAT(message, HasSubstr("big.json: the mesh of models[0] (sheet) at resolution 48 x "
                                   "resolution_scale ["))
        << scale;
    EXPECT_THAT(message, HasSubstr("MB of memory available; lower output.resolution (or "
                                   "--resolution) or models[0].resolution_scale"))
        << scale;
  }
  EXPECT_EQ(mesh_refusal("[1, 1]", 48), "meshed");
  // Under a limit of 100 MB: 400 x 400 cells (1.6e5 vertices, about 0.2 GB) are refused, 48 x 48
  // pass
  ::setenv("DNURBS_MEMORY_LIMIT", "1e8", 1);
  EXPECT_THAT(mesh_refusal("[1, 1]", 400), HasSubstr("MB, more than the 100 MB of memory"));
  EXPECT_EQ(mesh_refusal("[1, 1]", 48), "meshed");
  ::unsetenv("DNURBS_MEMORY_LIMIT");
}

std::string grid_scene(int nodes) {
  return R"({"models": [{"name": "cloth", "type": "terzopoulos_surface", "grid": {"nodes": [)" +
         std::to_string(nodes) + ", " + std::to_string(nodes) +
         R"(], "spacing": 0.1}}], "run": {"steps": 1}})";
}

TEST(SceneMemory, AGridBeyondTheMemoryIsRefusedBeforeItIsBuilt) {
  // 4096 x 4096 nodes: about 8 KB a node times the factor's fill, some 200 GB
  try {
    const SceneSimulation simulation(parse_scene_json(grid_scene(4096), "grid.json"));
    FAIL() << "built";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("grid.json: models[0]: the model needs about "));
    EXPECT_THAT(error.what(), HasSubstr("MB of memory available; lower models[0].grid.nodes"));
  }
  ::setenv("DNURBS_MEMORY_LIMIT", "1e8", 1);  // 100 MB: 300 x 300 (0.7 GB) refused, 30 x 30 built
  EXPECT_THROW(SceneSimulation(parse_scene_json(grid_scene(300), "grid.json")), Error);
  EXPECT_NO_THROW(SceneSimulation(parse_scene_json(grid_scene(30), "grid.json")));
  ::unsetenv("DNURBS_MEMORY_LIMIT");
}

}  // namespace
}  // namespace dnurbs
