// Tests of io/models/terzopoulos_surface_scene.h, the scene type "terzopoulos_surface": every
// value of the key "normal" (classic, christoffel, christoffel_unnormalized) reaches the model's
// settings and is written back, and an unknown value fails naming its JSON path.

#include "dnurbs/io/models/terzopoulos_surface_scene.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/io/scene.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

std::string sheet_scene(const std::string& normal) {
  return R"({"models": [{"name": "sheet", "type": "terzopoulos_surface",
     "grid": {"nodes": [4, 4], "spacing": 0.25}, "normal": ")" +
         normal + R"(", "delta": 0.25}], "run": {"steps": 1}})";
}

const SceneTerzopoulosSurface& terzopoulos_spec(const Scene& scene) {
  return dynamic_cast<const SceneTerzopoulosSurface&>(*scene.models[0].spec);
}

TEST(TerzopoulosSurfaceScene, EveryNormalValueReachesTheModelAndRoundTrips) {
  const std::pair<const char*, NormalApproximation> cases[] = {
      {"classic", NormalApproximation::kClassic},
      {"christoffel", NormalApproximation::kChristoffel},
      {"christoffel_unnormalized", NormalApproximation::kChristoffelUnnormalized}};
  for (const auto& [name, normal] : cases) {
    const Scene scene = parse_scene_json(sheet_scene(name));
    EXPECT_EQ(terzopoulos_spec(scene).settings.normal, normal) << name;
    EXPECT_EQ(terzopoulos_spec(scene).settings.delta, 0.25);
    const auto model = terzopoulos_spec(scene).build();
    EXPECT_EQ(dynamic_cast<const TerzopoulosSurface&>(*model).settings().normal, normal) << name;
    const std::string written = scene_to_json(scene);
    EXPECT_THAT(written, HasSubstr(std::string("\"normal\": \"") + name + "\""));
    EXPECT_EQ(terzopoulos_spec(parse_scene_json(written)).settings.normal, normal) << name;
  }
}

TEST(TerzopoulosSurfaceScene, UnknownNormalFailsNamingItsPath) {
  std::string message;
  try {
    parse_scene_json(sheet_scene("unnormalized"), "bad.json");
  } catch (const Error& error) {
    message = error.what();
  }
  EXPECT_THAT(message, HasSubstr("models[0].normal"));
  EXPECT_THAT(message, HasSubstr("christoffel_unnormalized"));
  EXPECT_THAT(message, HasSubstr("\"unnormalized\""));
}

}  // namespace
}  // namespace dnurbs
