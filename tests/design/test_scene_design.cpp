// The scene's "design" section (io/scene.h SceneDesign): parsed values, parse/write/parse
// round trip, absent unless given, and every written key documented in docs/scene-format.md.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io/scene.h"

namespace dnurbs {
namespace {

using Json = nlohmann::json;

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
