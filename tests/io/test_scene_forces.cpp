// The force types of io/scene_forces.h that tests/io/test_scene.cpp's full scene does not hold:
// "wind" (its keys, defaults, round trip, refusals with their JSON paths) and the flag of
// examples/scenes/flag_in_wind.json.

#include "dnurbs/io/scene_forces.h"

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

// A sheet, a rod and a second sheet; `forces` is the forces array.
std::string wind_scene(const std::string& forces) {
  return R"json({
  "models": [
    {"name": "sheet", "type": "terzopoulos_surface", "grid": {"nodes": [4, 4], "spacing": 0.25},
     "material": {"eta": [[1, 0], [0, 1]]}},
    {"name": "rod", "type": "dnurbs_curve", "make": {"kind": "line"}},
    {"name": "patch", "type": "dnurbs_surface", "make": {"kind": "plane"}}
  ],
  "forces": )json" +
         forces + R"json(,
  "run": {"steps": 2}
})json";
}

TEST(SceneWind, KeysAreReadAndWrittenBackIdentically) {
  const Scene scene = parse_scene_json(wind_scene(R"json([
    {"type": "wind", "velocity": [3, 0, 1], "drag": 0.5},
    {"type": "wind", "model": "patch", "drag": 2, "start": 0.5, "end": 4,
     "velocity": {"times": [0, 1, 2], "values": [[1, 0, 0], [2, 1, 0], [0, 0, 3]]}}])json"));
  ASSERT_EQ(scene.forces.size(), 2U);
  const auto& every = dynamic_cast<const SceneWind&>(*scene.forces[0].spec);
  const auto& one = dynamic_cast<const SceneWind&>(*scene.forces[1].spec);
  EXPECT_EQ(every.model, -1);  // absent: every surface model
  EXPECT_EQ(every.drag, 0.5);
  EXPECT_EQ(every.velocity.at(7.0), Eigen::Vector3d(3, 0, 1));
  EXPECT_EQ(one.model, 2);
  EXPECT_EQ(one.drag, 2.0);
  EXPECT_EQ(one.velocity.at(2.0), Eigen::Vector3d(0, 0, 3));
  EXPECT_EQ(scene.forces[1].start, 0.5);
  EXPECT_EQ(scene.forces[1].end, 4.0);
  const std::string written = scene_to_json(scene);
  const Scene again = parse_scene_json(written);
  EXPECT_TRUE(again == scene) << written;
  EXPECT_EQ(scene_to_json(again), written);
  EXPECT_THAT(written, HasSubstr("\"type\": \"wind\""));
  // The wind is part of the simulated state: its drag changes the state hash
  Scene changed = again;
  dynamic_cast<SceneWind&>(*changed.forces[0].spec).drag = 0.6;
  EXPECT_NE(scene_state_hash(changed), scene_state_hash(scene));
}

TEST(SceneSchedule, InterpolationIsReadWrittenBackAndRefusedNamingItsPath) {
  const Scene scene = parse_scene_json(wind_scene(R"json([
    {"type": "point", "model": "sheet", "at": [0.5, 0.5],
     "force": {"times": [0, 1, 1.05], "values": [[-3, 0, 0], [-3, 0, 0], [0, 0, 0]],
               "interpolation": "cubic"}},
    {"type": "pressure", "model": "patch",
     "pressure": {"times": [0, 1, 2], "values": [0, 2, 0], "interpolation": "linear"}},
    {"type": "wind", "drag": 1, "velocity": {"times": [0, 1, 2], "values": [[0, 0, 0], [1, 0, 0], [1, 0, 0]]}}])json"));
  const auto& point = dynamic_cast<const ScenePointForce&>(*scene.forces[0].spec);
  const auto& pressure = dynamic_cast<const ScenePressure&>(*scene.forces[1].spec);
  const auto& wind = dynamic_cast<const SceneWind&>(*scene.forces[2].spec);
  EXPECT_EQ(point.force.interpolation, Interpolation::kCubic);
  EXPECT_EQ(pressure.pressure.interpolation, Interpolation::kLinear);
  EXPECT_EQ(wind.velocity.interpolation, Interpolation::kMonotone);  // absent: monotone
  EXPECT_NEAR(pressure.pressure.at(1.5), 1.0, 1e-15);
  const std::string written = scene_to_json(scene);
  EXPECT_THAT(written, HasSubstr("\"interpolation\": \"cubic\""));
  EXPECT_THAT(written, HasSubstr("\"interpolation\": \"linear\""));
  EXPECT_THAT(written, HasSubstr("\"interpolation\": \"monotone\""));
  const Scene again = parse_scene_json(written);
  EXPECT_TRUE(again == scene) << written;
  EXPECT_EQ(scene_to_json(again), written);
  // The interpolation is part of the simulated state
  Scene changed = again;
  dynamic_cast<ScenePointForce&>(*changed.forces[0].spec).force.interpolation =
      Interpolation::kMonotone;
  EXPECT_FALSE(changed == scene);
  EXPECT_NE(scene_state_hash(changed), scene_state_hash(scene));
  const auto message = [](const std::string& forces) {
    return testing::error_message([&] { (void)parse_scene_json(wind_scene(forces), "s.json"); });
  };
  EXPECT_THAT(
      message(R"([{"type": "point", "model": 0, "at": [0.5, 0.5],
                   "force": {"times": [0, 1], "values": [[0, 0, 0], [1, 0, 0]], "interpolation": "spline"}}])"),
      HasSubstr("s.json: forces[0].force.interpolation: expected \"cubic\", \"monotone\" or "
                "\"linear\", got string \"spline\""));
  EXPECT_THAT(message(R"([{"type": "pressure", "model": 0,
                           "pressure": {"times": [0, 1], "values": [0, 1], "interpolation": 3}}])"),
              HasSubstr("forces[0].pressure.interpolation: expected \"cubic\", \"monotone\" or "
                        "\"linear\", got number 3"));
}

TEST(SceneWind, EverySurfaceModelFeelsItAndNoCurve) {
  // Model -1: one force on each of the two surfaces, none on the rod
  const SceneSimulation simulation(parse_scene_json(
      wind_scene(R"json([{"type": "wind", "velocity": [0, 0, 2], "drag": 1}])json")));
  EXPECT_EQ(simulation.system().force_count(), 2);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(simulation.system().velocity_count());
  const System& system = simulation.system();
  system.add_applied_forces(0.0, system.coordinates(), system.velocities(), force);
  // The 4 x 4 sheet at h = 0.25: 16 nodes of area 1/16 feel drag * 2 upwards in all, and the
  // unit patch (area 1, exact quadrature) as much: 2 each, to round-off
  const auto total_z = [&](int model) {
    const Eigen::VectorXd f =
        force.segment(system.velocity_offset(model), system.model(model).velocity_count());
    return f.reshaped(3, f.size() / 3).row(2).sum();
  };
  EXPECT_NEAR(total_z(0), 2.0, 1e-14);
  EXPECT_NEAR(total_z(2), 2.0, 1e-13);
  EXPECT_EQ(force.segment(system.velocity_offset(1), system.model(1).velocity_count())
                .cwiseAbs()
                .maxCoeff(),
            0.0);
}

TEST(SceneWind, BadValuesAreRefusedNamingTheirPath) {
  const auto message = [](const std::string& forces) {
    return testing::error_message(
        [&] { SceneSimulation simulation(parse_scene_json(wind_scene(forces), "w.json")); });
  };
  EXPECT_THAT(message(R"([{"type": "wind", "velocity": [1, 0, 0], "drag": -1}])"),
              HasSubstr("w.json: forces[0].drag: expected a number >= 0, got -1"));
  EXPECT_THAT(message(R"([{"type": "gravity"}, {"type": "wind", "velocity": [1, 0, 0]}])"),
              HasSubstr("forces[1].drag: missing key"));
  EXPECT_THAT(message(R"([{"type": "wind", "drag": 1}])"),
              HasSubstr("forces[0].velocity: missing key"));
  EXPECT_THAT(message(R"([{"type": "wind", "drag": 1, "velocity": [1, 0]}])"),
              HasSubstr("forces[0].velocity"));
  EXPECT_THAT(message(R"([{"type": "wind", "drag": 1, "velocity": [1, 0, 0], "speed": 2}])"),
              HasSubstr("forces[0].speed"));
  EXPECT_THAT(message(R"([{"type": "wind", "drag": 1, "velocity": [1, 0, 0], "model": "x"}])"),
              HasSubstr("forces[0].model"));
  // A curve named explicitly: it would feel nothing
  EXPECT_THAT(message(R"([{"type": "wind", "drag": 1, "velocity": [1, 0, 0], "model": "rod"}])"),
              HasSubstr("forces[0].model: expected a surface model: model 1 is a curve"));
}

TEST(FlagInWind, TheFreeEdgeStreamsDownwindAndStaysFinite) {
  SceneSimulation simulation(read_scene_file(kScenes / "flag_in_wind.json"));
  const System& system = simulation.system();
  const Eigen::VectorXd start = system.coordinates();
  for (int step = 0; step < simulation.scene().step_count(); ++step) {
    simulation.step();
  }
  const Eigen::VectorXd& q = system.coordinates();
  ASSERT_TRUE(q.allFinite());
  ASSERT_TRUE(system.velocities().allFinite());
  // The flag is 9 nodes along the wind's cross direction (i, free edge i = 8) by 6 up the pole
  double free_edge_dx = 0.0;
  double every_dx = 0.0;
  for (int j = 0; j < 6; ++j) {
    const int k = 8 + 9 * j;
    free_edge_dx += (q[3 * k] - start[3 * k]) / 6.0;
  }
  for (int k = 0; k < 54; ++k) {
    every_dx += (q[3 * k] - start[3 * k]) / 54.0;
  }
  std::printf("flag: mean x displacement of the free edge %.4f, of every node %.4f\n", free_edge_dx,
              every_dx);
  // The flag is 1 long and starts square to the wind: its free edge has swung downwind
  // (measured 0.35 at t = 2, while the gusts keep it flapping)
  EXPECT_GT(free_edge_dx, 0.25);
  EXPECT_GT(every_dx, 0.0);
  // The pole edge (i = 0) is pinned
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(q.segment<3>(3 * 9 * j), start.segment<3>(3 * 9 * j));
  }
}

}  // namespace
}  // namespace dnurbs
