// Tests of io/models/pde_surface_scene.h, the scene type "pde_surface": deformation regions by
// centre and radius or by box, force regions (force radius and force) and moving centres read,
// build the library's regions and forces, write back to an equal scene, and fail naming the key.

#include "dnurbs/io/models/pde_surface_scene.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/dynamics/grid/pde_force_region.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

// A flat 25 by 25 grid of spacing 1/24 with the given regions.
std::string scene_with(const std::string& regions) {
  return R"({"models": [{"name": "plate", "type": "pde_surface",
    "grid": {"nodes": [25, 25], "spacing": 0.041666666666666664, "origin": [0, 0, 0]},
    "material": {"damping": 2}, "regions": [)" +
         regions + R"(]}], "integrator": {"scheme": "implicit-euler", "dt": 0.01},
    "run": {"steps": 1}})";
}

std::string parse_error(const std::string& text) {
  try {
    parse_scene_json(text, "bad.json");
  } catch (const Error& error) {
    return error.what();
  }
  return {};
}

TEST(PdeSurfaceScene, BoxRegionAndForceRegionBuildTheLibrarysOnes) {
  const Scene scene = parse_scene_json(scene_with(
      R"({"box": {"min": [0.25, 0.25, -1], "max": [0.75, 0.75, 1]},
          "centre": [0.5, 0.5, 0], "force_radius": 0.1, "force": [0, 0, 300]})"));
  const SceneSimulation simulation(scene);
  const auto& surface = dynamic_cast<const PdeSurface&>(simulation.system().model(0));
  EXPECT_EQ(surface.coordinate_count(), 3 * 11 * 11);  // the nodes strictly inside the box
  Eigen::VectorXd f = Eigen::VectorXd::Zero(surface.coordinate_count());
  simulation.system().add_applied_forces(0.0, simulation.system().coordinates(),
                                         simulation.system().velocities(), f);
  EXPECT_EQ(f.sum(), 300.0 * 21);  // 300 on each of the 21 nodes within the force radius
  EXPECT_TRUE(parse_scene_json(scene_to_json(scene)) == scene);
}

TEST(PdeSurfaceScene, MovingCentreSweepsItsPath) {
  const Scene scene = parse_scene_json(scene_with(
      R"({"centre": {"times": [0, 1], "values": [[0.3, 0.5, 0], [0.7, 0.5, 0]]},
          "radius": 0.2, "force_radius": 0.08, "force": [0, 0, 1]})"));
  const SceneSimulation simulation(scene);
  const auto& spec = dynamic_cast<const ScenePdeSurface&>(*scene.models[0].spec);
  const PdeSurface swept(
      Grid(25, 25, 1.0 / 24), flat_grid_positions(Grid(25, 25, 1.0 / 24), Eigen::Vector3d::Zero()),
      {},
      swept_deformation_regions([](double t) { return Eigen::Vector3d(0.3 + 0.4 * t, 0.5, 0); },
                                0.2, 0.0, 1.0, 0.5 / 24));
  EXPECT_EQ(simulation.system().model(0).coordinate_count(), swept.coordinate_count());
  EXPECT_GT(spec.deformation_regions().size(), 1U);
  EXPECT_TRUE(parse_scene_json(scene_to_json(scene)) == scene);
}

TEST(PdeSurfaceScene, BadRegionsNameTheirKeys) {
  EXPECT_THAT(parse_error(scene_with(R"({"centre": [0.5, 0.5, 0]})")),
              HasSubstr("models[0].regions[0]: a region needs exactly one of"));
  EXPECT_THAT(
      parse_error(scene_with(
          R"({"centre": [0.5, 0.5, 0], "radius": 0.2, "box": {"min": [0, 0, 0], "max": [1, 1, 0]}})")),
      HasSubstr("models[0].regions[0]: a region needs exactly one of"));
  EXPECT_THAT(parse_error(scene_with(R"({"box": {"min": [0.5, 0, 0], "max": [0.4, 1, 0]}})")),
              HasSubstr("models[0].regions[0].box.max"));
  EXPECT_THAT(parse_error(scene_with(R"({"box": {"min": [0, 0, 0]}})")),
              HasSubstr("models[0].regions[0].box"));
  EXPECT_THAT(parse_error(scene_with(R"({"centre": [0.5, 0.5, 0], "radius": 0.2,
                                         "force_radius": 0.1})")),
              HasSubstr("models[0].regions[0].force"));
  EXPECT_THAT(parse_error(scene_with(R"({"centre": [0.5, 0.5, 0], "radius": 0.2,
                                         "force_radius": -1, "force": [0, 0, 1]})")),
              HasSubstr("models[0].regions[0].force_radius"));
  EXPECT_THAT(parse_error(scene_with(
                  R"({"centre": [0.5, 0.5, 0], "box": {"min": [0, 0, 0], "max": [1, 1, 0]}})")),
              HasSubstr("models[0].regions[0].centre"));
  // A box too thin for an interior node fails when the model is built, naming the model
  try {
    const SceneSimulation simulation(
        parse_scene_json(scene_with(R"({"box": {"min": [0.5, 0, -1], "max": [0.55, 1, 1]}})")));
    ADD_FAILURE() << "a thin box was accepted";
  } catch (const Error& error) {
    EXPECT_THAT(std::string(error.what()), HasSubstr("models[0]"));
    EXPECT_THAT(std::string(error.what()), HasSubstr("box region from (0.5, 0, -1)"));
  }
}

}  // namespace
}  // namespace dnurbs
