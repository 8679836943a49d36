// What a scene pays for: active coordinates, constant matrices and the saving of each automatic
// choice against the naive path (dnurbs info prints these).

#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"

namespace dnurbs {
namespace {

const std::filesystem::path kScenes =
    std::filesystem::path(DNURBS_TEST_DATA_DIR) / ".." / ".." / "examples" / "scenes";

const SceneModelCost& cost_of(const std::vector<SceneModelCost>& costs, const std::string& name) {
  for (const SceneModelCost& c : costs) {
    if (c.name == name) {
      return c;
    }
  }
  throw std::runtime_error("no model " + name);
}

TEST(SceneCost, DefaultDemoCountsActiveCoordinatesAndTheSavingOfEachChoice) {
  const SceneSimulation simulation(read_scene_file(kScenes / "hat_demo.json"));
  const std::vector<SceneModelCost> costs = simulation.cost();
  // The hat: 7 x 7 bicubic control points, the 24 on the border clamped: 25 x 3 active; with
  // free weights 49 x 4 velocities less the border's 72 and the weight gauge's 1
  const SceneModelCost& hat = cost_of(costs, "hat");
  EXPECT_EQ(hat.velocities, 147);
  EXPECT_EQ(hat.velocities - hat.fixed, 75);
  EXPECT_EQ(hat.naive_active, 196 - 72 - 1);
  EXPECT_TRUE(hat.constant_matrices);
  EXPECT_FALSE(hat.naive_constant_matrices);
  EXPECT_EQ(hat.kronecker_block, 3);
  // The scalar matrix over the 5 x 5 interior nodes (indices 1..5 each way): bicubic nodes
  // couple when their indices differ by at most 3 in u and in v, which 23 of the 25 ordered
  // pairs of 1..5 do (not (1, 5) and (5, 1)): 23^2 entries. Its factor holds the matrix's lower
  // triangle (252) and at most the dense 25 x 24 / 2 = 300.
  EXPECT_EQ(hat.matrix_non_zeros, 23 * 23);
  EXPECT_GE(hat.factor_non_zeros, (23 * 23 - 25) / 2);
  EXPECT_LE(hat.factor_non_zeros, 25 * 24 / 2);
  // A constant factor: one solve is a forward and a backward substitution per x, y, z
  EXPECT_EQ(hat.solve_work, 2.0 * static_cast<double>(hat.factor_non_zeros) * 3);
  EXPECT_GT(hat.naive_solve_work, 100.0 * hat.solve_work);  // refactoring 123 dense unknowns
  // A rigid superquadric: 6 velocities against the full model's rigid + global + local parts
  const SceneModelCost& link = cost_of(costs, "link");
  EXPECT_EQ(link.velocities - link.fixed, 6);
  EXPECT_GT(link.naive_active, 6);
  EXPECT_FALSE(link.constant_matrices);
  EXPECT_EQ(link.matrix_non_zeros, 36);
  // State-dependent: the 6 x 6 factorization (sum of squared column counts 5^2 + ... + 0^2)
  // plus the two substitutions
  EXPECT_EQ(link.solve_work, 2.0 * 15 + (25 + 16 + 9 + 4 + 1));
}

TEST(SceneCost, PdeSurfaceRegionSimulatesOnlyItsNodes) {
  const SceneSimulation simulation(read_scene_file(kScenes / "pde_surface.json"));
  const SceneModelCost plate = simulation.cost().front();
  EXPECT_EQ(plate.automatic_choice, "deformation regions (naive: every grid node)");
  EXPECT_LT(plate.velocities - plate.fixed, plate.naive_active);
  EXPECT_GT(plate.naive_solve_work, plate.solve_work);
}

// A flat bicubic sheet of 9 x 9 control points (6 spans each way) with a spring at (0.5, 0.5),
// clamped, with local sculpting at `margin` (and gravity on it when `gravity`)
Scene sculpting_scene(int margin, bool gravity) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < 9; ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (int j = 0; j < 9; ++j) {
      row.push_back({i / 8.0, j / 8.0, 0.0});
    }
    rows.push_back(row);
  }
  const std::vector<double> knots{0, 0, 0, 0, 1 / 6.0, 2 / 6.0, 0.5, 4 / 6.0, 5 / 6.0, 1, 1, 1, 1};
  nlohmann::json scene = {
      {"models",
       {{{"name", "sheet"},
         {"type", "dnurbs_surface"},
         {"shape",
          {{"type", "nurbs_surface"},
           {"degree_u", 3},
           {"degree_v", 3},
           {"knots_u", knots},
           {"knots_v", knots},
           {"control_points", rows}}},
         {"material", {{"a10", 1}, {"a01", 1}}},
         {"boundary", {{"clamp_border", true}, {"local_sculpting_margin", margin}}}}}},
      {"forces",
       {{{"type", "spring"},
         {"model", "sheet"},
         {"at", {0.5, 0.5}},
         {"stiffness", 1},
         {"target", {0.5, 0.5, 0.2}}}}},
      {"run", {{"duration", 0.1}}}};
  if (gravity) {
    scene["forces"].push_back({{"type", "gravity"}, {"acceleration", {0, 0, -1}}});
  }
  return parse_scene_json(scene.dump(), "sculpting.json");
}

TEST(SceneCost, LocalSculptingKeepsTheSupportOfTheSpringGrownByTheMargin) {
  // (0.5, 0.5) starts span [0.5, 4/6) in each direction, driven by control point indices 3..6:
  // 4 x 4 control points at margin 0, 6 x 6 (2..7) at margin 1, all 7 x 7 interior ones at 2
  const auto active = [](const Scene& scene) {
    const SceneModelCost c = SceneSimulation(scene).cost().front();
    return c.velocities - c.fixed;
  };
  EXPECT_EQ(active(sculpting_scene(0, false)), 4 * 4 * 3);
  EXPECT_EQ(active(sculpting_scene(1, false)), 6 * 6 * 3);
  EXPECT_EQ(active(sculpting_scene(2, false)), 7 * 7 * 3);
  // Gravity acts everywhere: nothing is frozen
  EXPECT_EQ(active(sculpting_scene(0, true)), 7 * 7 * 3);
  // The frozen sheet still runs: the spring's point rises, the frozen control points stay
  SceneSimulation simulation(sculpting_scene(1, false));
  const Eigen::VectorXd before = simulation.system().coordinates(0);
  for (int step = 0; step < 10; ++step) {
    simulation.step();
  }
  const Eigen::VectorXd after = simulation.system().coordinates(0);
  EXPECT_GT(after[3 * (4 * 9 + 4) + 2], 0.0);  // the centre control point moved up
  EXPECT_EQ(after[3 * (1 * 9 + 1) + 2], before[3 * (1 * 9 + 1) + 2]);  // (1, 1) is frozen
}

// A simulation rebuilt with another setting continues where the old one was: Newmark's next step
// from the carried state equals the old simulation's next step when nothing else changed.
TEST(SceneSimulation, ContinueFromCarriesTheStateAndTheLastAcceleration) {
  const Scene scene = read_scene_file(kScenes / "hat_demo.json");
  SceneSimulation first(scene);
  for (int step = 0; step < 30; ++step) {
    first.step();
  }
  SceneSimulation second(scene);
  second.continue_from(first);
  EXPECT_EQ(second.steps_done(), 30);
  EXPECT_EQ(second.system().time(), first.system().time());
  EXPECT_EQ(second.system().velocities(), first.system().velocities());
  first.step();
  second.step();
  const Eigen::VectorXd q = first.system().coordinates();
  EXPECT_LT((second.system().coordinates() - q).norm(), 1e-12 * q.norm());
  // Another scene's sizes are refused
  SceneSimulation other(sculpting_scene(1, false));
  EXPECT_THROW(other.continue_from(first), Error);
}

// Springs and forces added while the scene runs act as the scene's own, and a spring removed
// stops acting.
TEST(SceneSimulation, InteractiveSpringsAndForcesActLikeTheScenesOwn) {
  nlohmann::json json = nlohmann::json::parse(scene_to_json(sculpting_scene(0, false)));
  json["models"][0]["boundary"].erase("local_sculpting_margin");
  SceneSimulation scripted(parse_scene_json(json.dump(), "<scripted>"));
  nlohmann::json bare = json;
  bare["forces"] = nlohmann::json::array();
  SceneSimulation interactive(parse_scene_json(bare.dump(), "<bare>"));
  const SpringState state = scripted.system().spring_state(0, 0.0);
  const int id = interactive.add_interactive_spring(
      0, [state](double) { return state; }, "the test's drag");
  for (int step = 0; step < 20; ++step) {
    scripted.step();
    interactive.step();
  }
  const Eigen::VectorXd q = scripted.system().coordinates();
  EXPECT_LT((interactive.system().coordinates() - q).norm(), 1e-12 * q.norm());
  interactive.remove_interactive_spring(id);
  EXPECT_FALSE(interactive.system().has_spring(id));
  const int force = interactive.add_interactive_force(
      0, point_force(Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d(0, 0, 1)), "a push");
  EXPECT_EQ(force, interactive.system().force_count() - 1);
}

}  // namespace
}  // namespace dnurbs
