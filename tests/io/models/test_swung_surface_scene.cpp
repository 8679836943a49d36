// Tests of io/models/swung_surface_scene.h, the scene type "swung_surface": prototypes and curves
// (inline and shape files) parse into the surfaces they name, every key round-trips through the
// writer and is documented in docs/scene-format.md, malformed keys fail naming their JSON path,
// the cost report sets the model against its tensor-product twin, boundary keys, constraints and
// the rest shape keys reach the model, and the four example scenes of Fig. 6 keep the
// properties they are built on.

#include "dnurbs/io/models/swung_surface_scene.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"
#include "dnurbs/nurbs/swung_shapes.h"
#include "tests/dynamics/swung/swung_model_helpers.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;
using Json = nlohmann::json;

const std::filesystem::path kData = DNURBS_TEST_DATA_DIR;
const std::filesystem::path kExamples = kData / ".." / ".." / "examples" / "scenes";

std::string scene_with(const std::string& model, const std::string& rest = "") {
  return R"({"models": [)" + model + R"(], "run": {"steps": 1})" + rest + "}";
}

const SceneSwungSurface& swung_spec(const Scene& scene, size_t i = 0) {
  return dynamic_cast<const SceneSwungSurface&>(*scene.models[i].spec);
}

// The error message of parsing `text` (empty if it parses).
std::string parse_error(const std::string& text) {
  try {
    parse_scene_json(text, "bad.json", kData);
  } catch (const Error& error) {
    return error.what();
  }
  return {};
}

TEST(SwungSurfaceScene, PrototypesBuildTheSurfacesTheyName) {
  struct Case {
    const char* prototype;
    SwungSurface expected;
  };
  const std::vector<Case> cases = {
      {R"({"kind": "sphere", "radius": 1.5})", swung_sphere(1.5)},
      {R"({"kind": "torus", "major_radius": 3, "minor_radius": 1})", swung_torus(3, 1)},
      {R"({"kind": "cylinder", "radius": 0.5, "height": 2, "profile_control_points": 6})",
       swung_cylinder(0.5, 2, 6)},
      {R"({"kind": "cone", "radius": 0.5, "height": 2})", swung_cone(0.5, 2)},
      {R"({"kind": "hat", "brim_radius": 2, "crown_radius": 1, "height": 1.5})",
       swung_hat(2, 1, 1.5)},
      {R"({"kind": "open_profile", "start": [0, 0.5], "end": [2, 0], "profile_control_points": 5})",
       swung_open_profile(0, 0.5, 2, 0, 5)}};
  for (const Case& c : cases) {
    const Scene scene = parse_scene_json(
        scene_with(std::string(R"({"name": "s", "type": "swung_surface", "prototype": )") +
                   c.prototype + "}"));
    const SwungSurface& surface = swung_spec(scene).surface;
    EXPECT_EQ(surface.profile().control_points(), c.expected.profile().control_points())
        << c.prototype;
    EXPECT_EQ(surface.trajectory().control_points(), c.expected.trajectory().control_points());
    const std::unique_ptr<Model> model = swung_spec(scene).build();
    EXPECT_EQ(model->coordinate_count(), 2 * (c.expected.profile().control_point_count() +
                                              c.expected.trajectory().control_point_count()));
  }
  // Refinement: 1 knot per profile span and 2 per trajectory span (2 and 4 non-empty spans: the
  // rational circles have double knots at their quarter points).
  const Scene refined = parse_scene_json(scene_with(
      R"({"type": "swung_surface", "prototype": {"kind": "sphere"}, "refine": [1, 2]})"));
  const SwungSurface surface = swung_spec(refined).refined_surface();
  EXPECT_EQ(surface.profile().control_point_count(), 5 + 2);
  EXPECT_EQ(surface.trajectory().control_point_count(), 8 + 8);
}

TEST(SwungSurfaceScene, CurvesComeInlineOrFromShapeFilesAndRoundTrip) {
  const std::string text = scene_with(R"(
    {"name": "vase", "type": "swung_surface",
     "profile": {"shape_file": "swung_vase_profile.json"},
     "trajectory": {"shape": {"type": "nurbs_curve", "degree": 2, "periodic": true,
                              "knots": [0, 0.25, 0.5, 0.75, 1],
                              "control_points": [[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0]]}},
     "alpha": 1.5, "refine": [1, 0], "fix_profile": false, "fix_trajectory": true,
     "fix_poles": false, "weights": "free", "quadrature_points": 5, "minimum_weight": 0.01,
     "geometric_stiffness": true, "separable_assembly": false, "weight_inertia": 0.001,
     "material": {"mass_density": 2, "damping_density": 1, "a10": 1, "a01": 0.5, "b20": 0.1,
                  "b11": 0.05, "b02": 0.2},
     "boundary": {"fixed_points": [0]}})");
  const Scene scene = parse_scene_json(text, "vase.json", kData);
  const SceneSwungSurface& spec = swung_spec(scene);
  EXPECT_EQ(spec.profile_file, "swung_vase_profile.json");
  EXPECT_TRUE(spec.trajectory_file.empty());
  EXPECT_EQ(spec.surface.alpha(), 1.5);
  EXPECT_EQ(spec.surface.profile().control_point_count(), 7);
  EXPECT_TRUE(spec.surface.trajectory().is_periodic());
  EXPECT_EQ(spec.settings.weight_mode, WeightMode::kFree);
  EXPECT_EQ(spec.settings.quadrature_points, 5);
  EXPECT_TRUE(spec.settings.geometric_stiffness);
  EXPECT_FALSE(spec.settings.separable_assembly);
  EXPECT_EQ(spec.material.b02(Eigen::Vector2d::Zero()), 0.2);
  // Round trip: parse(write(parse)) == parse, writing is stable, no input key is dropped.
  const std::string written = scene_to_json(scene);
  const Scene again = parse_scene_json(written, "written.json", kData);
  EXPECT_TRUE(again == scene) << written;
  EXPECT_EQ(scene_to_json(again), written);
  const Json json = Json::parse(written).at("models")[0];
  EXPECT_EQ(json.at("profile").at("shape_file"), "swung_vase_profile.json");
  EXPECT_TRUE(json.at("trajectory").contains("shape"));
  const Json input = Json::parse(text);
  for (const auto& item : input.at("models")[0].items()) {
    EXPECT_TRUE(json.contains(item.key())) << item.key();
  }
  // The prototype form round-trips too, writing its kind's keys only.
  const Scene prototype =
      parse_scene_json(scene_with(R"({"type": "swung_surface", "prototype": {"kind": "hat"}})"));
  const std::string prototype_written = scene_to_json(prototype);
  EXPECT_TRUE(parse_scene_json(prototype_written) == prototype);
  EXPECT_EQ(Json::parse(prototype_written).at("models")[0].at("prototype"),
            Json::parse(R"({"kind": "hat", "brim_radius": 1.5, "crown_radius": 0.8,
                            "height": 1})"));
  // The model: the profile refined to 7 + 4 control points (one knot in each of its 4 spans) and
  // the trajectory's 4, with free weights.
  const SceneSimulation simulation(scene);
  EXPECT_EQ(simulation.system().model(0).coordinate_count(), 3 * (11 + 4));
}

void collect_keys(const Json& value, const std::string& path, std::set<std::string>& keys) {
  if (value.is_object()) {
    for (const auto& item : value.items()) {
      const std::string key = path.empty() ? item.key() : path + "." + item.key();
      // Inside a curve's "shape": the shape format of dnurbs eval
      if (!path.ends_with(".shape")) {
        keys.insert(key);
        collect_keys(item.value(), key, keys);
      }
    }
  }
}

TEST(SwungSurfaceScene, EveryWrittenKeyIsDocumented) {
  std::ifstream in(kData / ".." / ".." / "docs" / "scene-format.md");
  ASSERT_TRUE(in) << "docs/scene-format.md is missing";
  std::ostringstream text;
  text << in.rdbuf();
  const std::string docs = text.str();
  EXPECT_THAT(docs, HasSubstr("### `swung_surface`"));
  std::set<std::string> keys;
  for (const char* model :
       {R"({"type": "swung_surface", "prototype": {"kind": "torus"}})",
        R"({"type": "swung_surface", "prototype": {"kind": "open_profile"}})",
        R"({"type": "swung_surface", "prototype": {"kind": "hat"}})",
        R"({"type": "swung_surface", "prototype": {"kind": "cone"}})",
        R"({"type": "swung_surface", "profile": {"shape_file": "swung_vase_profile.json"},
            "trajectory": {"shape_file": "circle.json"}})"}) {
    const Scene scene = parse_scene_json(scene_with(model), "keys.json", kData);
    collect_keys(Json::parse(scene_to_json(scene)).at("models")[0], "", keys);
  }
  EXPECT_GT(keys.size(), 25U);
  for (const std::string& key : keys) {
    // In a table (`key`, `prefix.key`) or in an example ("key": ...)
    const std::string last = key.substr(key.rfind('.') + 1);
    const bool documented = docs.find("`" + key + "`") != std::string::npos ||
                            docs.find("`" + last + "`") != std::string::npos ||
                            docs.find("\"" + last + "\":") != std::string::npos;
    EXPECT_TRUE(documented) << key << " is not in docs/scene-format.md";
  }
}

TEST(SwungSurfaceScene, MalformedKeysNameTheirJsonPath) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"type": "swung_surface"})", "models[0].prototype: missing key"},
      {R"({"type": "swung_surface", "prototype": {"kind": "cube"}})",
       "models[0].prototype.kind: expected one of sphere, torus, cylinder, cone, hat, "
       "open_profile"},
      {R"({"type": "swung_surface", "prototype": {"kind": "sphere", "height": 2}})",
       "models[0].prototype.height: unknown key for a sphere prototype"},
      {R"({"type": "swung_surface", "prototype": {"kind": "sphere", "radius": -1}})",
       "models[0].prototype.radius: expected a number > 0"},
      {R"({"type": "swung_surface", "prototype": {"kind": "torus", "major_radius": 1,
           "minor_radius": 2}})",
       "models[0].prototype: swung torus minor radius 2 must be below the major radius 1"},
      {R"({"type": "swung_surface", "prototype": {"kind": "sphere"}, "alpha": 2})",
       "models[0].alpha: expected no \"alpha\" with a \"prototype\""},
      {R"({"type": "swung_surface", "profile": {"shape_file": "swung_vase_profile.json"}})",
       "models[0].trajectory: missing key"},
      {R"({"type": "swung_surface", "profile": {"shape_file": "circle.json"},
           "trajectory": {"shape_file": "circle.json"}})",
       "models[0].profile: profile control point 1 has y = 1"},
      {R"({"type": "swung_surface", "profile": {"shape_file": "swung_vase_profile.json"},
           "trajectory": {"shape_file": "swung_vase_profile.json"}})",
       "models[0].trajectory: trajectory control point 1 has z = 0.3"},
      {R"({"type": "swung_surface", "profile": {"shape_file": "swung_vase_profile.json"},
           "trajectory": {"shape_file": "circle.json"}, "alpha": 0})",
       "models[0].alpha: swung surface scale alpha is 0"},
      {R"({"type": "swung_surface", "profile": {"shape_file": "swung_vase_profile.json",
           "shape": {}}, "trajectory": {"shape_file": "circle.json"}})",
       "models[0].profile: expected exactly one of \"shape\""},
      {R"({"type": "swung_surface", "profile": {"shape": {"type": "nurbs_curve", "degree": 1,
           "knots": [0, 0, 1, 0.5], "control_points": [[1, 0, 0], [2, 0, 1]]}},
           "trajectory": {"shape_file": "circle.json"}})",
       "models[0].profile.shape.knots"},
      {R"({"type": "swung_surface", "profile": {"shape_file": "missing.json"},
           "trajectory": {"shape_file": "circle.json"}})",
       "models[0].profile.shape_file"},
      {R"({"type": "swung_surface", "prototype": {"kind": "sphere"}, "refine": [1]})",
       "models[0].refine: expected [profile, trajectory] knots per span"},
      {R"({"type": "swung_surface", "prototype": {"kind": "sphere"}, "refine": [1, -1]})",
       "models[0].refine[1]: expected an integer in 0..64"},
      {R"({"type": "swung_surface", "prototype": {"kind": "sphere"}, "fix_poles": 1})",
       "models[0].fix_poles"},
      {R"({"type": "swung_surface", "prototype": {"kind": "sphere"}, "weight_inertia": -1})",
       "models[0].weight_inertia: expected a number >= 0"},
      {R"({"type": "swung_surface", "prototype": {"kind": "sphere"},
           "material": {"tension": 1}})",
       "models[0].material.tension: unknown key"},
      {R"({"type": "swung_surface", "prototype": {"kind": "sphere"},
           "boundary": {"local_sculpting_margin": 1}})",
       "models[0].boundary.local_sculpting_margin: expected no local sculpting"}};
  for (const auto& [model, expected] : cases) {
    EXPECT_THAT(parse_error(scene_with(model)), HasSubstr(expected)) << model;
  }
  // Errors the model finds when the scene is built name the model too.
  const std::string closed = scene_with(
      R"({"type": "swung_surface", "prototype": {"kind": "sphere"},
          "boundary": {"clamp_border": true}})");
  try {
    SceneSimulation simulation(parse_scene_json(closed, "closed.json"));
    ADD_FAILURE() << "a sphere has no border";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("closed.json: models[0]: this swung surface is closed"));
  }
}

TEST(SwungSurfaceScene, CostSetsTheModelAgainstItsTensorProductTwin) {
  const SceneSimulation simulation(read_scene_file(kExamples / "swung_egg.json"));
  const SceneModelCost cost = simulation.cost().front();
  // 7 x 8 control points: 2 (7 + 8) = 30 swung coordinates, the poles' x and the trajectory
  // (16) fixed; the twin has 3 x 7 x 8 = 168, none fixed.
  EXPECT_EQ(cost.coordinates, 30);
  EXPECT_EQ(cost.fixed, 18);
  EXPECT_EQ(cost.naive_active, 168);
  EXPECT_FALSE(cost.constant_matrices);
  EXPECT_TRUE(cost.naive_constant_matrices);  // fixed weights: the twin factors once
  EXPECT_THAT(cost.automatic_choice,
              HasSubstr("tensor-product D-NURBS surface of the same shape, 7 x 8 control points"));
  std::cout << "egg: one solve " << cost.solve_work << " factor entries, twin "
            << cost.naive_solve_work << "\n";
  EXPECT_GT(cost.naive_solve_work, cost.solve_work);  // 12 dense unknowns against 168 banded
}

// Runs a scene to its end and returns the simulation.
SceneSimulation run_to_end(const std::filesystem::path& path) {
  SceneSimulation simulation(read_scene_file(path));
  while (simulation.steps_done() < simulation.scene().step_count()) {
    simulation.step();
  }
  return simulation;
}

TEST(SwungSurfaceScene, FigureSixScenesKeepTheirSymmetriesAndBoundaries) {
  // The egg, the hat and the wine glass hold their trajectory (the unit circle): surfaces of
  // revolution to round-off whatever the springs do.
  for (const char* name : {"swung_egg.json", "swung_hat.json", "swung_wine_glass.json"}) {
    const SceneSimulation simulation = run_to_end(kExamples / name);
    const double asymmetry = testing::rotational_asymmetry(
        simulation.system().model(0), simulation.system().coordinates(), 40, 64);
    const Eigen::VectorXd moved =
        simulation.system().coordinates() - simulation.system().model(0).initial_coordinates();
    std::cout << name << ": rotational asymmetry " << asymmetry << ", coordinates moved "
              << moved.norm() << "\n";
    EXPECT_LT(asymmetry, 1e-12) << name;   // round-off of the circle's evaluation (~4e-16)
    EXPECT_GT(moved.norm(), 0.3) << name;  // sculpted
  }
  // The egg is taller than wide and wider below its middle than above.
  const SceneSimulation egg = run_to_end(kExamples / "swung_egg.json");
  const auto at = [&](double u) { return egg.system().position(0, Eigen::Vector2d(u, 0.0)); };
  EXPECT_GT(at(1.0).z() - at(0.0).z(), 2.0);
  EXPECT_GT(at(0.4).x(), at(0.6).x());
  // The hat's brim edge is clamped exactly where it was.
  const SceneSimulation hat = run_to_end(kExamples / "swung_hat.json");
  for (const double v : {0.0, 0.3, 0.7}) {
    EXPECT_EQ(hat.system().position(0, Eigen::Vector2d(1.0, v)),
              hat.system().model(0).position(hat.system().model(0).initial_coordinates(),
                                             Eigen::Vector2d(1.0, v)));
  }
  EXPECT_GT(hat.system().position(0, Eigen::Vector2d(0.0, 0.0)).z(), 0.8);  // the crown rose
  // The toroid holds its profile: every cross-section keeps its height profile p_z(u), while the
  // trajectory is no longer a circle.
  const SceneSimulation toroid = run_to_end(kExamples / "swung_toroid.json");
  const Eigen::Vector3d outer = toroid.system().position(0, Eigen::Vector2d(0.0, 0.0));
  const Eigen::Vector3d pinched = toroid.system().position(0, Eigen::Vector2d(0.0, 0.25));
  EXPECT_GT(outer.head<2>().norm() - pinched.head<2>().norm(), 0.5);
  EXPECT_EQ(toroid.system().position(0, Eigen::Vector2d(0.3, 0.1)).z(),
            toroid.system().position(0, Eigen::Vector2d(0.3, 0.8)).z());
}

TEST(SwungSurfaceScene, ConstraintsAndBoundaryKeysReachTheModel) {
  // A surface normal held and a curve glued onto a swung sphere, a profile point fixed.
  const std::string text = scene_with(
      R"({"name": "ball", "type": "swung_surface", "prototype": {"kind": "sphere"},
          "material": {"damping_density": 1, "a10": 0.05, "a01": 0.05},
          "boundary": {"fixed_points": [6]}},
         {"name": "seam", "type": "dnurbs_curve",
          "shape": {"type": "nurbs_curve", "degree": 1, "knots": [0, 0, 1, 1],
                    "control_points": [[1.02, 0, -0.2], [1.02, 0, 0.2]]}})",
      R"(, "constraints": [
           {"type": "surface_normal", "model": "ball", "at": [0.5, 0], "direction": [1, 0, 0]},
           {"type": "curve_on_surface", "curve_model": "seam", "surface_model": "ball",
            "samples": 3}],
         "forces": [{"type": "spring", "model": "ball", "at": [0.4, 0.05], "stiffness": 5,
                     "target": [1.3, 0.1, -0.3]}],
         "integrator": {"newton_iterations": 2})");
  SceneSimulation simulation(parse_scene_json(text));
  const Model& ball = simulation.system().model(0);
  // The poles' x (coordinates 0 and 8); point 6 is trajectory control point 1 (the sphere's
  // profile has 5): X and Y fixed, and the gauge released (a trajectory point off the origin
  // already breaks the scaling).
  EXPECT_EQ(ball.fixed_coordinates(), (std::vector<int>{0, 8, 12, 13}));
  EXPECT_EQ(simulation.constraints().row_count(), 2 + 3 * 3);
  const Eigen::VectorXd initial = simulation.sample().violations;
  for (int k = 0; k < 20; ++k) {
    simulation.step();
  }
  EXPECT_TRUE(simulation.system().coordinates().allFinite());
  // The normal starts satisfied (the equator's normal is x), the ball joints 0.02..0.04 off (the
  // seam beside the surface); Baumgarte (alpha = beta = 20) decays them as
  // (1 + alpha t) e^(-alpha t), 0.092 at t = 0.2, while the spring pulls.
  const Eigen::VectorXd violations = simulation.sample().violations;
  std::cout << "swung sphere with a normal and a glued seam: violations " << initial.transpose()
            << " -> " << violations.transpose() << " after 0.2 s\n";
  EXPECT_LT(initial[0], 1e-12);
  EXPECT_LT(violations[0], 1e-8);  // measured 6e-11
  for (int c = 1; c < 4; ++c) {
    EXPECT_GT(initial[c], 0.015) << c;
    EXPECT_LT(violations[c], 0.1 * initial[c]) << c;  // measured 0.091 of the start
  }
}

TEST(SwungSurfaceScene, RestShapeAndPlasticKeysReachTheModelAndRoundTrip) {
  // "rest_shape": "initial" puts the sphere at rest (zero force); "plastic" makes it yield; both
  // are written back and read again; a plastic rest shape with "rest_shape": "none" is refused.
  const std::string sphere =
      R"({"type": "swung_surface", "prototype": {"kind": "sphere"}, "material": {"a10": 1}, )";
  for (const std::string keys :
       {R"("rest_shape": "initial"})", R"("plastic": {"yield": 0.01, "rate": 2}})"}) {
    const Scene scene = parse_scene_json(scene_with(sphere + keys));
    const DNurbsSwungSettings& settings = swung_spec(scene).settings;
    const bool plastic = keys.find("plastic") != std::string::npos;
    EXPECT_EQ(settings.initial_shape_at_rest, !plastic);
    EXPECT_EQ(settings.plastic_flow.has_value(), plastic);
    const Scene again = parse_scene_json(scene_to_json(scene));
    EXPECT_EQ(swung_spec(again).settings.initial_shape_at_rest, !plastic);
    ASSERT_EQ(swung_spec(again).settings.plastic_flow.has_value(), plastic);
    if (plastic) {
      EXPECT_EQ(swung_spec(again).settings.plastic_flow->yield, 0.01);
      EXPECT_EQ(swung_spec(again).settings.plastic_flow->rate, 2.0);
    }
    SceneSimulation simulation(scene);
    const Model& model = simulation.system().model(0);
    Eigen::VectorXd force = Eigen::VectorXd::Zero(model.velocity_count());
    model.add_internal_force(model.initial_coordinates(), force);
    EXPECT_EQ(force.lpNorm<Eigen::Infinity>(), 0.0) << keys;
    EXPECT_EQ(simulation.system().flowing_rest_coordinates().size(),
              plastic ? model.coordinate_count() : 0);
  }
  EXPECT_THAT(parse_error(scene_with(sphere + R"("plastic": {"yield": -1, "rate": 2}})")),
              HasSubstr("models[0].plastic.yield"));
  EXPECT_THAT(parse_error(scene_with(sphere + R"("rest_shape": "none",
                                                 "plastic": {"yield": 0, "rate": 2}})")),
              HasSubstr("a plastic rest shape needs \"rest_shape\": \"initial\""));
  EXPECT_THAT(parse_error(scene_with(sphere + R"("rest_shape": "bent"})")),
              HasSubstr("models[0].rest_shape: expected one of none, initial"));
}

TEST(SwungSurfaceScene, TheClayScenesSphereKeepsAWaistWhereAnElasticOneSpringsBack) {
  // examples/scenes/swung_clay.json: the equator ring pushed in for one second, released at
  // t = 1, settled by t = 5 (kinetic energy 2e-9 in its recorded log)
  const std::filesystem::path path = kExamples / "swung_clay.json";
  const SceneSimulation clay = run_to_end(path);
  const Eigen::Vector2d equator(0.5, 0.0);
  const Model& model = clay.system().model(0);
  const double radius = clay.system().position(0, equator).x();
  const Eigen::VectorXd rest = clay.system().flowing_rest_coordinates();
  ASSERT_EQ(rest.size(), model.coordinate_count());
  std::cout << "swung_clay: the equator's radius ends at " << radius << ", its rest shape's "
            << model.position(rest, equator).x() << "\n";
  // The waist is a dent of the rest shape: the surface has settled on it (to the rest motion of
  // the damped decay), 0.0456 inside the initial radius 1 (measured) under the keyed push of 3
  // (monotone keyframes); the natural cubic spline through the same keys pushed up to 14.0 and
  // left a waist of 0.199
  EXPECT_NEAR(radius, model.position(rest, equator).x(), 1e-6);
  EXPECT_NEAR(radius, 0.954393, 1e-6);
  EXPECT_LT(testing::rotational_asymmetry(model, clay.system().coordinates(), 40, 64), 1e-12);
  // The same push on an elastic sphere (its initial shape as rest): back to radius 1
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  std::string elastic = text.str();
  const std::string plastic_key = R"("plastic": {"yield": 0.01, "rate": 2})";
  ASSERT_NE(elastic.find(plastic_key), std::string::npos);
  elastic.replace(elastic.find(plastic_key), plastic_key.size(), R"("rest_shape": "initial")");
  SceneSimulation rubber(parse_scene_json(elastic));
  while (rubber.steps_done() < rubber.scene().step_count()) {
    rubber.step();
  }
  EXPECT_NEAR(rubber.system().position(0, equator).x(), 1.0, 1e-6);
}

}  // namespace
}  // namespace dnurbs
