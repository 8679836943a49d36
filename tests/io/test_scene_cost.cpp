// What a scene pays for: active coordinates, constant matrices and the saving of each automatic
// choice against the naive path (dnurbs info prints these).

#include <filesystem>

#include <gtest/gtest.h>

#include "io/scene.h"
#include "io/scene_simulation.h"

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
  // State-dependent: the 6 x 6 factorisation (sum of squared column counts 5^2 + ... + 0^2)
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

}  // namespace
}  // namespace dnurbs
