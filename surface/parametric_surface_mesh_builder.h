#pragma once
// Assembles a TriangleMesh from (u, v)-space triangles of a ParametricSurface: merges each
// pole's vertices into one, drops the triangles that collapse at a pole, and winds the rest so
// that their geometric normal follows the surface's normal orientation. Shared by the uniform
// tessellation and the restricted (adaptive) mesh of Goldenstein et al. 2005, section 4.

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/surface/parametric_surface.h"
#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// Collects vertices and triangles, then builds the mesh.
///
/// Vertices off the poles are added once each by the caller (who knows which parameters are
/// identified across a seam); every vertex added on a pole (ParameterDomain::pole_at) maps to
/// that pole's one vertex, sampled at the start of the pole edge ((u_pole, v_min) for a pole
/// at u_min or u_max), so every mesh of a surface has the same pole vertex.
class ParametricSurfaceMeshBuilder {
 public:
  explicit ParametricSurfaceMeshBuilder(const ParametricSurface& surface);

  /// Adds the vertex at (u, v), sampling point and unit normal from the surface; returns its
  /// index (an existing one for a pole).
  int add_vertex(double u, double v);
  /// The same with the point and normal already known (3-vectors; ignored on a pole).
  int add_vertex(double u, double v, const Eigen::Vector3d& point, const Eigen::Vector3d& normal);
  /// Adds the triangle (a, b, c), counter-clockwise in (u, v). It is dropped if two of its
  /// indices coincide (a triangle with an edge on a pole); it is wound (a, c, b) for surfaces
  /// whose normal is S_v x S_u.
  void add_triangle(int a, int b, int c);

  int vertex_count() const { return static_cast<int>(points_.size()); }
  /// The mesh: vertices, normals, uv (the parameters of each vertex) and triangles.
  TriangleMesh build(std::string name) const;

 private:
  int push(double u, double v, const Eigen::Vector3d& point, const Eigen::Vector3d& normal);

  const ParametricSurface* surface_;
  std::array<int, 4> pole_vertex_{-1, -1, -1, -1};
  std::vector<Eigen::Vector3d> points_;
  std::vector<Eigen::Vector3d> normals_;
  std::vector<Eigen::Vector2d> parameters_;
  std::vector<Eigen::Vector3i> triangles_;
};

}  // namespace dnurbs
