// The "curve_on_surface" scene constraint with "follow": true (io/scene_constraints.h): it reads,
// writes, builds one CurveOnSurfaceConstraint row per sample, holds a curve on a sculpted
// sheet, and rejects bad keys with their JSON path.

#include "dnurbs/io/scene_constraints.h"

#include <iostream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/constraints/curve_on_surface_constraint.h"
#include "dnurbs/core/error.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

// A bicubic sheet over [0, 3]^2 (7 x 7 control points) clamped at its border and pulled up at its
// centre by a spring, with a straight cubic curve lying on it along y = 1.5, and the
// curve_on_surface constraint whose keys are `keys`.
std::string sheet_and_curve(const std::string& keys) {
  return R"json({
  "models": [
    {"name": "sheet", "type": "dnurbs_surface",
     "make": {"kind": "plane", "size": [3, 3], "control_points": [7, 7]},
     "material": {"damping_density": 2, "a10": 1, "a01": 1},
     "boundary": {"clamp_border": true}},
    {"name": "seam", "type": "dnurbs_curve",
     "shape": {"type": "nurbs_curve", "degree": 3, "knots": [0, 0, 0, 0, 1, 1, 1, 1],
               "control_points": [[0.5, 1.5, 0], [1.2, 1.5, 0], [1.8, 1.5, 0], [2.5, 1.5, 0]]},
     "material": {"damping_density": 2, "tension": 0.1}}],
  "forces": [{"type": "spring", "model": "sheet", "at": [1.5, 1.5], "stiffness": 50,
              "target": {"times": [0, 1], "values": [[1.5, 1.5, 0], [1.5, 1.5, 0.5]]}}],
  "constraints": [{"type": "curve_on_surface", "curve_model": "seam", "surface_model": "sheet")json" +
         keys + R"json(}],
  "integrator": {"scheme": "newmark", "dt": 0.01, "newton_iterations": 2},
  "run": {"steps": 20}
})json";
}

TEST(SceneCurveOnSurface, FollowingSamplesBuildOneRowEachAndHoldTheCurve) {
  const Scene scene = parse_scene_json(sheet_and_curve(R"(, "samples": 6, "follow": true)"));
  const std::string written = scene_to_json(scene);
  EXPECT_THAT(written, HasSubstr("\"follow\": true"));
  EXPECT_TRUE(parse_scene_json(written) == scene);
  SceneSimulation simulation(scene);
  ASSERT_EQ(simulation.constraints().constraint_count(), 1);
  EXPECT_EQ(simulation.constraints().row_count(), 6);
  const auto* following =
      dynamic_cast<const CurveOnSurfaceConstraint*>(&simulation.constraints().constraint(0));
  ASSERT_NE(following, nullptr);
  EXPECT_EQ(following->curve_parameters(), (std::vector<double>{0.0, 0.2, 0.4, 0.6, 0.8, 1.0}));
  for (int k = 0; k < 20; ++k) {
    simulation.step();
  }
  // The sheet rose under the spring (its centre by 0.0236 after 0.2 s) and the curve's middle
  // with it; the constraint started satisfied, so what remains at the samples is Newmark's
  // O(dt^2) error on the non-linear rows (measured 1.4e-5), below 1 % of the rise.
  const System& system = simulation.system();
  std::cout << "centre " << system.position(0, Eigen::Vector2d(1.5, 1.5)).z() << ", curve middle "
            << system.position(1, Eigen::Vector2d(0.5, 0.0)).z() << ", violation "
            << simulation.constraints().max_violation(system) << "\n";
  EXPECT_GT(system.position(0, Eigen::Vector2d(1.5, 1.5)).z(), 0.01);
  EXPECT_GT(system.position(1, Eigen::Vector2d(0.5, 0.0)).z(), 0.01);  // t = 0.5
  EXPECT_LT(simulation.constraints().max_violation(system),
            1e-2 * system.position(0, Eigen::Vector2d(1.5, 1.5)).z());
  // Without "follow" the same keys give the frozen ball joints, and the key is not written.
  const Scene frozen = parse_scene_json(sheet_and_curve(R"(, "samples": 6)"));
  EXPECT_THAT(scene_to_json(frozen), ::testing::Not(HasSubstr("follow")));
  EXPECT_EQ(SceneSimulation(frozen).constraints().constraint_count(), 6);
}

TEST(SceneCurveOnSurface, BadFollowKeysNameTheirPath) {
  const auto message = [](const std::string& keys) {
    try {
      SceneSimulation simulation(parse_scene_json(sheet_and_curve(keys)));
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message(R"(, "samples": 1, "follow": true)"), HasSubstr("constraints[0].samples"));
  EXPECT_THAT(message(R"(, "samples": 1, "follow": true)"), HasSubstr("at least 2 samples"));
  EXPECT_THAT(message(R"(, "follow": "yes")"), HasSubstr("constraints[0].follow"));
  EXPECT_THAT(message(R"(, "follow": true, "curve_model": "sheet")"), HasSubstr("curve_model"));
}

}  // namespace
}  // namespace dnurbs
