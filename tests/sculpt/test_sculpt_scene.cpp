// The session's scene: the settings written through the scene's own material keys, pins as
// point_target constraints.

#include "dnurbs/sculpt/sculpt_scene.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace dnurbs {
namespace {

using Json = nlohmann::json;

const std::filesystem::path kScenes =
    std::filesystem::path(DNURBS_TEST_DATA_DIR) / ".." / ".." / "examples" / "scenes";

TEST(SculptScene, WritesSettingsIntoEveryDnurbsMaterialAndPinsAsConstraints) {
  const Scene scene = read_scene_file(kScenes / "hat_demo.json");
  const SculptSettingOverrides values = sculpt_scene_settings(scene);
  EXPECT_EQ(values[static_cast<int>(SculptSetting::kTension)], 1.0);  // the hat's a10
  EXPECT_EQ(values[static_cast<int>(SculptSetting::kDt)], 0.01);
  EXPECT_FALSE(values[static_cast<int>(SculptSetting::kStiffness)]);
  SculptSettingOverrides overrides;
  overrides[static_cast<int>(SculptSetting::kTension)] = 7.0;
  overrides[static_cast<int>(SculptSetting::kRigidity)] = 0.5;
  overrides[static_cast<int>(SculptSetting::kDensity)] = 2.0;
  overrides[static_cast<int>(SculptSetting::kDt)] = 0.02;
  const Scene changed = sculpt_scene(scene, overrides, {{0, {0.3, 0.4}, {1, 2, 3}}});
  const Json json = Json::parse(scene_to_json(changed));
  for (const int i : {0, 1}) {  // the hat and the torus
    const Json& material = json["models"][i]["material"];
    EXPECT_EQ(material["a10"], 7.0);
    EXPECT_EQ(material["a01"], 7.0);
    EXPECT_EQ(material["b20"], 0.5);
    EXPECT_EQ(material["b11"], 0.5);
    EXPECT_EQ(material["b02"], 0.5);
    EXPECT_EQ(material["mass_density"], 2.0);
  }
  // The superquadrics keep their own material; damping was not overridden
  EXPECT_EQ(json["models"][2]["material"],
            Json::parse(scene_to_json(scene))["models"][2]["material"]);
  EXPECT_EQ(json["models"][0]["material"]["damping_density"],
            Json::parse(scene_to_json(scene))["models"][0]["material"]["damping_density"]);
  EXPECT_EQ(changed.integrator.dt, 0.02);
  ASSERT_EQ(changed.constraints.size(), scene.constraints.size() + 1);
  const Json& pin = json["constraints"].back();
  EXPECT_EQ(pin["type"], "point_target");
  EXPECT_EQ(pin["model"], 0);
  EXPECT_EQ(pin["at"], Json::array({0.3, 0.4}));
  EXPECT_EQ(pin["target"], Json::array({1, 2, 3}));
}

}  // namespace
}  // namespace dnurbs
