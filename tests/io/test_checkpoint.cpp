// Checkpoints and resumed runs: checkpoints read back bit for bit, a run stopped part-way and
// resumed from its checkpoint ends in the same state as an uninterrupted run, the CSV log
// continues seamlessly, and a diverging run stops at its last good state.

#include "dnurbs/io/checkpoint.h"

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/io/csv_log.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_forces.h"
#include "dnurbs/io/scene_runner.h"
#include "dnurbs/io/scene_simulation.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kExamples =
    std::filesystem::path(DNURBS_TEST_DATA_DIR) / ".." / ".." / "examples" / "scenes";

std::filesystem::path fresh_directory(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("dnurbs_test_checkpoint_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Bit for bit, so that -0.0 and 0.0 differ (fuzz/fuzz_checkpoint_reader.cpp found -0.0 read
// back as 0.0: JSON "-0" is the integer 0).
bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0;
}

TEST(Checkpoint, JsonReadsBackBitForBit) {
  Checkpoint c;
  c.scene = "scenes/a \"quoted\" name.json";
  c.scene_hash = "0123456789abcdef";
  c.step = 42;
  c.time = 0.1 + 0.2;  // not a short decimal
  c.coordinates.resize(6);
  c.coordinates << 1.0 / 3.0, -2.5e-300, std::numeric_limits<double>::denorm_min(), 1e300, -0.0,
      std::nextafter(1.0, 2.0);
  c.velocities = -c.coordinates;
  c.accelerations_valid = true;
  c.accelerations = 7.0 * c.coordinates;
  const Checkpoint back = parse_checkpoint_json(checkpoint_to_json(c));
  EXPECT_EQ(back.scene, c.scene);
  EXPECT_EQ(back.scene_hash, c.scene_hash);
  EXPECT_EQ(back.step, 42);
  EXPECT_EQ(back.time, c.time);
  EXPECT_TRUE(same_bits(back.coordinates, c.coordinates));  // exact: 17 significant digits
  EXPECT_TRUE(same_bits(back.velocities, c.velocities));
  EXPECT_TRUE(back.accelerations_valid);
  EXPECT_TRUE(same_bits(back.accelerations, c.accelerations));
  c.accelerations_valid = false;
  EXPECT_EQ(parse_checkpoint_json(checkpoint_to_json(c)).accelerations.size(), 0);
}

TEST(Checkpoint, MalformedCheckpointsNameTheKey) {
  const auto message = [](const std::string& text) {
    try {
      parse_checkpoint_json(text, "cp.json");
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message("{"), HasSubstr("cp.json: (document): expected valid JSON"));
  EXPECT_THAT(message(R"({"format": "other"})"), HasSubstr("cp.json: format: expected"));
  const std::string good = R"({"format": "dnurbs-checkpoint-1", "scene": "s", "scene_hash": "h",
      "step": 3, "time": 0.5, "q": [1, 2], "qd": [0, 0], "accelerations_valid": true,
      "a": [0, 0]})";
  EXPECT_EQ(message(good), "no error");
  std::string bad = good;
  bad.replace(bad.find("[1, 2]"), 6, "[1, \"x\"]");
  EXPECT_THAT(message(bad), HasSubstr("cp.json: q[1]: expected a finite number"));
  bad = good;
  bad.replace(bad.find("\"a\": [0, 0]"), 11, "\"a\": [0]");
  EXPECT_THAT(message(bad), HasSubstr("cp.json: a: expected as many accelerations"));
  bad = good;
  bad.replace(bad.find("\"step\": 3"), 9, "\"step\": -3");
  EXPECT_THAT(message(bad), HasSubstr("cp.json: step: expected a step count"));
  // A number beyond a double names its place; a repeated key is refused, not overwritten
  bad = good;
  bad.replace(bad.find("[1, 2]"), 6, "[1, 1e999]");
  EXPECT_THAT(message(bad), HasSubstr("cp.json: (document): expected valid JSON at line 2, "
                                      "column 40: number overflow parsing '1e999'"));
  bad = good;
  bad.replace(bad.find("\"step\": 3"), 9, "\"step\": 3, \"step\": 9");
  EXPECT_THAT(message(bad), HasSubstr("cp.json: (document): expected every key once in an "
                                      "object, got string \"step\" twice"));
}

// Runs `steps` steps uninterrupted, and `split` steps + checkpoint (through its JSON text) +
// the rest in a fresh simulation; returns the largest difference of q and qd
double resume_difference(const Scene& scene, int split, int steps) {
  SceneSimulation uninterrupted(scene);
  for (int i = 0; i < steps; ++i) {
    uninterrupted.step();
  }
  SceneSimulation first(scene);
  for (int i = 0; i < split; ++i) {
    first.step();
  }
  const std::string text = checkpoint_to_json(first.checkpoint());
  SceneSimulation second(scene);
  second.restore(parse_checkpoint_json(text), "checkpoint");
  EXPECT_EQ(second.steps_done(), split);
  for (int i = split; i < steps; ++i) {
    second.step();
  }
  EXPECT_EQ(second.system().time(), uninterrupted.system().time());
  const double dq = (second.system().coordinates() - uninterrupted.system().coordinates())
                        .lpNorm<Eigen::Infinity>();
  const double dv = (second.system().velocities() - uninterrupted.system().velocities())
                        .lpNorm<Eigen::Infinity>();
  return std::max(dq, dv);
}

// Newmark (accelerations carried), central (velocity is the stored difference), implicit Euler
// with Newton iterations (state-dependent matrices), constraints with moving targets, and
// every model type but the superquadric (slow; tested through the tool)
TEST(ResumedRun, EndsInTheSameStateAsAnUninterruptedRun) {
  for (const char* name : {"hat_demo.json", "constraints.json", "snake_contour.json",
                           "cloth_terzopoulos.json", "pde_surface.json", "curve_sculpting.json"}) {
    const Scene scene = read_scene_file(kExamples / name);
    const int steps = std::min(scene.step_count(), 40);
    // The resumed run repeats the same floating-point operations on the same bits: the
    // difference is exactly 0; 1e-12 is the tolerance the format promises
    EXPECT_LE(resume_difference(scene, 17, steps), 1e-12) << name;
  }
}

// A clamped sheet with a plastic rest shape, pushed: its rest shape is part of the state.
const char* const kPlasticSheetScene = R"({"models": [{"name": "clay", "type": "dnurbs_surface",
    "make": {"kind": "plane", "size": [2, 2], "control_points": [6, 6]},
    "plastic": {"yield": 0.01, "rate": 4},
    "material": {"damping_density": 3, "a10": 1, "a01": 1, "b20": 0.1, "b11": 0.1, "b02": 0.1},
    "boundary": {"clamp_border": true}}],
  "forces": [{"type": "point", "model": "clay", "at": [1, 1], "force": [0, 0, -3]}],
  "integrator": {"dt": 0.05, "scheme": "implicit-euler"}, "run": {"steps": 30}})";

TEST(ResumedRun, APlasticRestShapeIsKeptByTheCheckpoint) {
  const Scene scene = parse_scene_json(kPlasticSheetScene);
  // The rest shape yields in the run, and a resumed run repeats it bit for bit
  EXPECT_EQ(resume_difference(scene, 13, 30), 0.0);
  SceneSimulation simulation(scene);
  for (int i = 0; i < 13; ++i) {
    simulation.step();
  }
  Checkpoint checkpoint = parse_checkpoint_json(checkpoint_to_json(simulation.checkpoint()));
  EXPECT_EQ(checkpoint.rest_coordinates.size(), 108);
  EXPECT_TRUE(same_bits(checkpoint.rest_coordinates, simulation.checkpoint().rest_coordinates));
  EXPECT_GT((checkpoint.rest_coordinates - simulation.system().model(0).initial_coordinates())
                .lpNorm<Eigen::Infinity>(),
            1e-3);
  // Without its rest shape the checkpoint would resume into a different state: refused
  checkpoint.rest_coordinates.resize(0);
  SceneSimulation resumed(scene);
  EXPECT_THAT(testing::error_message([&] { resumed.restore(checkpoint, "cp.json"); }),
              HasSubstr("cp.json: rest: rest coordinates: expected 108"));
  // The scene keys are read, written back and checked with their path
  EXPECT_NE(scene_to_json(scene).find(R"("plastic": {)"), std::string::npos);
  std::string bad = kPlasticSheetScene;
  bad.replace(bad.find(R"("yield": 0.01)"), 13, R"("yield": -1)");
  EXPECT_THAT(testing::error_message([&] { parse_scene_json(bad); }),
              HasSubstr("models[0].plastic.yield"));
  bad = kPlasticSheetScene;
  bad.replace(bad.find(R"("plastic")"), 9, R"("rest_shape": "none", "plastic")");
  EXPECT_THAT(testing::error_message([&] { parse_scene_json(bad); }),
              HasSubstr("a plastic rest shape needs \"rest_shape\": \"initial\""));
}

// Plastic rest shapes of the other model types: a pushed PDE surface, Terzopoulos sheet,
// triangular D-NURBS patch and swung D-NURBS sphere (its rest shape in profile and trajectory
// coordinates, stepped with a Newton iteration: M, D, K re-assembled at every iterate).
const char* const kPlasticScenes[] = {
    R"({"models": [{"name": "clay", "type": "pde_surface",
      "grid": {"nodes": [9, 9], "spacing": 0.125}, "material": {"damping": 5},
      "plastic": {"yield": 0.02, "rate": 3}}],
    "forces": [{"type": "point", "model": "clay", "at": [0.5, 0.5], "force": [0, 0, -50]}],
    "integrator": {"dt": 0.1, "scheme": "implicit-euler"}, "run": {"steps": 30}})",
    R"({"models": [{"name": "clay", "type": "terzopoulos_surface",
      "grid": {"nodes": [9, 9], "spacing": 0.125}, "plastic": {"yield": 0.001, "rate": 3},
      "material": {"damping_density": 2, "eta": [[0.1, 0], [0, 0.1]],
                   "xi": [[0.0001, 0.0001], [0.0001, 0.0001]]},
      "boundary": {"clamp_border": true}}],
    "forces": [{"type": "gravity", "acceleration": [0, 0, -5]}],
    "integrator": {"dt": 0.01, "scheme": "implicit-euler", "newton_iterations": 2},
    "run": {"steps": 30}})",
    R"({"models": [{"name": "clay", "type": "triangular_dnurbs_surface",
      "domain": {"shape": "rectangle", "cells": [3, 3]}, "plastic": {"yield": 0.02, "rate": 3},
      "material": {"damping_density": 3, "a10": 1, "a01": 1, "b20": 0.05, "b11": 0.05, "b02": 0.05},
      "boundary": {"clamp_border": true}}],
    "forces": [{"type": "point", "model": "clay", "at": [0.5, 0.5], "force": [0, 0, -1]}],
    "integrator": {"dt": 0.1, "scheme": "implicit-euler"}, "run": {"steps": 30}})",
    R"({"models": [{"name": "clay", "type": "swung_surface", "prototype": {"kind": "sphere"},
      "plastic": {"yield": 0.01, "rate": 3},
      "material": {"damping_density": 3, "a10": 1, "a01": 1, "b20": 0.1, "b11": 0.1, "b02": 0.1}}],
    "forces": [{"type": "point", "model": "clay", "at": [0.5, 0], "force": [-8, 0, 0]}],
    "integrator": {"dt": 0.1, "scheme": "implicit-euler", "newton_iterations": 1},
    "run": {"steps": 30}})"};

TEST(ResumedRun, EveryPlasticModelTypeKeepsItsRestShapeInTheCheckpoint) {
  for (const char* text : kPlasticScenes) {
    const Scene scene = parse_scene_json(text);
    EXPECT_EQ(resume_difference(scene, 11, 30), 0.0) << text;
    SceneSimulation simulation(scene);
    for (int i = 0; i < 11; ++i) {
      simulation.step();
    }
    const Checkpoint checkpoint =
        parse_checkpoint_json(checkpoint_to_json(simulation.checkpoint()));
    EXPECT_TRUE(same_bits(checkpoint.rest_coordinates, simulation.checkpoint().rest_coordinates));
    EXPECT_GT((checkpoint.rest_coordinates - simulation.system().model(0).initial_coordinates())
                  .lpNorm<Eigen::Infinity>(),
              1e-3)
        << text;
    // The key is written back, and read with its path
    EXPECT_NE(scene_to_json(scene).find(R"("plastic": {)"), std::string::npos);
    std::string bad = text;
    bad.replace(bad.find(R"("rate": 3)"), 9, R"("rate": 0)");
    EXPECT_THAT(testing::error_message([&] { parse_scene_json(bad); }),
                HasSubstr("models[0].plastic.rate"));
  }
}

TEST(ResumedRun, CheckpointOfAnotherSceneIsRejected) {
  const Scene scene = read_scene_file(kExamples / "snake_contour.json");
  SceneSimulation simulation(scene);
  Checkpoint checkpoint = simulation.checkpoint();
  checkpoint.scene_hash = "ffffffffffffffff";
  try {
    simulation.restore(checkpoint, "old.json");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("old.json: scene_hash: expected"));
  }
}

// A checkpoint must be one this run could have written: its step within the run, its time
// step * dt (to the rounding of the sum of step dt's)
TEST(ResumedRun, CheckpointOutsideTheRunIsRejected) {
  const Scene scene = read_scene_file(kExamples / "snake_contour.json");
  SceneSimulation simulation(scene);
  for (int i = 0; i < 5; ++i) {
    simulation.step();
  }
  const Checkpoint written = simulation.checkpoint();
  const auto refusal = [&](const Checkpoint& checkpoint) -> std::string {
    SceneSimulation fresh(scene);
    try {
      fresh.restore(checkpoint, "cp.json");
    } catch (const Error& error) {
      EXPECT_EQ(fresh.steps_done(), 0);  // nothing restored
      return error.what();
    }
    return "accepted";
  };
  EXPECT_EQ(refusal(written), "accepted");
  Checkpoint bad = written;
  bad.step = scene.step_count() + 1;
  EXPECT_THAT(refusal(bad), HasSubstr("cp.json: step: expected a step of this run (0.." +
                                      std::to_string(scene.step_count()) + ")"));
  bad = written;
  bad.time = -written.time;
  EXPECT_THAT(refusal(bad), HasSubstr("cp.json: time: expected step * dt = 5 * "));
  bad = written;
  bad.time = written.time * (1.0 + 1e-9);
  EXPECT_THAT(refusal(bad), HasSubstr("cp.json: time: expected"));
}

// The runner: stop part-way (as if killed after the last periodic checkpoint), resume from the
// checkpoint file, compare files with an uninterrupted run
TEST(ResumedRun, RunnerFilesMatchAnUninterruptedRun) {
  Scene scene = read_scene_file(kExamples / "constraints.json");
  scene.output.checkpoint_every = 25;
  scene.output.mesh_every = 0;
  scene.output.resolution = 4;
  const auto whole = fresh_directory("whole");
  const auto parts = fresh_directory("parts");
  SceneSimulation a(scene);
  SceneRunOptions options;
  options.output_directory = whole;
  const SceneRunResult full = run_scene(a, options);
  EXPECT_FALSE(full.diverged);
  EXPECT_EQ(full.steps_done, 200);

  SceneSimulation b(scene);
  options.output_directory = parts;
  options.stop_after = 90;  // "killed" at step 90: the last checkpoint is step 75
  const SceneRunResult stopped = run_scene(b, options);
  EXPECT_TRUE(stopped.stopped);
  EXPECT_EQ(read_checkpoint_file(parts / "checkpoint.json").step, 75);
  EXPECT_FALSE(std::filesystem::exists(parts / "constraints.obj"));

  SceneSimulation c(scene);
  options.stop_after = -1;
  options.resume = parts / "checkpoint.json";
  const SceneRunResult resumed = run_scene(c, options);
  EXPECT_EQ(resumed.steps_done, 200);
  const Checkpoint x = read_checkpoint_file(whole / "checkpoint.json");
  const Checkpoint y = read_checkpoint_file(parts / "checkpoint.json");
  EXPECT_EQ(y.step, 200);
  // Same bits (the 1e-12 promise with room to spare)
  EXPECT_LE((x.coordinates - y.coordinates).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_LE((x.velocities - y.velocities).lpNorm<Eigen::Infinity>(), 1e-12);
  // The log continues: rows 0..75 kept, 76..200 appended, identical to the whole run's log
  EXPECT_EQ(read_text(parts / "log.csv"), read_text(whole / "log.csv"));
  EXPECT_TRUE(std::filesystem::exists(parts / "constraints.obj"));
  // No temporary file is left behind
  for (const auto& entry : std::filesystem::directory_iterator(parts)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  }
  std::filesystem::remove_all(whole);
  std::filesystem::remove_all(parts);
}

TEST(DivergingRun, StopsAtTheLastGoodStateAndWritesIt) {
  const Scene scene = read_scene_file(kExamples / "diverging_sheet.json");
  const auto directory = fresh_directory("diverging");
  SceneSimulation simulation(scene);
  SceneRunOptions options;
  options.output_directory = directory;
  const SceneRunResult result = run_scene(simulation, options);
  EXPECT_TRUE(result.diverged);
  EXPECT_THAT(result.message, HasSubstr("diverged"));
  // Named: the energy budget, and what drove it (Newmark's gamma = 0.05 < 1/2)
  EXPECT_THAT(result.message, HasSubstr("exceeds its budget"));
  EXPECT_THAT(result.message, HasSubstr("driven by integrator.newmark_gamma = 0.05"));
  EXPECT_LT(result.steps_done, scene.step_count());
  const Checkpoint last = read_checkpoint_file(directory / "checkpoint.json");
  EXPECT_EQ(last.step, result.steps_done);
  EXPECT_TRUE(last.coordinates.allFinite());
  // The last good state is the budget's last accepted one, and its energy passed the check:
  // within the initial energy plus the forces' work, plus energy_growth times the energy moved
  const System& system = simulation.system();
  const EnergyBudget& budget = simulation.energy_budget();
  const double energy =
      system.kinetic_energy() + system.potential_energy() + system.spring_energy();
  EXPECT_EQ(energy, budget.energy());
  EXPECT_LE(energy, budget.initial_energy() + budget.work() +
                        scene.integrator.energy_growth * budget.energy_moved());
  EXPECT_LE(energy, scene.integrator.max_energy * std::max(1.0, budget.energy_moved()));
  EXPECT_TRUE(std::filesystem::exists(directory / "sheet.obj"));
  std::filesystem::remove_all(directory);
}

TEST(DivergingRun, NonFiniteStepKeepsTheLastGoodState) {
  // Two point forces of 1e308 overflow their sum to infinity at t = 0.035: the integrator
  // rejects step 4 with the state unchanged
  Scene scene = read_scene_file(kExamples / "diverging_sheet.json");
  scene.integrator = SceneIntegrator{};
  scene.integrator.dt = 0.01;
  SceneForce huge;
  ScenePointForce point;
  point.at = Eigen::Vector2d(0.5, 0.5);
  point.force.values = {Eigen::Vector3d(0, 0, 1e308)};
  huge.spec = std::make_unique<ScenePointForce>(point);
  huge.start = 0.035;
  scene.forces = {huge, huge};
  SceneSimulation simulation(scene);
  for (int i = 0; i < 3; ++i) {
    simulation.step();
  }
  const Checkpoint good = simulation.checkpoint();
  try {
    simulation.step();
    FAIL() << "no divergence";
  } catch (const SimulationDiverged& error) {
    EXPECT_THAT(error.what(), HasSubstr("step 4 (t = 0.04) diverged"));
    EXPECT_THAT(error.what(), HasSubstr("non-finite"));
  }
  EXPECT_EQ(simulation.steps_done(), 3);
  EXPECT_EQ(simulation.system().coordinates(), good.coordinates);
  EXPECT_EQ(simulation.system().velocities(), good.velocities);
  EXPECT_EQ(simulation.system().time(), good.time);
}

TEST(CsvLog, ContinuesFromAnEarlierLogUpToAStep) {
  CsvLog log({"time", "energy"});
  log.add_row(0, {0.0, 1.0});
  log.add_row(5, {0.5, 1.0 / 3.0});
  log.add_row(10, {1.0, 2.0});
  const std::string text = log.to_string();
  EXPECT_THAT(text, HasSubstr("step,time,energy\n0,0,1\n5,0.5,0.33333333333333331\n"));
  CsvLog continued({"time", "energy"});
  ASSERT_TRUE(continued.continue_from(text, 5));
  EXPECT_EQ(continued.row_count(), 2);
  CsvLog other({"time"});
  EXPECT_FALSE(other.continue_from(text, 5));
  EXPECT_THROW(log.add_row(11, {1.0}), Error);
}

}  // namespace
}  // namespace dnurbs
