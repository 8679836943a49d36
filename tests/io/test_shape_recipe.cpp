// Shape recipes: every kind builds what its generator builds, scenes take them as a model's
// "make" key (a made sheet runs exactly like the same sheet typed out), and every bad recipe is
// refused with the JSON path of the bad value.
#include "dnurbs/io/shape_recipe.h"

#include <algorithm>
#include <filesystem>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"
#include "dnurbs/io/shape_file.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "dnurbs/nurbs/shape_generators.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

using testing::error_message;
using ::testing::HasSubstr;

Shape make(const std::string& json) {
  const SceneReader reader("recipe", std::filesystem::temp_directory_path());
  return make_shape(reader, JsonValue::parse(json), "make");
}

// Same knots, control points and weights, exactly.
template <typename ShapeType>
void expect_same(const Shape& made, const ShapeType& expected) {
  ASSERT_TRUE(std::holds_alternative<ShapeType>(made));
  EXPECT_EQ(shape_to_json(made), shape_to_json(Shape(expected)));
}

TEST(ShapeRecipe, EveryKindBuildsWhatItsGeneratorBuilds) {
  expect_same(make(R"({"kind": "line", "start": [0, 1, 0], "end": [2, 1, 0], "degree": 2})"),
              greville_line({0, 1, 0}, {2, 1, 0}, 4, 2));
  expect_same(make(R"({"kind": "plane", "size": [3, 2], "control_points": [6, 5],
                       "degree": [3, 2], "origin": [1, 1, 1]})"),
              greville_plane({3, 2}, {6, 5}, {3, 2}, {1, 1, 1}));
  expect_same(make(R"({"kind": "plane"})"), greville_plane({1, 1}, {4, 4}, {3, 3}));
  expect_same(make(R"({"kind": "box", "size": [1, 2, 3]})"), box({1, 2, 3}));
  expect_same(make(R"({"kind": "cylinder", "radius": 2, "height": 3,
                       "profile_control_points": 6})"),
              cylinder(2, 3, 6));
  expect_same(make(R"({"kind": "cone", "radius": 2, "height": 3})"), cone(2, 3));
  expect_same(make(R"({"kind": "sphere", "radius": 2})"), sphere(2));
  expect_same(make(R"({"kind": "torus", "major_radius": 2, "minor_radius": 0.5})"), torus(2, 0.5));
  const NurbsCurve profile = half_circle_xz(1.0);
  const std::string profile_json = shape_to_json(Shape(profile));
  expect_same(make(R"({"kind": "revolve", "angle_degrees": 90, "profile": )" + profile_json + "}"),
              revolve(profile, std::numbers::pi / 2));
  expect_same(make(R"({"kind": "revolve", "profile": )" + profile_json + "}"),
              surface_of_revolution(profile));
  expect_same(make(R"({"kind": "extrude", "direction": [0, 0, 2], "curve": )" + profile_json + "}"),
              extrude(profile, {0, 0, 2}));
  const NurbsCurve line = greville_line({0, 0, 1}, {1, 0, 1}, 4, 3);
  expect_same(make(R"({"kind": "loft", "degree": 2, "sections": [)" + profile_json +
                   R"(, {"kind": "line", "start": [0, 0, 1], "end": [1, 0, 1]}]})"),
              loft({profile, line}, 2));
}

TEST(ShapeRecipe, SplitTranslateAndShapeFilesApplyToEveryKind) {
  const Shape made = make(R"({"kind": "sphere", "radius": 2, "split": [2, 3],
                              "translate": [1, 0, -1]})");
  NurbsSurface expected = split_spans(sphere(2), {2, 3});
  Eigen::MatrixX3d moved = expected.control_points();
  moved.rowwise() += Eigen::RowVector3d(1, 0, -1);
  expected.set_control_points(moved);
  expect_same(made, expected);
  expect_same(make(R"({"kind": "line", "split": 3})"),
              split_spans(greville_line({0, 0, 0}, {1, 0, 0}, 4, 3), 3));

  const auto file = std::filesystem::temp_directory_path() / "dnurbs_recipe_profile.json";
  write_shape_file(file, Shape(half_circle_xz(1.5)));
  expect_same(make(R"({"kind": "revolve", "profile": "dnurbs_recipe_profile.json"})"), sphere(1.5));
  std::filesystem::remove(file);
}

TEST(ShapeRecipe, TheKeyListHasEveryKeyOfEveryKindOnce) {
  // The options of `dnurbs make` are these keys: the union of the kinds' own keys, then the
  // common ones
  std::vector<std::string> keys(shape_recipe_keys().begin(), shape_recipe_keys().end());
  EXPECT_EQ(keys.size(), 20U);
  EXPECT_EQ(keys.front(), "start");  // line's first key
  EXPECT_EQ(keys[keys.size() - 2], "split");
  EXPECT_EQ(keys.back(), "translate");
  std::sort(keys.begin(), keys.end());
  EXPECT_EQ(std::adjacent_find(keys.begin(), keys.end()), keys.end());
  for (const char* key : {"profile_control_points", "major_radius", "angle_degrees", "sections"}) {
    EXPECT_TRUE(std::binary_search(keys.begin(), keys.end(), std::string(key))) << key;
  }
}

TEST(ShapeRecipe, BadRecipesNameTheirJsonPath) {
  const auto message = [](const std::string& json) { return error_message([&] { make(json); }); };
  EXPECT_THAT(message(R"({"kind": "blob"})"),
              HasSubstr("recipe: make.kind: expected one of line, plane, box"));
  EXPECT_THAT(message(R"({"size": [1, 1]})"), HasSubstr("make.kind: missing key"));
  EXPECT_THAT(message(R"({"kind": "plane", "size": [1, -2]})"),
              HasSubstr("make.size[1]: expected a number > 0, got -2"));
  // A generator's refusal keeps the recipe's path
  EXPECT_THAT(message(R"({"kind": "plane", "control_points": [4, 2], "degree": [3, 3]})"),
              HasSubstr("make: plane domain y needs at least"));
  EXPECT_THAT(message(R"({"kind": "plane", "radius": 1})"),
              HasSubstr("make.radius: unknown key for a \"plane\" recipe"));
  EXPECT_THAT(message(R"({"kind": "sphere", "radius": 0})"),
              HasSubstr("make.radius: expected a number > 0"));
  EXPECT_THAT(message(R"({"kind": "revolve", "angle_degrees": 400, "profile": {"kind": "line"}})"),
              HasSubstr("make.angle_degrees: expected at most 360, got 400"));
  EXPECT_THAT(message(R"({"kind": "extrude", "curve": {"kind": "plane"}})"),
              HasSubstr("make.curve: expected a curve, got a surface"));
  EXPECT_THAT(message(R"({"kind": "extrude", "curve": "no_such_file.json"})"),
              HasSubstr("make.curve: "));
  EXPECT_THAT(message(R"({"kind": "loft", "sections": [{"kind": "line"}]})"),
              HasSubstr("make.sections: expected an array of >= 2 curves"));
  EXPECT_THAT(message(R"({"kind": "loft", "sections": [{"kind": "line"}, 3]})"),
              HasSubstr("make.sections[1]: expected a nurbs_curve, a shape file name"));
  EXPECT_THAT(message(R"({"kind": "plane", "control_points": [1000, 1000]})"),
              HasSubstr("the recipe makes 1000000 control points, more than the limit"));
  EXPECT_THAT(message(R"({"kind": "plane", "control_points": [300, 300], "split": [2, 2]})"),
              HasSubstr("more than the limit"));
  // A loft of many sections of many knots is refused before its sections are refined
  std::string many = R"({"kind": "loft", "sections": [)";
  for (int i = 0; i < 40; ++i) {
    many += std::string(i > 0 ? ", " : "") + R"({"kind": "line", "control_points": )" +
            std::to_string(400 + 7 * i) + "}";
  }
  EXPECT_THAT(message(many + "]}"), HasSubstr("make: the loft would make"));
  // Nesting is bounded: a hostile document cannot recurse without end
  std::string nested = R"({"kind": "line"})";
  for (int i = 0; i < 12; ++i) {
    nested = R"({"kind": "extrude", "curve": )" + nested + "}";
  }
  EXPECT_THAT(message(nested), HasSubstr("nested more than 8 deep"));
}

// The sheet of the first example of docs/scene-format.md, typed out and as a recipe.
std::string sheet_scene(const std::string& shape) {
  return R"({"models": [{"name": "sheet", "type": "dnurbs_surface", )" + shape + R"(,
              "material": {"damping_density": 2, "a10": 1, "a01": 1, "b20": 0.1},
              "boundary": {"clamp_border": true}}],
  "forces": [{"type": "spring", "model": "sheet", "at": [1.5, 1.5], "stiffness": 50,
              "target": [1.5, 1.5, 0.5]}],
  "run": {"steps": 30}})";
}

TEST(ShapeRecipe, ASceneModelMadeByARecipeRunsLikeTheSameShapeTypedOut) {
  const std::string typed = R"("shape": {"type": "nurbs_surface", "degree_u": 3, "degree_v": 3,
      "knots_u": [0, 0, 0, 0, 3, 3, 3, 3], "knots_v": [0, 0, 0, 0, 3, 3, 3, 3],
      "control_points": [[[0, 0, 0], [0, 1, 0], [0, 2, 0], [0, 3, 0]],
                         [[1, 0, 0], [1, 1, 0], [1, 2, 0], [1, 3, 0]],
                         [[2, 0, 0], [2, 1, 0], [2, 2, 0], [2, 3, 0]],
                         [[3, 0, 0], [3, 1, 0], [3, 2, 0], [3, 3, 0]]]})";
  const std::string made = R"("make": {"kind": "plane", "size": [3, 3]})";
  SceneSimulation a(parse_scene_json(sheet_scene(typed)));
  SceneSimulation b(parse_scene_json(sheet_scene(made)));
  const Eigen::VectorXd start = a.system().coordinates();
  for (int step = 0; step < 30; ++step) {
    a.step();
    b.step();
  }
  EXPECT_GT((a.system().coordinates() - start).lpNorm<Eigen::Infinity>(), 0.01);  // it moved
  EXPECT_EQ(a.system().coordinates(), b.system().coordinates());
}

// A free sphere under tension and bending, made by a recipe, with or without "rest_shape".
std::string sphere_scene(const std::string& rest) {
  return R"({"models": [{"name": "ball", "type": "dnurbs_surface",
              "make": {"kind": "sphere", "radius": 0.8}, )" +
         rest + R"("material": {"damping_density": 2, "a10": 1, "a01": 1, "b20": 0.1,
              "b11": 0.1, "b02": 0.1}}],
  "run": {"steps": 30}})";
}

TEST(ShapeRecipe, AMadeShapeWithItsInitialShapeAsRestStaysPut) {
  for (const bool at_rest : {true, false}) {
    const Scene scene =
        parse_scene_json(sphere_scene(at_rest ? R"("rest_shape": "initial", )" : ""));
    // The key survives the scene writer
    EXPECT_EQ(scene_to_json(scene).find(R"("rest_shape": "initial")") != std::string::npos,
              at_rest);
    SceneSimulation simulation(scene);
    const Eigen::VectorXd start = simulation.system().coordinates();
    for (int step = 0; step < 30; ++step) {
      simulation.step();
    }
    const double moved = (simulation.system().coordinates() - start).lpNorm<Eigen::Infinity>();
    if (at_rest) {
      EXPECT_EQ(moved, 0.0);  // the step solves for the increment, which is exactly zero
    } else {
      EXPECT_GT(moved, 0.01);  // measured from zero, tension shrinks the sphere
    }
  }
  EXPECT_THAT(error_message([] { parse_scene_json(sphere_scene(R"("rest_shape": "flat", )")); }),
              HasSubstr("models[0].rest_shape"));
}

TEST(ShapeRecipe, SceneKeysAreCheckedWithTheModelsPath) {
  const auto message = [](const std::string& shape) {
    return error_message([&] { parse_scene_json(sheet_scene(shape), "scene.json"); });
  };
  EXPECT_THAT(message(R"("make": {"kind": "plane", "size": [3, 0]})"),
              HasSubstr("scene.json: models[0].make.size[1]: expected a number > 0, got 0"));
  EXPECT_THAT(message(R"("make": {"kind": "line"})"),
              HasSubstr("models[0].make: expected a recipe that makes a nurbs_surface"));
  EXPECT_THAT(message(R"("make": {"kind": "plane"}, "shape_file": "x.json")"),
              HasSubstr("expected exactly one of \"shape\""));
  EXPECT_THAT(message(R"("make": {"kind": "plane"}, "fit": {"points": "x.xyz"})"),
              HasSubstr("expected either \"fit\" or \"make\""));
}

}  // namespace
}  // namespace dnurbs
