#pragma once
// The binary frames of `dnurbs serve` (docs/serve.md, "Binary messages"): the vertex buffers of
// the shapes that changed since the last frame, as little-endian 32-bit words and floats, so that
// a page copies them into its vertex buffers without parsing.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// One model's part of a frame.
struct SculptFrameModel {
  int index = 0;                       ///< the model's index in the scene
  const TriangleMesh* mesh = nullptr;  ///< positions and normals (n vertices)
  Eigen::MatrixX3d control_points;     ///< c by 3; 0 rows: no control net
};

/// The frame "DNF1", frame number, model count, then per model its index, vertex count,
/// control point count, positions (3 n floats), normals (3 n floats) and control points (3 c
/// floats). Throws Error if a mesh's normals do not match its vertices.
std::string encode_sculpt_frame(std::uint32_t frame_number,
                                const std::vector<SculptFrameModel>& models);

/// Reads a frame back (for tests and tools): per model its index and the three arrays as
/// doubles. Throws Error naming the offset for a truncated or malformed frame.
struct DecodedSculptFrame {
  std::uint32_t frame_number = 0;
  struct Model {
    int index = 0;
    Eigen::MatrixX3d positions;
    Eigen::MatrixX3d normals;
    Eigen::MatrixX3d control_points;
  };
  std::vector<Model> models;
};
DecodedSculptFrame decode_sculpt_frame(const std::string& frame);

}  // namespace dnurbs
