#pragma once
// Topology of triangle meshes that T-surfaces produce: the closed, oriented 2-manifold check and
// the Euler characteristic chi = V - E + F (genus g = (2c - chi) / 2 for c closed components).

#include <string>

#include <Eigen/Core>

namespace dnurbs {

/// The counts of a triangle mesh's topology.
///
/// vertices, edges, triangles  V, E (undirected), F
/// components                  connected components (through shared edges)
/// euler_characteristic        V - E + F
struct MeshTopology {
  int vertices = 0;
  int edges = 0;
  int triangles = 0;
  int components = 0;
  int euler_characteristic = 0;
};

/// V, E, F, components and chi of `triangles` (#F by 3 indices into vertex_count vertices).
/// Throws Error naming the triangle for an index outside [0, vertex_count).
MeshTopology mesh_topology(const Eigen::MatrixX3i& triangles, int vertex_count);

/// Whether `triangles` form a closed, consistently oriented 2-manifold on vertex_count vertices:
/// every vertex is used; no triangle repeats a vertex; every edge bounds exactly two triangles,
/// which traverse it in opposite directions; the triangles around every vertex form a single
/// fan (one cycle). If not, `reason` (when given) names the first offending edge or vertex.
bool is_closed_oriented_manifold(const Eigen::MatrixX3i& triangles, int vertex_count,
                                 std::string* reason = nullptr);

/// The volume enclosed by a closed mesh by the divergence theorem, sum over triangles of
/// det(a, b, c) / 6: positive when the triangles are counter-clockwise seen from outside.
///
/// vertices   #V by 3 positions
/// triangles  #F by 3 indices
double enclosed_volume(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& triangles);

}  // namespace dnurbs
