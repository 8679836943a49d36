#pragma once
// The frames of a run as one animated glTF 2.0 binary file (.glb): each model's mesh of the
// first frame, one morph target per later frame (the displacement of every vertex and normal
// from the first frame), and an animation of the morph weights over the frames' times, linear
// between frames (glTF 2.0 specification, sections 3.7.2.2 "Morph targets" and 3.11
// "Animations"). Any glTF viewer plays it; coordinates are Y-up as glTF requires ((x, y, z) of
// dnurbs becomes (x, z, -y)).

#include <filesystem>
#include <string>
#include <vector>

#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// The most frames one animation holds: its weights are frames x (frames - 1) numbers per mesh.
inline constexpr int kMaxAnimationFrames = 1000;

class GltfAnimation {
 public:
  /// Adds the meshes of every model at time `time` (after the previous frame's). Every frame
  /// has the first frame's meshes: the same count, and each the same vertex count and
  /// triangles. Throws Error naming the mesh and the frame otherwise, for a non-finite time or
  /// coordinate, and beyond kMaxAnimationFrames frames.
  void add_frame(double time, const std::vector<TriangleMesh>& meshes);

  int frame_count() const { return static_cast<int>(times_.size()); }

  /// The .glb file's bytes: the JSON chunk and the binary chunk (positions and normals in
  /// 32-bit floats, triangles in 32-bit indices). Throws Error if there is no frame.
  std::string glb() const;

  /// Writes glb() to a file, through a temporary file and a rename.
  void write(const std::filesystem::path& path) const;

 private:
  std::vector<double> times_;
  std::vector<std::vector<TriangleMesh>> frames_;
};

}  // namespace dnurbs
