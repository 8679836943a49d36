// Obstacles in scene files (io/scene_obstacles.h): the keys "obstacles" and "contact" read,
// written back and refused with their JSON paths, the contact points of each kind of model, and
// the rug of examples/scenes/rug_on_obstacles.json at rest on its obstacles.

#include "dnurbs/io/scene_obstacles.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kScenes =
    std::filesystem::path(DNURBS_TEST_DATA_DIR) / ".." / ".." / "examples" / "scenes";

// A grid sheet and a D-NURBS patch above the ground; `extra` holds further top-level keys.
std::string obstacle_scene(const std::string& extra) {
  return R"json({
  "models": [
    {"name": "sheet", "type": "terzopoulos_surface",
     "grid": {"nodes": [4, 4], "spacing": 0.25, "origin": [0, 0, 1]},
     "material": {"eta": [[1, 0], [0, 1]]}},
    {"name": "patch", "type": "dnurbs_surface",
     "make": {"kind": "plane", "origin": [2, 0, 0.5]}, "material": {"a10": 1, "a01": 1}}
  ],
  "run": {"steps": 2})json" +
         extra + "\n}";
}

const char* const kObstacles = R"json(,
  "obstacles": [
    {"type": "plane", "point": [0, 0, -0.5], "normal": [0, 0.1, 1]},
    {"type": "box", "min": [-1, -1, -2], "max": [1, 1, 0]},
    {"type": "sphere", "centre": [2.5, 0.5, 0], "radius": 0.25}
  ],
  "contact": {"method": "penalty", "stiffness": 500, "damping": 2, "friction": 0.25})json";

TEST(SceneObstacles, KeysAreReadAndWrittenBackIdentically) {
  const Scene scene = parse_scene_json(obstacle_scene(kObstacles));
  ASSERT_EQ(scene.obstacles.size(), 3U);
  const auto& plane = std::get<GroundPlane>(scene.obstacles[0]);
  EXPECT_EQ(plane.point, Eigen::Vector3d(0, 0, -0.5));
  EXPECT_EQ(plane.normal, Eigen::Vector3d(0, 0.1, 1));
  const auto& box = std::get<BoxObstacle>(scene.obstacles[1]);
  EXPECT_EQ(box.minimum, Eigen::Vector3d(-1, -1, -2));
  EXPECT_EQ(box.maximum, Eigen::Vector3d(1, 1, 0));
  const auto& sphere = std::get<SphereObstacle>(scene.obstacles[2]);
  EXPECT_EQ(sphere.centre, Eigen::Vector3d(2.5, 0.5, 0));
  EXPECT_EQ(sphere.radius, 0.25);
  EXPECT_EQ(scene.contact.method, "penalty");
  EXPECT_EQ(scene.contact.settings.stiffness, 500.0);
  EXPECT_EQ(scene.contact.settings.damping, 2.0);
  EXPECT_EQ(scene.contact.settings.friction, 0.25);
  const std::string written = scene_to_json(scene);
  const Scene again = parse_scene_json(written);
  EXPECT_TRUE(again == scene) << written;
  EXPECT_EQ(scene_to_json(again), written);
  // Obstacles are part of the simulated state; a scene without them writes no key, so its
  // state hash (and its checkpoints) are those of before obstacles existed
  const Scene bare = parse_scene_json(obstacle_scene(""));
  EXPECT_NE(scene_state_hash(bare), scene_state_hash(scene));
  EXPECT_THAT(scene_to_json(bare), ::testing::Not(HasSubstr("obstacles")));
  EXPECT_THAT(scene_to_json(bare), ::testing::Not(HasSubstr("contact")));
  Scene changed = again;
  std::get<SphereObstacle>(changed.obstacles[2]).radius = 0.3;
  EXPECT_NE(scene_state_hash(changed), scene_state_hash(scene));
  // Defaults: penalty contact with ContactSettings' values
  const Scene defaults =
      parse_scene_json(obstacle_scene(R"json(, "obstacles": [{"type": "plane", "point": [0, 0, 0],
      "normal": [0, 0, 1]}])json"));
  EXPECT_EQ(defaults.contact.method, "penalty");
  EXPECT_EQ(defaults.contact.settings.stiffness, ContactSettings{}.stiffness);
  EXPECT_EQ(defaults.contact.settings.friction, 0.0);
}

TEST(SceneObstacles, BadValuesAreRefusedNamingTheirPath) {
  const auto message = [](const std::string& extra) {
    return testing::error_message(
        [&] { SceneSimulation simulation(parse_scene_json(obstacle_scene(extra), "o.json")); });
  };
  const std::string plane = R"({"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]})";
  EXPECT_THAT(message(R"(, "obstacles": [)" + plane +
                      R"(, {"type": "sphere", "centre": [0, 0, 0], "radius": 0}])"),
              HasSubstr("o.json: obstacles[1].radius: expected a number > 0, got 0"));
  EXPECT_THAT(
      message(R"(, "obstacles": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 0]}])"),
      HasSubstr("obstacles[0].normal: expected a non-zero normal"));
  EXPECT_THAT(message(R"(, "obstacles": [)" + plane + "," + plane +
                      R"(, {"type": "box", "min": [0, 0, 0], "max": [1, 0, 1]}])"),
              HasSubstr("obstacles[2].max: expected a corner above min in every coordinate, got "
                        "0 <= 0 in coordinate 1"));
  EXPECT_THAT(message(R"(, "obstacles": [{"type": "cone"}])"), HasSubstr("obstacles[0].type"));
  EXPECT_THAT(
      message(
          R"(, "obstacles": [{"type": "sphere", "centre": [0, 0, 0], "radius": 1, "colour": 1}])"),
      HasSubstr("obstacles[0].colour"));
  EXPECT_THAT(message(R"(, "obstacles": [{"type": "box", "min": [0, 0, 0]}])"),
              HasSubstr("obstacles[0].max: missing key"));
  EXPECT_THAT(message(R"(, "obstacles": {"type": "box"})"), HasSubstr("obstacles: expected"));
  EXPECT_THAT(message(R"(, "obstacles": [)" + plane + R"(], "contact": {"method": "glue"})"),
              HasSubstr("contact.method"));
  EXPECT_THAT(message(R"(, "obstacles": [)" + plane + R"(], "contact": {"friction": -1})"),
              HasSubstr("contact.friction: expected a number >= 0, got -1"));
  EXPECT_THAT(message(R"(, "obstacles": [)" + plane + R"(], "contact": {"stiff": 1})"),
              HasSubstr("contact.stiff"));
  EXPECT_THAT(message(R"(, "contact": {"method": "penalty"})"),
              HasSubstr("o.json: contact: expected no contact settings without \"obstacles\""));
  // Projection moves nodes: the D-NURBS patch has none, and is named
  EXPECT_THAT(message(R"(, "obstacles": [)" + plane + R"(], "contact": {"method": "projection"})"),
              HasSubstr("o.json: contact.method: expected \"penalty\": model 1 (patch, a "
                        "dnurbs_surface) has no nodes to project"));
}

TEST(SceneObstacles, GridModelsMeetObstaclesAtTheirNodesOthersAtALattice) {
  const SceneSimulation simulation(parse_scene_json(obstacle_scene(kObstacles)));
  const SceneContacts& contacts = simulation.contacts();
  ASSERT_FALSE(contacts.empty());
  // The 4 x 4 sheet: its 16 nodes (i h, j h) in node order; the patch: 16 x 16 samples of
  // [0, 1]^2 with both ends
  ASSERT_EQ(contacts.points(0).size(), 16U);
  EXPECT_EQ(contacts.points(0)[5], Eigen::Vector2d(0.25, 0.25));
  EXPECT_EQ(contacts.points(0)[15], Eigen::Vector2d(0.75, 0.75));
  ASSERT_EQ(contacts.points(1).size(), 256U);
  EXPECT_EQ(contacts.points(1).front(), Eigen::Vector2d(0, 0));
  EXPECT_EQ(contacts.points(1).back(), Eigen::Vector2d(1, 1));
  // Penalty contact: one force per model
  EXPECT_EQ(simulation.system().force_count(), 2);

  // A closed snake of 5 nodes: s = k / 5; an open one of 4: s = k / 3; a PDE surface with a
  // region: only its simulated nodes
  const Scene chains = parse_scene_json(R"json({
    "models": [
      {"type": "snake", "nodes": [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1], [-0.5, 0.5, 1]],
       "closed": true},
      {"type": "snake", "nodes": [[0, 0, 1], [1, 0, 1], [2, 0, 1], [3, 0, 1]]},
      {"type": "pde_surface", "grid": {"nodes": [9, 9], "spacing": 0.125},
       "regions": [{"centre": [0.5, 0.5, 0], "radius": 0.2}]},
      {"type": "dnurbs_curve", "make": {"kind": "line"}}
    ],
    "obstacles": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}],
    "contact": {"method": "penalty"},
    "run": {"steps": 1}})json");
  const SceneSimulation chain_simulation(chains);
  const SceneContacts& chain_contacts = chain_simulation.contacts();
  ASSERT_EQ(chain_contacts.points(0).size(), 5U);
  EXPECT_EQ(chain_contacts.points(0)[2].x(), 0.4);
  ASSERT_EQ(chain_contacts.points(1).size(), 4U);
  EXPECT_EQ(chain_contacts.points(1)[3].x(), 1.0);
  const size_t active = chain_contacts.points(2).size();
  EXPECT_GT(active, 0U);
  EXPECT_LT(active, 81U);
  for (const Eigen::Vector2d& u : chain_contacts.points(2)) {
    EXPECT_LE((u - Eigen::Vector2d(0.5, 0.5)).norm(), 0.2 + 1e-12);
  }
  EXPECT_EQ(chain_contacts.points(3).size(), 32U);  // a D-NURBS rod: 32 samples
  // 3 * 0.2 / 0.2 rounds to 3 + 4e-16: node 3 of the closed snake has no parameter that picks
  // it alone, so projection could not move it and is refused
  Scene projected = chains;
  projected.models.resize(1);
  projected.contact.method = "projection";
  EXPECT_THAT(testing::error_message([&] { SceneSimulation simulation(projected); }),
              HasSubstr("contact.method: expected \"penalty\": the node of model 0 (model0, a "
                        "snake) at parameter 0.60000000000000009 is not picked exactly"));
}

TEST(SceneObstacles, PenaltyContactHoldsADNurbsSheetOnTheGround) {
  // The patch falls 0.05 onto the plane z = 0 under penalty contact: it ends resting on it,
  // sunk by about its weight over the stiffness of its 256 samples, 9.81 / (256 * 50) = 7.7e-4
  // (the penalty is explicit: k = 256 * 50 and c = 256 * 0.2 against the unit mass keep
  // omega dt = 0.57 and c dt / m = 0.26 stable)
  const Scene scene = parse_scene_json(R"json({
    "models": [{"name": "patch", "type": "dnurbs_surface",
                "make": {"kind": "plane", "origin": [0, 0, 0.05]},
                "material": {"damping_density": 2, "a10": 1, "a01": 1}}],
    "forces": [{"type": "gravity", "acceleration": [0, 0, -9.81]}],
    "obstacles": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}],
    "contact": {"method": "penalty", "stiffness": 50, "damping": 0.2},
    "integrator": {"scheme": "implicit-euler", "dt": 0.005},
    "run": {"steps": 1200}})json");
  SceneSimulation simulation(scene);
  for (int step = 0; step < scene.step_count(); ++step) {
    simulation.step();
  }
  const double depth = simulation.contacts().max_penetration(simulation.system());
  const double centre_z = simulation.system().position(0, Eigen::Vector2d(0.5, 0.5)).z();
  std::printf(
      "penalty: patch at rest %.3e deep (weight / stiffness of the samples %.3e), "
      "centre z %.3e, kinetic energy %.3e\n",
      depth, 9.81 / (256 * 50.0), centre_z, simulation.system().kinetic_energy());
  EXPECT_LT(depth, 2e-3);
  EXPECT_LT(std::abs(centre_z), 2e-3);
  EXPECT_LT(simulation.system().kinetic_energy(), 1e-4);  // of the fall's m g h = 0.49
}

// The rug of the example, `steps` steps (every step when 0)
SceneSimulation run_rug(int steps) {
  SceneSimulation simulation(read_scene_file(kScenes / "rug_on_obstacles.json"));
  const int count = steps > 0 ? steps : simulation.scene().step_count();
  for (int step = 0; step < count; ++step) {
    simulation.step();
  }
  return simulation;
}

TEST(RugOnObstacles, ComesToRestDrapedOverTheBoxAndSphereWithoutPassingThrough) {
  const SceneSimulation simulation = run_rug(0);
  const System& system = simulation.system();
  const Scene& scene = simulation.scene();
  ASSERT_EQ(scene.obstacles.size(), 3U);
  const double box_top = std::get<BoxObstacle>(scene.obstacles[1]).maximum.z();
  // Projection leaves each node on the surface it was pushed to: only the round-off of
  // x + depth n remains (ulps of the coordinates)
  const double depth = simulation.contacts().max_penetration(system);
  const Eigen::VectorXd& q = system.coordinates();
  const auto z = q.reshaped(3, q.size() / 3).row(2);
  const int below_top = static_cast<int>((z.array() < box_top - 0.1).count());
  const double kinetic = system.kinetic_energy();
  // The rug's weight times its fall, 1.5^2 mu g 0.8 (mu = 1), against which "at rest" is small
  const double fall_energy = 2.25 * 9.81 * 0.8;
  std::printf(
      "rug: deepest node %.3e inside an obstacle, kinetic energy %.3e (%.2e of the fall's "
      "energy), %d of 169 nodes more than 0.1 below the box top, lowest z %.4f, "
      "highest z %.4f\n",
      depth, kinetic, kinetic / fall_energy, below_top, z.minCoeff(), z.maxCoeff());
  EXPECT_LE(depth, 1e-12);
  EXPECT_LT(kinetic, 1e-3 * fall_energy);
  EXPECT_GT(below_top, 20);         // draped: the free border hangs down
  EXPECT_GE(z.minCoeff(), -1e-12);  // on the ground, not through it
  // Nodes lie on the box top and on the sphere, where the projection put them
  const auto& box = std::get<BoxObstacle>(scene.obstacles[1]);
  const auto& sphere = std::get<SphereObstacle>(scene.obstacles[2]);
  int on_top = 0;
  int on_sphere = 0;
  for (Eigen::Index k = 0; k < q.size() / 3; ++k) {
    const Eigen::Vector3d x = q.segment<3>(3 * k);
    on_top += std::abs(x.z() - box_top) < 1e-9 && x.x() > box.minimum.x() &&
              x.x() < box.maximum.x() && x.y() > box.minimum.y() && x.y() < box.maximum.y();
    on_sphere += std::abs((x - sphere.centre).norm() - sphere.radius) < 1e-9;
  }
  std::printf("rug: %d nodes on the box top, %d on the sphere\n", on_top, on_sphere);
  EXPECT_GE(on_top, 4);
  EXPECT_GE(on_sphere, 1);
  EXPECT_TRUE(q.allFinite());
}

TEST(RugOnObstacles, ResumingFromACheckpointRepeatsTheRunBitForBit) {
  // Projection is part of the step: a checkpoint after a projected step resumes into the same
  // states as the run that wrote it (the projection invalidates Newmark's stored acceleration,
  // which the checkpoint records)
  const SceneSimulation whole = run_rug(120);
  SceneSimulation first = run_rug(70);
  SceneSimulation resumed(read_scene_file(kScenes / "rug_on_obstacles.json"));
  resumed.restore(first.checkpoint(), "checkpoint.json");
  for (int step = 70; step < 120; ++step) {
    resumed.step();
  }
  EXPECT_EQ(resumed.system().coordinates(), whole.system().coordinates());
  EXPECT_EQ(resumed.system().velocities(), whole.system().velocities());
}

}  // namespace
}  // namespace dnurbs
