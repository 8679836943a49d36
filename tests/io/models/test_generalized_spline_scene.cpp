// The scene type "generalized_spline" (io/models/generalized_spline_scene.h): chains and grids
// read, written back and built into the model the keys describe, and bad keys refused with their
// JSON paths.

#include "dnurbs/io/models/generalized_spline_scene.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

std::string scene_with(const std::string& model) {
  return R"json({"models": [)json" + model + R"json(], "run": {"steps": 2}})json";
}

const char* const kChain = R"json({"name": "c", "type": "generalized_spline",
    "nodes": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 1.5, 0]], "closed": true,
    "order": 2, "terms": [{"j": [1], "weight": 0.5}, {"j": [2], "weight": [1, 2, 3, 4, 5]}],
    "material": {"mass_density": 0, "damping_density": 2}})json";

const char* const kPlate = R"json({"name": "p", "type": "generalized_spline",
    "grid": {"nodes": [5, 4], "spacing": 0.25}, "order": 2,
    "terms": [{"j": [1, 0], "weight": 1}, {"j": [0, 1], "weight": 1},
              {"j": [2, 0], "weight": 0.1}, {"j": [1, 1], "weight": 0.1},
              {"j": [0, 2], "weight": 0.1}],
    "boundary": {"clamp_border": true}})json";

TEST(GeneralizedSplineScene, AChainIsReadWrittenBackAndBuiltAsDescribed) {
  const Scene scene = parse_scene_json(scene_with(kChain));
  const std::string written = scene_to_json(scene);
  EXPECT_EQ(scene_to_json(parse_scene_json(written)), written);
  const SceneSimulation simulation(scene);
  const auto& model = dynamic_cast<const GeneralizedSpline&>(simulation.system().model(0));
  // The same material built by hand gives the same stiffness and mass
  GeneralizedSplineMaterial material;
  material.order = 2;
  material.mass_density = 0.0;
  material.damping_density = 2.0;
  SplineTerm tension;
  tension.ju = 1;
  tension.weight = 0.5;
  SplineTerm rigidity;
  rigidity.ju = 2;
  rigidity.node_weights = Eigen::Vector<double, 5>(1, 2, 3, 4, 5);
  material.terms = {tension, rigidity};
  const SparseMatrix expected = generalized_spline_stiffness(NodeChain(5, true), material);
  EXPECT_EQ(Eigen::MatrixXd(model.scalar().stiffness - expected).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(model.scalar().mass.nonZeros(), 0);  // massless: the first-order flow
  EXPECT_EQ(model.parametric_dimension(), 1);
}

TEST(GeneralizedSplineScene, AThinPlateOnAGridIsClampedAndStepped) {
  SceneSimulation simulation(parse_scene_json(scene_with(kPlate)));
  const auto& model = dynamic_cast<const GeneralizedSpline&>(simulation.system().model(0));
  EXPECT_EQ(model.parametric_dimension(), 2);
  EXPECT_EQ(model.coordinate_count(), 3 * 20);
  // The 14 border nodes are fixed: 6 interior nodes keep 18 free coordinates
  EXPECT_EQ(simulation.system().fixed_coordinates().size(), 3U * 14U);
  const std::string written = scene_to_json(simulation.scene());
  EXPECT_EQ(scene_to_json(parse_scene_json(written)), written);
  simulation.step();
  EXPECT_TRUE(simulation.system().coordinates().allFinite());
}

TEST(GeneralizedSplineScene, BadKeysAreRefusedNamingTheirPath) {
  const auto message = [](const std::string& model) {
    return testing::error_message(
        [&] { SceneSimulation simulation(parse_scene_json(scene_with(model), "g.json")); });
  };
  EXPECT_THAT(message(R"({"type": "generalized_spline", "order": 1})"),
              HasSubstr("g.json: models[0]: missing key \"nodes\" (a chain) or \"grid\""));
  EXPECT_THAT(
      message(
          R"({"type": "generalized_spline", "nodes": [[0,0,0],[1,0,0]], "grid": {"nodes": [3, 3], "spacing": 1}})"),
      HasSubstr("both \"nodes\" and \"grid\""));
  EXPECT_THAT(
      message(
          R"({"type": "generalized_spline", "grid": {"nodes": [3, 3], "spacing": 1}, "closed": true})"),
      HasSubstr("models[0].closed: a grid is open"));
  EXPECT_THAT(
      message(R"({"type": "generalized_spline", "nodes": [[0,0,0],[1,0,0],[2,0,0]], "order": 0})"),
      HasSubstr("models[0].order"));
  EXPECT_THAT(
      message(
          R"({"type": "generalized_spline", "nodes": [[0,0,0],[1,0,0],[2,0,0]], "terms": [{"j": [1, 0]}]})"),
      HasSubstr("models[0].terms[0].j: expected [ju] on a chain"));
  EXPECT_THAT(
      message(
          R"({"type": "generalized_spline", "nodes": [[0,0,0],[1,0,0],[2,0,0]], "terms": [{"j": [1], "weight": -1}]})"),
      HasSubstr("models[0].terms[0].weight: expected a number >= 0, got -1"));
  EXPECT_THAT(
      message(
          R"({"type": "generalized_spline", "nodes": [[0,0,0],[1,0,0],[2,0,0]], "terms": [{"j": [1], "weight": [1, 2]}]})"),
      HasSubstr("models[0].terms[0].weight: expected 3 weights (one per node), got 2"));
  // The model's own checks, named at the model: too few nodes for the order, no mass and no
  // damping, a term above the order
  EXPECT_THAT(message(R"({"type": "generalized_spline", "nodes": [[0,0,0],[1,0,0]], "order": 2})"),
              HasSubstr("models[0]: "));
  EXPECT_THAT(
      message(
          R"({"type": "generalized_spline", "nodes": [[0,0,0],[1,0,0],[2,0,0]], "material": {"mass_density": 0}})"),
      HasSubstr("models[0]: "));
  EXPECT_THAT(
      message(
          R"({"type": "generalized_spline", "nodes": [[0,0,0],[1,0,0],[2,0,0]], "terms": [{"j": [3]}]})"),
      HasSubstr("models[0]: "));
}

}  // namespace
}  // namespace dnurbs
