// Animated glTF: decoding the written .glb gives back every frame (the first frame's mesh plus
// morph target k is frame k + 1, Y-up, to float precision), the weights pick one target per
// frame at the frames' times, a run with output.animation writes it, and frames that do not
// fit are refused naming the frame.
#include "dnurbs/io/animated_gltf.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "dnurbs/core/error.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_runner.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

/// A .glb's JSON document and binary chunk.
struct Glb {
  nlohmann::json document;
  std::string binary;
};

std::uint32_t u32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, 4);
  return value;
}

Glb decode(const std::string& bytes) {
  EXPECT_EQ(u32(bytes, 0), 0x46546C67U);  // "glTF"
  EXPECT_EQ(u32(bytes, 4), 2U);
  EXPECT_EQ(u32(bytes, 8), bytes.size());
  const std::uint32_t json_length = u32(bytes, 12);
  EXPECT_EQ(json_length % 4, 0U);
  EXPECT_EQ(u32(bytes, 16), 0x4E4F534AU);  // "JSON"
  Glb glb{nlohmann::json::parse(bytes.substr(20, json_length)), {}};
  const std::size_t bin = 20 + json_length;
  EXPECT_EQ(u32(bytes, bin + 4), 0x004E4942U);  // "BIN\0"
  glb.binary = bytes.substr(bin + 8, u32(bytes, bin));
  return glb;
}

/// The floats of accessor `index`.
std::vector<float> floats(const Glb& glb, int index) {
  const nlohmann::json& accessor = glb.document["accessors"][index];
  const nlohmann::json& view = glb.document["bufferViews"][accessor["bufferView"].get<int>()];
  EXPECT_EQ(accessor["componentType"], 5126);
  const int width = accessor["type"] == "VEC3" ? 3 : 1;
  std::vector<float> values(accessor["count"].get<std::size_t>() * width);
  EXPECT_EQ(view["byteLength"].get<std::size_t>(), values.size() * 4);
  std::memcpy(values.data(), glb.binary.data() + view["byteOffset"].get<std::size_t>(),
              values.size() * 4);
  return values;
}

/// A 3 x 3 grid of vertices (two triangles per cell) bent by `bend`, with unit normals.
TriangleMesh grid(double bend, const std::string& name) {
  TriangleMesh mesh;
  mesh.name = name;
  mesh.vertices.resize(9, 3);
  mesh.normals.resize(9, 3);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      mesh.vertices.row(i * 3 + j) << i, j, bend * (i - 1.0) * (i - 1.0) + 0.1 * j;
      mesh.normals.row(i * 3 + j) << -2.0 * bend * (i - 1.0), -0.1, 1.0;
      mesh.normals.row(i * 3 + j).normalize();
    }
  }
  mesh.triangles.resize(8, 3);
  int row = 0;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      const int corner = i * 3 + j;
      mesh.triangles.row(row++) << corner, corner + 3, corner + 4;
      mesh.triangles.row(row++) << corner, corner + 4, corner + 1;
    }
  }
  return mesh;
}

TEST(AnimatedGltf, EveryFrameDecodesFromTheBaseMeshAndItsMorphTarget) {
  GltfAnimation animation;
  const std::vector<double> times = {0.0, 0.25, 0.5, 1.0};
  for (std::size_t frame = 0; frame < times.size(); ++frame) {
    animation.add_frame(times[frame], {grid(0.3 * frame, "sheet"), grid(-0.1 * frame, "cap")});
  }
  const Glb glb = decode(animation.glb());
  const nlohmann::json& document = glb.document;
  EXPECT_EQ(document["asset"]["version"], "2.0");
  ASSERT_EQ(document["meshes"].size(), 2U);
  ASSERT_EQ(document["animations"].size(), 1U);
  const nlohmann::json& run = document["animations"][0];
  for (int mesh = 0; mesh < 2; ++mesh) {
    const double scale = mesh == 0 ? 0.3 : -0.1;
    const nlohmann::json& primitive = document["meshes"][mesh]["primitives"][0];
    const std::vector<float> base = floats(glb, primitive["attributes"]["POSITION"]);
    const std::vector<float> base_normals = floats(glb, primitive["attributes"]["NORMAL"]);
    ASSERT_EQ(primitive["targets"].size(), 3U);
    for (std::size_t frame = 0; frame < times.size(); ++frame) {
      const TriangleMesh expected = grid(scale * frame, "");
      std::vector<float> position = base;
      std::vector<float> normal = base_normals;
      if (frame > 0) {
        const nlohmann::json& target = primitive["targets"][frame - 1];
        const std::vector<float> delta = floats(glb, target["POSITION"]);
        const std::vector<float> normal_delta = floats(glb, target["NORMAL"]);
        for (std::size_t k = 0; k < position.size(); ++k) {
          position[k] += delta[k];
          normal[k] += normal_delta[k];
        }
      }
      for (int v = 0; v < 9; ++v) {
        // Y-up: (x, y, z) is stored as (x, z, -y); floats hold 24 bits (6e-8 relative).
        const Eigen::Vector3d point = expected.vertices.row(v);
        EXPECT_NEAR(position[3 * v], point.x(), 1e-6);
        EXPECT_NEAR(position[3 * v + 1], point.z(), 1e-6);
        EXPECT_NEAR(position[3 * v + 2], -point.y(), 1e-6);
        EXPECT_NEAR(normal[3 * v + 1], expected.normals(v, 2), 1e-6);
      }
    }
    // The sampler: the frames' times in, one-hot weights out (target f - 1 at frame f).
    const nlohmann::json& channel = run["channels"][mesh];
    EXPECT_EQ(channel["target"]["node"], mesh);
    EXPECT_EQ(channel["target"]["path"], "weights");
    const nlohmann::json& sampler = run["samplers"][channel["sampler"].get<int>()];
    EXPECT_EQ(sampler["interpolation"], "LINEAR");
    const std::vector<float> input = floats(glb, sampler["input"]);
    ASSERT_EQ(input.size(), times.size());
    for (std::size_t frame = 0; frame < times.size(); ++frame) {
      EXPECT_EQ(input[frame], static_cast<float>(times[frame]));
    }
    EXPECT_EQ(document["accessors"][sampler["input"].get<int>()]["max"][0], 1.0);
    const std::vector<float> weights = floats(glb, sampler["output"]);
    ASSERT_EQ(weights.size(), 4U * 3U);
    for (std::size_t frame = 0; frame < 4; ++frame) {
      for (std::size_t target = 0; target < 3; ++target) {
        EXPECT_EQ(weights[frame * 3 + target], frame > 0 && target == frame - 1 ? 1.0F : 0.0F);
      }
    }
  }
}

TEST(AnimatedGltf, FramesThatDoNotFitAreRefusedNamingTheFrame) {
  GltfAnimation animation;
  EXPECT_THAT(testing::error_message([&] { (void)animation.glb(); }),
              HasSubstr("an animation needs at least one frame"));
  animation.add_frame(0.0, {grid(0.0, "sheet")});
  EXPECT_THAT(testing::error_message([&] { animation.add_frame(0.0, {grid(1.0, "sheet")}); }),
              HasSubstr("animation frame 1: time 0 is not finite or not after"));
  TriangleMesh other = grid(1.0, "sheet");
  other.triangles.row(0) << 0, 1, 2;
  EXPECT_THAT(testing::error_message([&] { animation.add_frame(1.0, {other}); }),
              HasSubstr("animation frame 1: mesh 0 (sheet) has other vertices or triangles"));
  EXPECT_THAT(testing::error_message([&] {
                animation.add_frame(1.0, {grid(1, "a"), grid(1, "b")});
              }),
              HasSubstr("animation frame 1 has 2 meshes, the first frame 1"));
  TriangleMesh broken = grid(1.0, "sheet");
  broken.vertices(4, 2) = std::nan("");
  EXPECT_THAT(testing::error_message([&] { animation.add_frame(1.0, {broken}); }),
              HasSubstr("animation frame 1: mesh 0 (sheet) has a non-finite coordinate"));
  EXPECT_EQ(animation.frame_count(), 1);
  // One frame: a still mesh, no animation.
  EXPECT_FALSE(decode(animation.glb()).document.contains("animations"));
}

std::string curve_scene(const nlohmann::json& output, int steps) {
  const nlohmann::json scene = {{"models",
                                 {{{"name", "curve"},
                                   {"type", "dnurbs_curve"},
                                   {"shape",
                                    {{"type", "nurbs_curve"},
                                     {"degree", 2},
                                     {"knots", {0, 0, 0, 1, 1, 1}},
                                     {"control_points", {{0, 0, 0}, {1, 1, 0}, {2, 0, 0}}}}},
                                   {"material", {{"mass_density", 1}, {"tension", 1}}}}}},
                                {"run", {{"steps", steps}}},
                                {"output", output}};
  return scene.dump();
}

TEST(AnimatedGltf, ARunWritesItsFramesAsOneAnimation) {
  const auto root = std::filesystem::temp_directory_path() / "dnurbs_test_animated_gltf";
  std::filesystem::remove_all(root);
  SceneSimulation simulation(parse_scene_json(
      curve_scene({{"mesh_every", 2}, {"animation", true}, {"name", "rod"}}, 6), "<rod>"));
  SceneRunOptions options;
  options.output_directory = root;
  const SceneRunResult result = run_scene(simulation, options);
  ASSERT_EQ(result.animation, root / "rod_animation.glb");
  std::ifstream in(result.animation, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Glb glb = decode(bytes);
  // Frames at steps 0, 2, 4 and 6: 4 keyframes, 3 morph targets.
  EXPECT_EQ(result.frames_written, 4);
  EXPECT_EQ(glb.document["meshes"][0]["primitives"][0]["targets"].size(), 3U);
  const nlohmann::json& sampler = glb.document["animations"][0]["samplers"][0];
  EXPECT_EQ(floats(glb, sampler["input"]).size(), 4U);
  std::filesystem::remove_all(root);
}

TEST(AnimatedGltf, AnAnimationWithoutFramesOrWithTooManyIsRefusedAtLoad) {
  EXPECT_THAT(testing::error_message([] {
                parse_scene_json(curve_scene({{"animation", true}}, 6), "a.json");
              }),
              HasSubstr("a.json: output.animation: expected false when output.mesh_every is 0"));
  EXPECT_THAT(testing::error_message([] {
                parse_scene_json(
                    curve_scene({{"animation", true}, {"mesh_every", 1}}, kMaxAnimationFrames),
                    "b.json");
              }),
              HasSubstr("b.json: output.animation: the run has 1001 frames, more than an "
                        "animation holds (1000); raise output.mesh_every"));
}

}  // namespace
}  // namespace dnurbs
