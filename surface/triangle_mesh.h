#pragma once
// A triangle mesh as plain Eigen matrices: what tessellation produces and exporters consume.

#include <string>

#include <Eigen/Core>

namespace dnurbs {

/// An indexed triangle mesh with per-vertex normals and texture coordinates.
///
/// vertices   #V by 3 positions
/// normals    #V by 3 unit normals (or 0 rows when the mesh has none)
/// uv         #V by 2 texture coordinates, here the surface parameters (u, v) (or 0 rows)
/// triangles  #F by 3 vertex indices, counter-clockwise seen from the side the normals point to
/// name       names the mesh in exported files (an OBJ object, a glTF node)
struct TriangleMesh {
  std::string name;
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3d normals;
  Eigen::MatrixX2d uv;
  Eigen::MatrixX3i triangles;

  int vertex_count() const { return static_cast<int>(vertices.rows()); }
  int triangle_count() const { return static_cast<int>(triangles.rows()); }
};

}  // namespace dnurbs
