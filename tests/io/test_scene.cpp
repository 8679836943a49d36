// Scene files: every key round-trips, model references resolve, schedules interpolate, every
// model type builds and steps, and every malformed scene of the corpus names its JSON path.

#include "dnurbs/io/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "dnurbs/core/error.h"
#include "dnurbs/io/models/dnurbs_scene.h"
#include "dnurbs/io/scene_constraints.h"
#include "dnurbs/io/scene_fit.h"
#include "dnurbs/io/scene_forces.h"
#include "dnurbs/io/scene_simulation.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;
using Json = nlohmann::json;

const std::filesystem::path kData = DNURBS_TEST_DATA_DIR;

// Uses every key of the format, each with a value other than its default
const char* const kFullScene = R"json({
  "description": "every key",
  "models": [
    {"name": "curve", "type": "dnurbs_curve", "shape_file": "circle.json",
     "material": {"mass_density": 2, "damping_density": 0.5, "tension": 3, "rigidity": 0.25},
     "weights": "free", "quadrature_points": 4, "minimum_weight": 0.01,
     "boundary": {"fixed_points": [0], "local_sculpting_margin": 1},
     "resolution_scale": [2, 1]},
    {"name": "sheet", "type": "dnurbs_surface",
     "shape": {"type": "nurbs_surface", "degree_u": 2, "degree_v": 2,
               "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 0, 1, 1, 1],
               "control_points": [[[-1, -1, 0], [-1, 0, 0], [-1, 1, 0]],
                                  [[0, -1, 0], [0, 0, 0.5], [0, 1, 0]],
                                  [[1, -1, 0], [1, 0, 0], [1, 1, 0]]],
               "weights": [[1, 1, 1], [1, 2, 1], [1, 1, 1]]},
     "material": {"mass_density": 1.5, "damping_density": 0.25, "a10": 1, "a01": 2, "b20": 0.1,
                  "b11": 0.2, "b02": 0.3},
     "weights": "fixed", "quadrature_points": 3, "minimum_weight": 0.002,
     "boundary": {"clamp_border": true, "fixed_points": [4]}},
    {"name": "blob", "type": "superquadric",
     "shape": {"a": 1.5, "a1": 0.5, "a2": 0.6, "a3": 0.7, "e1": 0.9, "e2": 1.1, "t1": 0.1,
               "t2": 0.2, "b1": 0.01, "b2": 0.02, "b3": 0.03, "tau": 0.04, "sx": 0.05, "sy": 0.06},
     "centre": [3, 0, 0], "orientation": [0, 1, 0, 0], "parts": "global", "mesh_cells": [4, 8],
     "quadrature_points": 2, "regularization": 0.002,
     "material": {"mass_density": 2, "damping_alpha": 0.1, "damping_beta": 0.01,
                  "shape_stiffness": 20, "local_stiffness": [2, 3, 0.5]}},
    {"name": "cloth", "type": "terzopoulos_surface",
     "grid": {"nodes": [4, 5], "spacing": 0.25, "origin": [0, 0, 2], "axis_u": [0, 1, 0],
              "axis_v": [1, 0, 0]},
     "normal": "christoffel", "delta": 0.25,
     "material": {"mass_density": 2, "damping_density": 0.5, "eta": [[1, 0.5], [0.5, 1]],
                  "xi": [[0.1, 0], [0, 0.1]]},
     "boundary": {"clamp_border": true}},
    {"name": "plate", "type": "pde_surface",
     "grid": {"nodes": [9, 9], "spacing": 0.125, "origin": [0, 0, -2], "axis_u": [1, 0, 0],
              "axis_v": [0, 1, 0]},
     "material": {"b": 2, "c": 3, "d": 4, "density": 2, "damping": 1, "su0": 0.1, "su1": 0.2,
                  "sv0": 0.3, "sv1": 0.4},
     "regions": [{"centre": [0.5, 0.5, -2], "radius": 0.3}]},
    {"name": "snake", "type": "snake",
     "nodes": [[0, 0, 5], [1, 0, 5], [1, 1, 5], [0, 1, 5], [-0.5, 0.5, 5]], "closed": true,
     "material": {"mass_density": 2, "damping_density": 1, "tension": 0.5, "rigidity": 0.05},
     "boundary": {"fixed_points": [0]}, "resolution_scale": [0.5, 1]},
    {"name": "scan", "type": "dnurbs_surface",
     "fit": {"points": "fit_surface_points.xyz", "degree": 2, "spans": 3, "smoothness": 1e-6,
             "iterations": 5},
     "material": {"b20": 1, "b11": 1, "b02": 1}}
  ],
  "forces": [
    {"type": "point", "model": "sheet", "at": [0.5, 0.5],
     "force": {"times": [0, 1], "values": [[0, 0, 0], [0, 0, 1]]}, "start": 0.1, "end": 2},
    {"type": "spring", "model": 0, "at": [0.25], "stiffness": 2, "target": [1, 1, 1]},
    {"type": "control_point", "model": "snake", "control_points": [1, 2], "force": [0, 0, 1]},
    {"type": "gravity", "model": "blob", "acceleration": [0, 0, -1]},
    {"type": "gravity", "acceleration": [0, -0.5, 0], "start": 1},
    {"type": "pressure", "model": "sheet", "pressure": {"times": [0, 1, 3], "values": [0, 1, 0.5]}},
    {"type": "pressure", "model": "cloth", "pressure": 0.25, "end": 5}
  ],
  "constraints": [
    {"type": "point_target", "model": "sheet", "at": [0.5, 0.5],
     "target": {"times": [0, 1], "values": [[0, 0, 0.5], [0, 0, 1]]}, "alpha": 10, "beta": 5},
    {"type": "point_to_point", "model_a": "sheet", "at_a": [0.2, 0.2], "model_b": "cloth",
     "at_b": [0.25, 0.25], "alpha": 5},
    {"type": "hinge", "model_a": "blob", "axis_a": [[0, 0], [0.5, 0]], "model_b": "plate",
     "axis_b": [[0.5, 0.5], [0.5, 0.625]], "alpha": 4, "beta": 4},
    {"type": "control_point", "model": "sheet", "control_point": 4, "target": [0, 0, 1], "alpha": 3},
    {"type": "surface_normal", "model": "sheet", "at": [0.3, 0.3], "direction": [0, 0, 1],
     "alpha": 2},
    {"type": "curve_on_surface", "curve_model": "curve", "surface_model": "sheet", "samples": 3,
     "alpha": 1, "beta": 2}
  ],
  "integrator": {"scheme": "implicit-euler", "dt": 0.005, "newton_iterations": 2,
                 "newton_tolerance": 1e-8, "automatic_newton": false,
                 "keep_factor_across_steps": false, "newmark_beta": 0.3,
                 "newmark_gamma": 0.6,
                 "max_energy": 1e9},
  "run": {"steps": 7},
  "probes": [{"name": "tip", "model": "curve", "at": [0.5]},
             {"name": "centre", "model": "sheet", "at": [0.5, 0.5]}],
  "output": {"mesh_every": 3, "format": "ply", "resolution": 12, "final_mesh": false,
             "preview": false, "log_every": 2, "checkpoint_every": 4, "name": "full",
             "shape_files": true}
})json";

// Every object key path ("models[].material.a10") of a document
void key_paths(const Json& value, const std::string& path, std::set<std::string>& paths) {
  if (value.is_object()) {
    for (const auto& item : value.items()) {
      const std::string key = path.empty() ? item.key() : path + "." + item.key();
      paths.insert(key);
      key_paths(item.value(), key, paths);
    }
  } else if (value.is_array()) {
    for (const auto& element : value) {
      key_paths(element, path + "[]", paths);
    }
  }
}

// The spec of a scene model, force or constraint as its type (the test knows the type).
template <typename Spec, typename Base>
Spec& as(const ClonePtr<Base>& spec) {
  return dynamic_cast<Spec&>(*spec);
}

Scene full_scene() {
  Scene scene = parse_scene_json(kFullScene, "full.json", kData);
  fit_initial_shapes(scene);
  return scene;
}

TEST(SceneFile, EveryKeyRoundTripsThroughTheWriter) {
  const Scene scene = full_scene();
  const std::string written = scene_to_json(scene);
  const Scene again = parse_scene_json(written, "written.json", kData);
  EXPECT_TRUE(again == scene) << written;
  // Writing is stable
  EXPECT_EQ(scene_to_json(again), written);
  // No key of the input is dropped: every key path reappears in the written document
  std::set<std::string> input;
  std::set<std::string> output;
  key_paths(Json::parse(kFullScene), "", input);
  key_paths(Json::parse(written), "", output);
  for (const auto& path : input) {
    EXPECT_TRUE(output.count(path) == 1) << path << " is not written";
  }
}

TEST(SceneFile, ChangingAnyValueMakesScenesDifferent) {
  const Scene scene = full_scene();
  Scene changed = scene;
  changed.integrator.newmark_gamma = 0.61;
  EXPECT_FALSE(changed == scene);
  changed = scene;
  changed.integrator.automatic_newton = !scene.integrator.automatic_newton;
  EXPECT_FALSE(changed == scene);
  EXPECT_NE(scene_state_hash(changed), scene_state_hash(scene));
  changed = scene;
  changed.integrator.keep_factor_across_steps = !scene.integrator.keep_factor_across_steps;
  EXPECT_FALSE(changed == scene);
  EXPECT_NE(scene_state_hash(changed), scene_state_hash(scene));
  changed = scene;
  as<SceneDNurbsSurface>(changed.models[1].spec).material.b11 = 0.21;
  EXPECT_FALSE(changed == scene);
  EXPECT_NE(scene_state_hash(changed), scene_state_hash(scene));
  // Output settings do not change the state hash (a run may be resumed with other outputs)
  changed = scene;
  changed.output.resolution = 5;
  EXPECT_FALSE(changed == scene);
  EXPECT_EQ(scene_state_hash(changed), scene_state_hash(scene));
}

TEST(SceneFile, ValuesAndReferencesAreParsedAsWritten) {
  const Scene scene = full_scene();
  ASSERT_EQ(scene.models.size(), 7u);
  EXPECT_EQ(scene_model_type(scene.models[0]), "dnurbs_curve");
  EXPECT_EQ(as<SceneDNurbsCurve>(scene.models[0].spec).shape_file, "circle.json");
  EXPECT_TRUE(as<SceneDNurbsCurve>(scene.models[0].spec).settings.weight_mode == WeightMode::kFree);
  EXPECT_EQ(scene_model_type(scene.models[5]), "snake");
  EXPECT_EQ(as<SceneDNurbsSurface>(scene.models[6].spec).fit->points, "fit_surface_points.xyz");
  EXPECT_EQ(as<SceneDNurbsSurface>(scene.models[6].spec).surface->degree_u(), 2);
  // Names resolve to indices
  EXPECT_EQ(as<ScenePointForce>(scene.forces[0].spec).model, 1);
  EXPECT_EQ(as<SceneSpringForce>(scene.forces[1].spec).model, 0);
  EXPECT_EQ(as<SceneGravity>(scene.forces[4].spec).model, -1);
  EXPECT_EQ(as<SceneHingeConstraint>(scene.constraints[2].spec).model_b, 4);
  EXPECT_EQ(scene.constraints[1].beta, -1.0);  // absent: beta = alpha
  EXPECT_EQ(scene.forces[1].end, std::numeric_limits<double>::infinity());
  EXPECT_EQ(scene.step_count(), 7);
  EXPECT_EQ(scene.output.formats, std::vector<std::string>{"ply"});
}

TEST(SceneFile, DurationGivesTheStepCount) {
  const std::string text = R"({"models": [{"type": "snake", "nodes": [[0,0,0],[1,0,0],[2,0,0]]}],
                               "integrator": {"dt": 0.01}, "run": {"duration": 0.3}})";
  const Scene scene = parse_scene_json(text);
  // 0.3 / 0.01 = 29.999999999999996 in doubles: the count rounds to 30, not 31
  EXPECT_EQ(scene.step_count(), 30);
  EXPECT_TRUE(parse_scene_json(scene_to_json(scene)) == scene);
  EXPECT_EQ(scene.models[0].name, "model0");
}

TEST(SceneFile, FramesOfSubStepsSetTheStepLogAndMeshRate) {
  // Romero 2005, section 4.3: each frame of 1/30 is solved in 4 steps of 1/120
  const std::string text = R"({"models": [{"type": "snake", "nodes": [[0,0,0],[1,0,0],[2,0,0]]}],
                               "run": {"frames": 3, "frame_rate": 30, "substeps": 4}})";
  const Scene scene = parse_scene_json(text);
  EXPECT_EQ(scene.step_count(), 12);
  EXPECT_EQ(scene.integrator.dt, 1.0 / 120.0);
  EXPECT_EQ(scene.output.log_every, 4);
  EXPECT_EQ(scene.output.mesh_every, 4);
  EXPECT_TRUE(parse_scene_json(scene_to_json(scene)) == scene);
  SceneSimulation simulation(scene);
  for (int frame = 1; frame <= 3; ++frame) {
    for (int s = 0; s < 4; ++s) {
      simulation.step();
    }
    EXPECT_EQ(simulation.steps_done(), 4 * frame);
    // frame / 30 after 4 frame additions of 1/120 each: round-off of a few ulps
    EXPECT_NEAR(simulation.system().time(), frame / 30.0, 1e-15);
  }
  const auto error = [](const std::string& run, const std::string& integrator = "") {
    try {
      parse_scene_json(R"({"models": [{"type": "snake", "nodes": [[0,0,0],[1,0,0],[2,0,0]]}],)" +
                       integrator + R"("run": )" + run + "}");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_THAT(error(R"({"frames": 3, "substeps": 4})"), HasSubstr("run.frame_rate: missing key"));
  EXPECT_THAT(error(R"({"frames": 3, "frame_rate": 0})"), HasSubstr("run.frame_rate"));
  EXPECT_THAT(error(R"({"frames": 3, "frame_rate": 30, "substeps": 0})"),
              HasSubstr("run.substeps"));
  EXPECT_THAT(error(R"({"steps": 3, "substeps": 4})"), HasSubstr("run.substeps"));
  EXPECT_THAT(error(R"({"steps": 3, "frames": 4, "frame_rate": 30})"),
              HasSubstr("run.frames: expected \"frames\" without"));
  EXPECT_THAT(error(R"({"frames": 3, "frame_rate": 30})", R"("integrator": {"dt": 0.1},)"),
              HasSubstr("integrator.dt"));
}

TEST(SceneFile, SchedulesHoldConstantsAndInterpolateKeyframes) {
  VectorSchedule constant;
  constant.values = {Eigen::Vector3d(1, 2, 3)};
  EXPECT_EQ(constant.at(-5.0), Eigen::Vector3d(1, 2, 3));
  VectorSchedule keyframes;
  keyframes.times = {0.0, 1.0, 3.0};
  keyframes.values = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 2, 0)};
  // At a keyframe the interpolant (monotone by default) passes through its value (1e-14)
  EXPECT_LT((keyframes.at(1.0) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-14);
  // Before the first and after the last keyframe the value rests there
  EXPECT_EQ(keyframes.at(-1.0), Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(keyframes.at(10.0), Eigen::Vector3d(1, 2, 0));
  ScalarSchedule pressure;
  pressure.times = {0.0, 2.0};
  pressure.values = {0.0, 4.0};
  // Two keyframes: every interpolation is the straight line (rounding: 1e-14)
  EXPECT_NEAR(pressure.at(0.5), 1.0, 1e-14);
  pressure.interpolation = Interpolation::kCubic;
  EXPECT_NEAR(pressure.at(0.5), 1.0, 1e-14);
  // swung_clay's push, keys -3, -3, 0 at 0, 1, 1.05: the default (monotone) holds -3 on [0, 1];
  // the natural cubic spline reaches -3 - 400 / (21 sqrt 3) = -14.0 at t = 1 / sqrt 3
  ScalarSchedule push;
  push.times = {0.0, 1.0, 1.05};
  push.values = {-3.0, -3.0, 0.0};
  EXPECT_EQ(push.interpolation, Interpolation::kMonotone);
  EXPECT_EQ(push.at(1.0 / std::sqrt(3.0)), -3.0);
  push.interpolation = Interpolation::kCubic;
  EXPECT_NEAR(push.at(1.0 / std::sqrt(3.0)), -3.0 - 400.0 / (21.0 * std::sqrt(3.0)), 1e-12);
  push.interpolation = Interpolation::kLinear;
  EXPECT_NEAR(push.at(1.025), -1.5, 1e-12);
}

TEST(SceneSimulation, EveryModelForceAndConstraintTypeBuildsAndSteps) {
  SceneSimulation simulation(full_scene());
  const System& system = simulation.system();
  EXPECT_EQ(system.model_count(), 7);
  // sheet (3 x 3, border clamped) + control point 4 fixed: all 27 coordinates fixed;
  // curve: control point 0 fixed (3 of its 4 coordinates) plus the weight gauge
  EXPECT_GT(system.fixed_coordinates().size(), 27u);
  // curve_on_surface with 3 samples gives 3 ball joints: 5 + 3 - 1 constraints
  EXPECT_EQ(simulation.constraints().constraint_count(), 8);
  for (int i = 0; i < 2; ++i) {
    simulation.step();
  }
  EXPECT_EQ(simulation.steps_done(), 2);
  EXPECT_TRUE(system.coordinates().allFinite());
  const std::vector<TriangleMesh> meshes = simulation.meshes(6);
  ASSERT_EQ(meshes.size(), 7u);
  EXPECT_EQ(meshes[1].name, "sheet");
  EXPECT_EQ(meshes[1].triangle_count(), 2 * 6 * 6);
  // superquadric: 6 x 6 cells, the two pole rows fans of 6 triangles around one vertex each (the
  // one tessellation path, dynamics/core/model_tessellation.h; the scene's own mesh used to
  // duplicate the poles and keep 12 zero-area triangles: 2 * 6 * 6)
  EXPECT_EQ(meshes[2].triangle_count(), 2 * 6 * 4 + 2 * 6);
  EXPECT_EQ(meshes[3].vertex_count(), 4 * 5);  // terzopoulos: one vertex per node
  const SceneSample sample = simulation.sample();
  EXPECT_EQ(sample.probes.size(), 2u);
  EXPECT_EQ(sample.violations.size(), 8);
  EXPECT_EQ(simulation.log_columns().size(), simulation.log_row(sample).size());
  EXPECT_EQ(simulation.cost().size(), 7u);
  EXPECT_TRUE(simulation.shape(0).has_value());
  EXPECT_FALSE(simulation.shape(2).has_value());
}

// The corpus: tests/data/bad_scenes/*.json, expected_messages.tsv lists the substrings each
// file's message must contain
TEST(SceneFile, EveryMalformedSceneOfTheCorpusNamesItsJsonPath) {
  const std::filesystem::path directory = kData / "bad_scenes";
  std::ifstream manifest(directory / "expected_messages.tsv");
  ASSERT_TRUE(manifest) << "missing expected_messages.tsv";
  std::set<std::string> listed;
  std::string line;
  while (std::getline(manifest, line)) {
    if (line.empty() || line[0] == '#') {
      continue;
    }
    std::vector<std::string> fields;
    std::istringstream parts(line);
    std::string field;
    while (std::getline(parts, field, '\t')) {
      fields.push_back(field);
    }
    ASSERT_GE(fields.size(), 2u) << line;
    listed.insert(fields[0]);
    const std::filesystem::path file = directory / fields[0];
    std::string message;
    try {
      SceneSimulation simulation(read_scene_file(file));
      ADD_FAILURE() << fields[0] << " was accepted";
      continue;
    } catch (const Error& error) {
      message = error.what();
    }
    EXPECT_THAT(message, ::testing::StartsWith(file.string() + ": ")) << fields[0];
    for (size_t k = 1; k < fields.size(); ++k) {
      EXPECT_THAT(message, HasSubstr(fields[k])) << fields[0];
    }
    // One line without control characters, whatever the file holds (hostile names included)
    EXPECT_TRUE(std::none_of(message.begin(), message.end(),
                             [](char c) {
                               const auto u = static_cast<unsigned char>(c);
                               return u < 0x20 || u == 0x7f;
                             }))
        << fields[0] << ": " << message;
  }
  EXPECT_GE(listed.size(), 30u);
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    if (entry.path().extension() == ".json") {
      EXPECT_EQ(listed.count(entry.path().filename().string()), 1u)
          << entry.path() << " has no expected message";
    }
  }
}

TEST(SceneFile, EveryKeyIsDocumented) {
  std::ifstream in(kData / ".." / ".." / "docs" / "scene-format.md");
  ASSERT_TRUE(in) << "docs/scene-format.md is missing";
  std::ostringstream text;
  text << in.rdbuf();
  const std::string docs = text.str();
  std::set<std::string> paths;
  key_paths(Json::parse(scene_to_json(full_scene())), "", paths);
  for (const auto& path : paths) {
    // Keys inside a "shape" are the shape format of dnurbs eval (or the superquadric's q_s,
    // listed in one table cell)
    if (path.starts_with("models[].shape.")) {
      continue;
    }
    // In a table (`key`, `prefix.key`) or in an example ("key": ...)
    const std::string key = path.substr(path.rfind('.') + 1);
    const bool documented = docs.find("`" + key + "`") != std::string::npos ||
                            docs.find("." + key + "`") != std::string::npos ||
                            docs.find("\"" + key + "\":") != std::string::npos;
    EXPECT_TRUE(documented) << path << " is not in docs/scene-format.md";
  }
}

TEST(SceneFile, UnreadableFileIsNamed) {
  try {
    read_scene_file(kData / "no_such_scene.json");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("no_such_scene.json: the scene file does not exist"));
  }
}

// ----------------------------------------------------------------------------------------------
// The scene's "design" section (io/scene.h SceneDesign): parsed values, parse/write/parse
// round trip, absent unless given, and every written key documented in docs/scene-format.md.

constexpr const char* kModels = R"("models": [{"name": "rod", "type": "dnurbs_curve",
  "shape": {"type": "nurbs_curve", "degree": 1, "knots": [0, 0, 1, 1],
            "control_points": [[0, 0, 0], [1, 0, 0]]}}], "run": {"steps": 1})";

TEST(SceneDesign, SectionParsesAndRoundTrips) {
  const Scene scene =
      parse_scene_json(std::string("{") + kModels +
                       R"(, "design": {"algorithm": "auglag_lbfgs", "variable_tolerance": 1e-10,
          "energy_tolerance": 1e-15, "constraint_tolerance": 1e-9, "max_evaluations": 77,
          "max_seconds": 2.5}})");
  ASSERT_TRUE(scene.design.has_value());
  EXPECT_EQ(scene.design->algorithm, "auglag_lbfgs");
  EXPECT_EQ(scene.design->variable_tolerance, 1e-10);
  EXPECT_EQ(scene.design->energy_tolerance, 1e-15);
  EXPECT_EQ(scene.design->constraint_tolerance, 1e-9);
  EXPECT_EQ(scene.design->max_evaluations, 77);
  EXPECT_EQ(scene.design->max_seconds, 2.5);
  const Scene again = parse_scene_json(scene_to_json(scene));
  EXPECT_TRUE(again == scene);
  ASSERT_TRUE(again.design.has_value());
  EXPECT_EQ(*again.design, *scene.design);

  // Defaults, and no section unless given (so existing scenes write and hash as before).
  const Scene defaults = parse_scene_json(std::string("{") + kModels + R"(, "design": {}})");
  EXPECT_EQ(*defaults.design, SceneDesign{});
  const Scene plain = parse_scene_json(std::string("{") + kModels + "}");
  EXPECT_FALSE(plain.design.has_value());
  EXPECT_FALSE(Json::parse(scene_to_json(plain)).contains("design"));
  EXPECT_FALSE(plain == defaults);
}

TEST(SceneDesign, EveryWrittenKeyIsDocumented) {
  const Scene scene = parse_scene_json(std::string("{") + kModels + R"(, "design": {}})");
  std::ifstream in(std::filesystem::path(DNURBS_TEST_DATA_DIR) / ".." / ".." / "docs" /
                   "scene-format.md");
  ASSERT_TRUE(in) << "docs/scene-format.md is missing";
  std::ostringstream text;
  text << in.rdbuf();
  const std::string docs = text.str();
  const Json written = Json::parse(scene_to_json(scene));
  EXPECT_NE(docs.find("| `design` |"), std::string::npos);
  ASSERT_EQ(written.at("design").size(), 6u);
  for (const auto& item : written.at("design").items()) {
    EXPECT_NE(docs.find("`design." + item.key() + "`"), std::string::npos)
        << "design." << item.key() << " is not in docs/scene-format.md";
  }
}

}  // namespace
}  // namespace dnurbs
