#include "dnurbs/io/animated_gltf.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include <nlohmann/json.hpp>

#include "dnurbs/core/error.h"
#include "dnurbs/io/atomic_write.h"

namespace dnurbs {
namespace {

// glTF 2.0 constants (specification, sections 3.6.2 and 4.4).
constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kTriangles = 4;
constexpr std::uint32_t kGlbMagic = 0x46546C67;   // "glTF"
constexpr std::uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kBinChunk = 0x004E4942;   // "BIN\0"

/// dnurbs' Z-up (x, y, z) as glTF's Y-up (x, z, -y).
Eigen::Vector3f y_up(const Eigen::Vector3d& point) {
  return {static_cast<float>(point.x()), static_cast<float>(point.z()),
          static_cast<float>(-point.y())};
}

/// The binary chunk being filled and the JSON arrays that describe it.
class GlbBuilder {
 public:
  /// A VEC3 float accessor of rows (Y-up) of `values`, minus `base` if given (morph targets);
  /// min and max as glTF requires for positions.
  int add_vectors(const Eigen::MatrixX3d& values, const Eigen::MatrixX3d* base) {
    const auto start = bytes_.size();
    Eigen::Vector3f low = Eigen::Vector3f::Constant(INFINITY);
    Eigen::Vector3f high = Eigen::Vector3f::Constant(-INFINITY);
    for (Eigen::Index row = 0; row < values.rows(); ++row) {
      Eigen::Vector3d value = values.row(row).transpose();
      if (base != nullptr) {
        value -= base->row(row).transpose();
      }
      const Eigen::Vector3f stored = y_up(value);
      low = low.cwiseMin(stored);
      high = high.cwiseMax(stored);
      append(stored.data(), 3 * sizeof(float));
    }
    return add_accessor(
        start, kArrayBuffer, kFloat, "VEC3", values.rows(),
        {{"min", {low.x(), low.y(), low.z()}}, {"max", {high.x(), high.y(), high.z()}}});
  }

  int add_indices(const Eigen::MatrixX3i& triangles) {
    const auto start = bytes_.size();
    for (Eigen::Index row = 0; row < triangles.rows(); ++row) {
      for (int corner = 0; corner < 3; ++corner) {
        const auto index = static_cast<std::uint32_t>(triangles(row, corner));
        append(&index, sizeof(index));
      }
    }
    return add_accessor(start, kElementArrayBuffer, kUnsignedInt, "SCALAR", 3 * triangles.rows(),
                        {});
  }

  int add_scalars(const std::vector<float>& values, bool bounds) {
    const auto start = bytes_.size();
    append(values.data(), values.size() * sizeof(float));
    nlohmann::json extra = nlohmann::json::object();
    if (bounds) {
      extra["min"] = {values.front()};
      extra["max"] = {values.back()};
    }
    return add_accessor(start, -1, kFloat, "SCALAR", static_cast<Eigen::Index>(values.size()),
                        extra);
  }

  nlohmann::json accessors = nlohmann::json::array();
  nlohmann::json buffer_views = nlohmann::json::array();
  const std::string& bytes() const { return bytes_; }

 private:
  void append(const void* data, std::size_t size) {
    bytes_.append(static_cast<const char*>(data), size);
  }

  int add_accessor(std::size_t start, int target, int component, const char* type,
                   Eigen::Index count, const nlohmann::json& extra) {
    nlohmann::json view = {
        {"buffer", 0}, {"byteOffset", start}, {"byteLength", bytes_.size() - start}};
    if (target > 0) {
      view["target"] = target;
    }
    buffer_views.push_back(view);
    nlohmann::json accessor = {{"bufferView", buffer_views.size() - 1},
                               {"componentType", component},
                               {"count", count},
                               {"type", type}};
    for (const auto& [key, value] : extra.items()) {
      accessor[key] = value;
    }
    accessors.push_back(accessor);
    return static_cast<int>(accessors.size()) - 1;
  }

  std::string bytes_;
};

void append_u32(std::string& out, std::uint32_t value) {
  char bytes[4];
  std::memcpy(bytes, &value, 4);  // glTF is little-endian, as every machine dnurbs builds on
  out.append(bytes, 4);
}

void check_frame(const std::vector<TriangleMesh>& first, const std::vector<TriangleMesh>& meshes,
                 int frame) {
  if (meshes.size() != first.size()) {
    throw make_error("animation frame ", frame, " has ", meshes.size(), " meshes, the first frame ",
                     first.size());
  }
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const TriangleMesh& mesh = meshes[i];
    if (mesh.vertex_count() != first[i].vertex_count() || mesh.triangles != first[i].triangles) {
      throw make_error("animation frame ", frame, ": mesh ", i, " (", mesh.name,
                       ") has other vertices or triangles than in the first frame; an animated "
                       "glTF needs the same mesh in every frame");
    }
    if (!mesh.vertices.allFinite() || !mesh.normals.allFinite()) {
      throw make_error("animation frame ", frame, ": mesh ", i, " (", mesh.name,
                       ") has a non-finite coordinate");
    }
  }
}

}  // namespace

void GltfAnimation::add_frame(double time, const std::vector<TriangleMesh>& meshes) {
  const int frame = frame_count();
  if (!std::isfinite(time) || (frame > 0 && !(time > times_.back()))) {
    throw make_error("animation frame ", frame, ": time ", time,
                     " is not finite or not after the previous frame's");
  }
  if (frame >= kMaxAnimationFrames) {
    throw make_error("an animation holds at most ", kMaxAnimationFrames,
                     " frames (write frames less often)");
  }
  if (meshes.empty()) {
    throw make_error("animation frame ", frame, " has no mesh");
  }
  check_frame(frame == 0 ? meshes : frames_.front(), meshes, frame);
  times_.push_back(time);
  frames_.push_back(meshes);
}

std::string GltfAnimation::glb() const {
  if (frames_.empty()) {
    throw Error("an animation needs at least one frame");
  }
  GlbBuilder builder;
  nlohmann::json nodes = nlohmann::json::array();
  nlohmann::json meshes = nlohmann::json::array();
  nlohmann::json samplers = nlohmann::json::array();
  nlohmann::json channels = nlohmann::json::array();
  const std::vector<TriangleMesh>& first = frames_.front();
  const std::size_t targets = frames_.size() - 1;
  std::vector<float> times;
  for (const double time : times_) {
    times.push_back(static_cast<float>(time));
  }
  const int time_accessor = targets > 0 ? builder.add_scalars(times, true) : -1;
  for (std::size_t i = 0; i < first.size(); ++i) {
    const bool normals = first[i].normals.rows() == first[i].vertices.rows();
    nlohmann::json attributes = {{"POSITION", builder.add_vectors(first[i].vertices, nullptr)}};
    if (normals) {
      attributes["NORMAL"] = builder.add_vectors(first[i].normals, nullptr);
    }
    nlohmann::json primitive = {{"attributes", attributes},
                                {"indices", builder.add_indices(first[i].triangles)},
                                {"material", 0},
                                {"mode", kTriangles}};
    // Morph target k: frame k + 1 minus the first frame.
    nlohmann::json morphs = nlohmann::json::array();
    for (std::size_t k = 1; k < frames_.size(); ++k) {
      nlohmann::json target = {
          {"POSITION", builder.add_vectors(frames_[k][i].vertices, &first[i].vertices)}};
      if (normals) {
        target["NORMAL"] = builder.add_vectors(frames_[k][i].normals, &first[i].normals);
      }
      morphs.push_back(target);
    }
    nlohmann::json mesh = {{"name", first[i].name}, {"primitives", {primitive}}};
    if (targets > 0) {
      mesh["primitives"][0]["targets"] = morphs;
      mesh["weights"] = std::vector<float>(targets, 0.0F);
      // At frame f the weight of target f - 1 is 1 and every other 0: frame f exactly, and
      // between frames the linear blend of the two.
      std::vector<float> weights(frames_.size() * targets, 0.0F);
      for (std::size_t frame = 1; frame < frames_.size(); ++frame) {
        weights[frame * targets + frame - 1] = 1.0F;
      }
      samplers.push_back({{"input", time_accessor},
                          {"output", builder.add_scalars(weights, false)},
                          {"interpolation", "LINEAR"}});
      channels.push_back(
          {{"sampler", samplers.size() - 1}, {"target", {{"node", i}, {"path", "weights"}}}});
    }
    meshes.push_back(mesh);
    nodes.push_back({{"mesh", i}, {"name", first[i].name}});
  }
  nlohmann::json scene_nodes = nlohmann::json::array();
  for (std::size_t i = 0; i < first.size(); ++i) {
    scene_nodes.push_back(i);
  }
  nlohmann::json document = {{"asset", {{"version", "2.0"}, {"generator", "dnurbs"}}},
                             {"scene", 0},
                             {"scenes", {{{"nodes", scene_nodes}}}},
                             {"nodes", nodes},
                             {"meshes", meshes},
                             {"materials",
                              {{{"doubleSided", true},
                                {"pbrMetallicRoughness",
                                 {{"baseColorFactor", {0.8, 0.8, 0.85, 1.0}},
                                  {"metallicFactor", 0.0},
                                  {"roughnessFactor", 0.6}}}}}},
                             {"accessors", builder.accessors},
                             {"bufferViews", builder.buffer_views},
                             {"buffers", {{{"byteLength", builder.bytes().size()}}}}};
  if (targets > 0) {
    document["animations"] = {{{"name", "run"}, {"samplers", samplers}, {"channels", channels}}};
  }
  std::string json = document.dump();
  json.append((4 - json.size() % 4) % 4, ' ');
  std::string binary = builder.bytes();
  binary.append((4 - binary.size() % 4) % 4, '\0');
  std::string out;
  append_u32(out, kGlbMagic);
  append_u32(out, 2);
  append_u32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + binary.size()));
  append_u32(out, static_cast<std::uint32_t>(json.size()));
  append_u32(out, kJsonChunk);
  out += json;
  append_u32(out, static_cast<std::uint32_t>(binary.size()));
  append_u32(out, kBinChunk);
  out += binary;
  return out;
}

void GltfAnimation::write(const std::filesystem::path& path) const {
  write_file_atomically(path, glb());
}

}  // namespace dnurbs
