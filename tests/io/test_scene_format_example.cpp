// The first example of docs/scene-format.md, as a reader copies it: it loads on its own (no file
// it refers to is missing), its sheet starts at rest, and its spring lifts the centre toward
// the target the text describes.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"

namespace dnurbs {
namespace {

std::string first_json_example() {
  std::ifstream in(std::filesystem::path(DNURBS_TEST_DATA_DIR) / ".." / ".." / "docs" /
                   "scene-format.md");
  std::ostringstream text;
  text << in.rdbuf();
  const std::string docs = text.str();
  const std::string fence = "```json\n";
  const size_t start = docs.find(fence);
  const size_t end = docs.find("```", start + fence.size());
  if (start == std::string::npos || end == std::string::npos) {
    ADD_FAILURE() << "docs/scene-format.md has no ```json example";
    return {};
  }
  return docs.substr(start + fence.size(), end - start - fence.size());
}

TEST(SceneFormatExample, LoadsAsCopiedAndItsSheetStartsAtRest) {
  Scene scene = parse_scene_json(first_json_example(), "docs/scene-format.md");
  ASSERT_EQ(scene.models.size(), 1U);
  // Without its spring the sheet stays where it is: the tension exerts no force on a surface
  // linear in its parameters (round-off of the quadrature sums only)
  scene.forces.clear();
  SceneSimulation simulation(scene);
  const Eigen::VectorXd start = simulation.system().coordinates();
  for (int step = 0; step < 20; ++step) {
    simulation.step();
  }
  EXPECT_LT((simulation.system().coordinates() - start).lpNorm<Eigen::Infinity>(), 1e-13);
}

TEST(SceneFormatExample, TheSpringLiftsTheCentreTowardItsTarget) {
  SceneSimulation simulation(parse_scene_json(first_json_example(), "docs/scene-format.md"));
  const int steps = simulation.scene().step_count();
  ASSERT_EQ(steps, 100);
  for (int step = 0; step < steps; ++step) {
    simulation.step();
  }
  const Eigen::Vector3d centre = simulation.sample().probes.at(0);
  // By symmetry the centre only rises; the clamped sheet's tension holds it below the target
  // (1.5, 1.5, 0.5), which the spring reached at t = 1
  EXPECT_NEAR(centre.x(), 1.5, 1e-12);
  EXPECT_NEAR(centre.y(), 1.5, 1e-12);
  EXPECT_GT(centre.z(), 0.1);
  EXPECT_LT(centre.z(), 0.5);
}

}  // namespace
}  // namespace dnurbs
