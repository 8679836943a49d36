#pragma once
// Regular (u, v) grids of nodes (DESIGN.md, "Grid surfaces"): the parameterization of the
// Terzopoulos surface (Wu & de Melo) and of the dynamic PDE surface (Romero 2005), kept separate
// from the node positions (the coordinates) as geometry-central keeps connectivity apart from
// geometry.

#include <array>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/surface/parametric_surface.h"
#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// Node positions of a grid or chain, one row per node (#nodes by 3).
using NodePositions = Eigen::MatrixX3d;

/// A regular grid of nu by nv nodes with equal spacing h in u and v (Romero 2005, section 4.3:
/// "horizontal and vertical internode spacings h equal in both directions"). Node (i, j) sits
/// at the parameter (u, v) = (i h, j h), i = 0..nu-1 along u, j = 0..nv-1 along v, and has the
/// index k = i + nu j (u fastest). The parametric domain is [0, (nu-1) h] x [0, (nv-1) h].
class Grid {
 public:
  /// Throws Error naming the value if nu or nv is below `minimum_nodes` (>= 2) or h is not
  /// positive and finite.
  Grid(int nu, int nv, double h, int minimum_nodes = 2);

  int nu() const { return nu_; }
  int nv() const { return nv_; }
  double spacing() const { return h_; }
  int node_count() const { return nu_ * nv_; }
  int index(int i, int j) const { return i + nu_ * j; }
  /// (i, j) of node k.
  std::pair<int, int> node(int k) const { return {k % nu_, k / nu_}; }
  Eigen::Vector2d parameter(int i, int j) const { return {i * h_, j * h_}; }
  Eigen::Vector2d parameter(int k) const;
  /// True for nodes on the grid's border (i or j at either end).
  bool on_border(int i, int j) const { return i == 0 || j == 0 || i == nu_ - 1 || j == nv_ - 1; }
  /// Indices of the border nodes, ascending.
  std::vector<int> border_nodes() const;
  /// Parameters of every node, in node order (contact points, sampling).
  std::vector<Eigen::Vector2d> node_parameters() const;
  /// Parameters of the nu nodes of row j (v = j h), i = 0..nu-1; throws Error if j is outside
  /// 0..nv-1.
  std::vector<Eigen::Vector2d> row_parameters(int j) const;

  /// The (at most 4) nodes and bilinear weights that interpolate a point at the parameter u
  /// (clamped to the domain): x(u) = sum w_a r_{node_a}. Weights sum to 1; a weight is exactly 1
  /// at a node (parameters within 1e-9 spacings of a node snap to it, so parameter(i, j) hits
  /// node (i, j) exactly).
  std::array<std::pair<int, double>, 4> bilinear_weights(const Eigen::Vector2d& u) const;

 private:
  int nu_;
  int nv_;
  double h_;
};

/// Rest shape of a flat sheet: r(i, j) = origin + (i h) axis_u + (j h) axis_v (#nodes by 3).
/// With unit orthogonal axes the sheet is isometric to the parameter plane (G0 = identity).
NodePositions flat_grid_positions(const Grid& grid, const Eigen::Vector3d& origin,
                                  const Eigen::Vector3d& axis_u = Eigen::Vector3d::UnitX(),
                                  const Eigen::Vector3d& axis_v = Eigen::Vector3d::UnitY());

/// The grid's parameter rectangle [0, (nu - 1) h] x [0, (nv - 1) h] (no closures).
ParameterDomain grid_parameter_domain(const Grid& grid);

/// x(u) by bilinear interpolation of the node positions.
Eigen::Vector3d interpolate_grid(const Grid& grid, const NodePositions& positions,
                                 const Eigen::Vector2d& u);

/// The node positions as a triangle mesh: one vertex per node (row k = node k), two triangles
/// per cell, oriented so that (b - a) x (c - a) points along r_u x r_v; normals by central
/// differences (one-sided on the border; zero rows where the tangents are parallel) and uv the
/// node parameters. Throws Error if positions has the wrong row count or is not finite.
TriangleMesh grid_triangle_mesh(const Grid& grid, const NodePositions& positions,
                                std::string name = "grid");

/// Throws Error naming `what`, the node and the coordinate if positions does not have
/// grid.node_count() rows or holds a non-finite value.
void check_grid_positions(const Grid& grid, const NodePositions& positions, const char* what);

}  // namespace dnurbs
