// Scene type "triangular_dnurbs_surface": every key parses, writes back and is documented; the
// generated domains, inline shapes and shape files build the model; boundary conditions, local
// sculpting, forces on the domain, meshes (uniform and adaptive) and the cost report work.

#include "dnurbs/io/models/triangular_dnurbs_surface_scene.h"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/triangular/triangular_local_sculpting.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"
#include "dnurbs/io/triangular_shape_file.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kData = DNURBS_TEST_DATA_DIR;

// Every key of the type, each with a value other than its default
const char* const kScene = R"json({
  "models": [
    {"name": "patch", "type": "triangular_dnurbs_surface",
     "domain": {"shape": "square_with_hole", "cells": 1, "degree": 2, "knot_radius": 0.25},
     "weights": "free", "minimum_weight": 0.01, "weight_inertia": 0.001, "quadrature_degree": 5,
     "quadrature_subdivisions": 2,
     "tessellation": {"subdivisions": 3, "max_error": 0.01, "max_level": 9},
     "material": {"mass_density": 2, "damping_density": 1.5, "a10": 1, "a01": 0.5, "b20": 0.1,
                  "b11": 0.2, "b02": 0.3},
     "boundary": {"fixed_points": [0, 7]}},
    {"name": "plate", "type": "triangular_dnurbs_surface",
     "domain": {"shape": "rectangle", "cells": [3, 2], "lo": [-1, 0], "hi": [1, 1]},
     "material": {"b20": 1, "b11": 1, "b02": 1},
     "boundary": {"clamp_border": true}},
    {"name": "tile", "type": "triangular_dnurbs_surface",
     "shape": {"type": "triangular_nurbs", "degree": 1, "vertices": [[0, 0], [1, 0], [0, 1]],
               "triangles": [[0, 1, 2]], "control_points": [[0, 0, 1], [1, 0, 1], [0, 1, 1]]},
     "boundary": {"local_sculpting_margin": 1}}
  ],
  "forces": [
    {"type": "spring", "model": "patch", "at": [2.5, 0.5], "stiffness": 5, "target": [2.5, 0.5, 1]},
    {"type": "pressure", "model": "plate", "pressure": 0.5},
    {"type": "point", "model": "tile", "at": [0.2, 0.2], "force": [0, 0, 1]}
  ],
  "integrator": {"dt": 0.01},
  "run": {"steps": 3},
  "probes": [{"name": "pulled", "model": "patch", "at": [2.5, 0.5]}]
})json";

template <typename Spec>
const Spec& as(const ClonePtr<SceneModelSpec>& spec) {
  return dynamic_cast<const Spec&>(*spec);
}

void key_paths(const nlohmann::json& value, const std::string& path, std::set<std::string>& out) {
  if (value.is_object()) {
    for (const auto& item : value.items()) {
      const std::string child = path.empty() ? item.key() : path + "." + item.key();
      out.insert(child);
      key_paths(item.value(), child, out);
    }
  } else if (value.is_array()) {
    for (const auto& item : value) {
      key_paths(item, path + "[]", out);
    }
  }
}

TEST(TriangularDNurbsSurfaceScene, EveryKeyIsReadWrittenBackAndDocumented) {
  const Scene scene = parse_scene_json(kScene, "tri.json", kData);
  ASSERT_EQ(scene.models.size(), 3u);
  const auto& patch = as<SceneTriangularDNurbsSurface>(scene.models[0].spec);
  ASSERT_TRUE(patch.domain.has_value());
  EXPECT_EQ(patch.domain->shape, "square_with_hole");
  EXPECT_EQ(patch.domain->degree, 2);
  EXPECT_EQ(patch.domain->knot_radius, 0.25);
  EXPECT_TRUE(patch.settings.weight_mode == WeightMode::kFree);
  EXPECT_EQ(patch.settings.minimum_weight, 0.01);
  EXPECT_EQ(patch.settings.weight_inertia, 0.001);
  EXPECT_EQ(patch.settings.quadrature_degree, 5);
  EXPECT_EQ(patch.settings.quadrature_subdivisions, 2);
  EXPECT_EQ(patch.settings.tessellation_subdivisions, 3);
  EXPECT_EQ(patch.settings.tessellation_max_error, 0.01);
  EXPECT_EQ(patch.settings.tessellation_max_level, 9);
  EXPECT_EQ(patch.material.b02(Eigen::Vector2d::Zero()), 0.3);
  // Square with a hole, 1 cell per unit: 8 cells, 16 triangles of 6 quadratic B-splines each
  EXPECT_EQ(patch.surface->control_point_count(), 96);
  const auto& plate = as<SceneTriangularDNurbsSurface>(scene.models[1].spec);
  EXPECT_EQ(plate.surface->basis().triangulation().triangle_count(), 12);
  EXPECT_EQ(plate.surface->basis().triangulation().vertices().col(0).minCoeff(), -1.0);
  // Round trip: parse(write(parse)) == parse, writing is stable
  const std::string written = scene_to_json(scene);
  const Scene again = parse_scene_json(written, "written.json", kData);
  EXPECT_TRUE(again == scene) << written;
  EXPECT_EQ(scene_to_json(again), written);
  // The inline shape is written back as the same surface
  EXPECT_EQ(as<SceneTriangularDNurbsSurface>(again.models[2].spec).surface->control_points(),
            as<SceneTriangularDNurbsSurface>(scene.models[2].spec).surface->control_points());
  // Every written key of the model is documented (in a table or an example)
  std::ifstream in(kData / ".." / ".." / "docs" / "scene-format.md");
  ASSERT_TRUE(in);
  std::ostringstream docs;
  docs << in.rdbuf();
  std::set<std::string> paths;
  key_paths(nlohmann::json::parse(written)["models"], "models", paths);
  for (const std::string& path : paths) {
    const std::string key = path.substr(path.rfind('.') + 1);
    const bool documented = docs.str().find("`" + key + "`") != std::string::npos ||
                            docs.str().find("." + key + "`") != std::string::npos ||
                            docs.str().find("\"" + key + "\":") != std::string::npos;
    EXPECT_TRUE(documented) << path << " is not in docs/scene-format.md";
  }
}

TEST(TriangularDNurbsSurfaceScene, BuildsStepsMeshesAndReportsItsCost) {
  SceneSimulation simulation(parse_scene_json(kScene, "tri.json", kData));
  const System& system = simulation.system();
  ASSERT_EQ(system.model_count(), 3);
  // patch: control points 0 and 7 fixed (3 each) and the weight gauge
  const auto& patch = as<SceneTriangularDNurbsSurface>(simulation.scene().models[0].spec);
  // plate: the border control points (fixed weights, 3 coordinates each)
  const auto& plate = as<SceneTriangularDNurbsSurface>(simulation.scene().models[1].spec);
  const int border = static_cast<int>(border_control_points(plate.surface->basis()).size());
  const std::vector<SceneModelCost> cost = simulation.cost();
  EXPECT_EQ(cost[0].fixed, 7);
  EXPECT_EQ(cost[0].velocities, 4 * patch.surface->control_point_count());
  EXPECT_EQ(cost[1].fixed, 3 * border);
  EXPECT_TRUE(cost[1].constant_matrices);
  EXPECT_EQ(cost[1].kronecker_block, 3);
  EXPECT_EQ(cost[1].automatic_choice, "fixed weights (naive: free weights)");
  EXPECT_GT(cost[1].naive_active, cost[1].velocities - cost[1].fixed);
  // tile: a point force at one parameter, margin 1 ring: nothing of the single triangle frozen
  EXPECT_EQ(cost[2].fixed, 0);
  for (int i = 0; i < 3; ++i) {
    simulation.step();
  }
  EXPECT_TRUE(system.coordinates().allFinite());
  // The spring lifts the patch where it pulls
  const SceneSample sample = simulation.sample();
  EXPECT_GT(sample.probes[0].z(), 0.0);
  // Meshes: patch adaptive (its tessellation.max_error), plate uniform from the resolution
  // (6 segments over the height 1: edges <= 1/6, the longest domain edge, the diagonal 0.83 of a
  // 2/3 by 1/2 cell, needs 5 subdivisions)
  const std::vector<TriangleMesh> meshes = simulation.meshes(6);
  ASSERT_EQ(meshes.size(), 3u);
  EXPECT_EQ(meshes[1].name, "plate");
  EXPECT_EQ(meshes[1].triangle_count(), 12 * 25);
  EXPECT_GT(meshes[0].triangle_count(), 0);
  // tile: edges <= 1/6 with the hypotenuse sqrt(2) need 9 subdivisions
  EXPECT_EQ(meshes[2].triangle_count(), 81);
  // No tensor-product shape to write
  EXPECT_FALSE(simulation.shape(0).has_value());
}

TEST(TriangularDNurbsSurfaceScene, ShapeFilesAreReadRelativeToTheScene) {
  const std::filesystem::path directory = std::filesystem::temp_directory_path();
  const SceneTriangularDomain domain;  // 4 x 4 unit square, degree 2
  write_triangular_shape_file(directory / "dnurbs_test_tri_shape.json",
                              triangular_domain_surface(domain));
  const Scene scene = parse_scene_json(
      R"({"models": [{"type": "triangular_dnurbs_surface", "shape_file": "dnurbs_test_tri_shape.json"}],
          "run": {"steps": 1}})",
      "scene.json", directory);
  const auto& spec = as<SceneTriangularDNurbsSurface>(scene.models[0].spec);
  EXPECT_EQ(spec.shape_file, "dnurbs_test_tri_shape.json");
  EXPECT_EQ(spec.surface->control_point_count(), 32 * 6);
  EXPECT_THAT(scene_to_json(scene), HasSubstr("\"shape_file\": \"dnurbs_test_tri_shape.json\""));
  std::filesystem::remove(directory / "dnurbs_test_tri_shape.json");
  try {
    parse_scene_json(scene_to_json(scene), "scene.json", directory);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("scene.json: models[0].shape_file:"));
    EXPECT_THAT(error.what(), HasSubstr("the shape file does not exist"));
  }
}

TEST(TriangularDNurbsSurfaceScene, ParametersOutsideTheDomainAreErrors) {
  // A spring in the L-shape's missing quadrant
  const std::string text = R"({"models": [{"name": "l", "type": "triangular_dnurbs_surface",
      "domain": {"shape": "l_shape"}}],
    "forces": [{"type": "spring", "model": "l", "at": [1.5, 1.5], "stiffness": 1,
                "target": [0, 0, 1]}],
    "run": {"steps": 1}})";
  try {
    SceneSimulation simulation(parse_scene_json(text, "l.json"));
    simulation.step();
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("outside"));
  }
}

}  // namespace
}  // namespace dnurbs
