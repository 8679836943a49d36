// Tests of io/models/deformation_field_scene.h, the scene type "deformation_field": a keyed
// parameter equals its schedule at every step, a dynamic one settles where a spring balances its
// stiffness, the keys round-trip, the face preset reads its geometry image, the model's meshes are
// adaptive to "max_error", and bad values fail naming their JSON path.

#include "dnurbs/io/models/deformation_field_scene.h"

#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/model_tessellation.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"
#include "dnurbs/surface/adaptive_tessellation.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

// A unit square lifted by a bump (parameter "lift", dynamic, stiffness 4) and tilted by a uniform
// field (parameter "tilt", keyed); a point force of 2 along z at the bump's centre
constexpr const char* kBumpScene = R"({"models": [{"name": "sheet", "type": "deformation_field",
  "stages": [
    {"type": "constant", "field": {"type": "plane"}},
    {"type": "add_vector", "field": {"type": "gaussian", "vector": [0, 0, 1],
                                     "centre": [0.5, 0.5], "radius": 0.2}, "parameter": "lift"},
    {"type": "add_vector", "field": {"type": "uniform", "vector": [0, 0, 0.5]},
     "parameter": "tilt"}],
  "parameters": [{"name": "lift", "stiffness": 4},
                 {"name": "tilt", "keyed": {"times": [0, 0.5, 1], "values": [0, 1, -0.5]}}],
  "material": {"mass_density": 1, "damping_density": 3},
  "quadrature": {"cells": [4, 4], "points": 4},
  "max_error": 0.002}],
  "forces": [{"type": "point", "model": 0, "at": [0.5, 0.5], "force": [0, 0, 2]}],
  "integrator": {"scheme": "implicit-euler", "dt": 0.05},
  "run": {"steps": 200}})";

TEST(DeformationFieldScene, KeyedParameterFollowsItsScheduleAtEveryStep) {
  const Scene scene = parse_scene_json(kBumpScene);
  const auto& spec = dynamic_cast<const SceneDeformationField&>(*scene.models[0].spec);
  SceneSimulation simulation(scene);
  EXPECT_EQ(simulation.system().coordinates()(1), 0.0);
  for (int n = 1; n <= 200; ++n) {
    simulation.step();
    const double t = simulation.system().time();
    // The scene sets the keyed coordinate to the schedule at the step's time: equal bits
    ASSERT_EQ(simulation.system().coordinates()(1), spec.parameters[1].schedule.at(t)) << t;
  }
  EXPECT_EQ(simulation.system().coordinates()(1), -0.5);
  // The dynamic parameter settles at L^T f / k = (2 exp(0)) / 4 = 0.5 (the bump is 1 at its
  // centre); implicit Euler with damping 3 over t = 10 leaves a transient of ~exp(-6)
  EXPECT_NEAR(simulation.system().coordinates()(0), 0.5, 1e-2);
}

TEST(DeformationFieldScene, GravityAndAPointConstraintActOnTheParameters) {
  // The bump's centre held at z = 0.3 by a point_target constraint against gravity and the
  // stiffness: x_z(centre) = q_lift (the bump is 1 there), so q_lift -> 0.3; the constraint's x and
  // y rows have zero Jacobian and zero value (redundant, solved by least squares)
  const std::string text = R"({"models": [{"name": "sheet", "type": "deformation_field",
    "stages": [{"type": "constant", "field": {"type": "plane"}},
               {"type": "add_vector", "field": {"type": "gaussian", "vector": [0, 0, 1],
                "centre": [0.5, 0.5], "radius": 0.2}, "parameter": "lift"}],
    "parameters": [{"name": "lift", "stiffness": 4}],
    "material": {"mass_density": 1, "damping_density": 3}}],
    "forces": [{"type": "gravity", "acceleration": [0, 0, -9.81]}],
    "constraints": [{"type": "point_target", "model": 0, "at": [0.5, 0.5],
                     "target": [0.5, 0.5, 0.3]}],
    "integrator": {"scheme": "implicit-euler", "dt": 0.05}, "run": {"steps": 200}})";
  SceneSimulation simulation(parse_scene_json(text));
  for (int n = 0; n < 200; ++n) {
    simulation.step();
  }
  // Baumgarte's critically damped drift (alpha = 20) has decayed over t = 10 to rounding
  EXPECT_NEAR(simulation.system().coordinates()(0), 0.3, 1e-12);
}

TEST(DeformationFieldScene, KeysRoundTrip) {
  const Scene scene = parse_scene_json(kBumpScene);
  const std::string written = scene_to_json(scene);
  EXPECT_THAT(written, HasSubstr("\"type\": \"gaussian\""));
  EXPECT_THAT(written, HasSubstr("\"keyed\""));
  EXPECT_TRUE(parse_scene_json(written) == scene);
}

TEST(DeformationFieldScene, MeshIsAdaptiveToMaxError) {
  Scene scene = parse_scene_json(kBumpScene);
  SceneSimulation simulation(scene);
  const Eigen::Vector2d q(0.8, 0.0);
  simulation.set_coordinates(q);
  const TriangleMesh mesh = simulation.mesh(0, 4);
  const Model& model = simulation.system().model(0);
  const ParametricSurface surface = model.parametric_surface(q);
  RestrictedMesh restricted(surface, 4, 4);
  restricted.refine(surface_error_criterion(surface, 2e-3), 16);
  EXPECT_EQ(mesh.vertex_count(), restricted.to_triangle_mesh("sheet").vertex_count());
  EXPECT_LE(mesh_surface_error(restricted, kDefaultErrorSampleOrder).max, 2e-3);
  const UniformTessellationChoice uniform = coarsest_uniform_tessellation(surface, 4, 4, 2e-3);
  EXPECT_LT(mesh.vertex_count(), uniform.vertices);
}

TEST(DeformationFieldScene, FacePresetReadsItsGeometryImage) {
  const std::string file =
      (std::filesystem::path(DNURBS_TEST_DATA_DIR) / "../../examples/faces/face_ada.gim").string();
  const std::string text = R"({"models": [{"name": "face", "type": "deformation_field",
    "face": ")" + file + R"(",
    "parameters": [{"name": "jaw_open", "stiffness": 1},
                   {"name": "zygomatic_left", "keyed": 0.5}]}], "run": {"steps": 1}})";
  const Scene scene = parse_scene_json(text);
  const auto model = scene.models[0].spec->build();
  ASSERT_EQ(model->coordinate_count(), kFaceParameterCount);
  // Every face parameter but jaw_open is fixed; zygomatic_left starts at its keyed 0.5
  EXPECT_EQ(model->fixed_coordinates(), (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(model->initial_coordinates()(2), 0.5);
  const DeformableFace face = DeformableFace::read(file);
  const Eigen::VectorXd q = model->initial_coordinates();
  EXPECT_LT((model->position(q, {0.4, 0.3}) - face.point(q, 0.4, 0.3)).norm(), 1e-12);
}

std::string failure(const std::string& text) {
  try {
    parse_scene_json(text, "bad.json");
  } catch (const Error& error) {
    return error.what();
  }
  return "(accepted)";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST(DeformationFieldScene, BadValuesFailNamingTheirPath) {
  const std::string scene = kBumpScene;
  EXPECT_THAT(failure(replaced(scene, "\"stiffness\": 4", "\"stiffness\": -4")),
              HasSubstr("models[0].parameters[0].stiffness"));
  EXPECT_THAT(failure(replaced(scene, "\"parameter\": \"tilt\"", "\"parameter\": \"tlit\"")),
              HasSubstr("models[0].stages[2].parameter: no parameter \"tlit\""));
  EXPECT_THAT(failure(replaced(scene, "\"radius\": 0.2", "\"radius\": 0")),
              HasSubstr("models[0].stages[1].field.radius"));
  EXPECT_THAT(failure(replaced(scene, "\"type\": \"uniform\"", "\"type\": \"swirl\"")),
              HasSubstr("models[0].stages[2].field.type"));
  EXPECT_THAT(failure(replaced(scene, "{\"name\": \"lift\", \"stiffness\": 4}",
                               "{\"name\": \"lift\", \"keyed\": 1, \"initial\": 2}")),
              HasSubstr("models[0].parameters[0].initial: a keyed parameter"));
  EXPECT_THAT(failure(replaced(scene, "\"points\": 4", "\"points\": 40")),
              HasSubstr("models[0].quadrature.points"));
  EXPECT_THAT(failure(replaced(scene, "\"stages\"", "\"face\": \"x.gim\", \"stages\"")),
              HasSubstr("models[0]: expected exactly one of \"face\""));
  EXPECT_THAT(failure(replaced(scene, "{\"name\": \"lift\", \"stiffness\": 4},",
                               "{\"name\": \"lift\", \"stiffness\": 4}, {\"name\": \"spare\"},")),
              HasSubstr("models[0].parameters[1].name: parameter \"spare\" moves no add_vector"));
}

}  // namespace
}  // namespace dnurbs
