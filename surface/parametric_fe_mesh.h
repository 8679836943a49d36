#pragma once
// The (u, v) finite-element mesh of a deformable superquadric's local deformations
// (Terzopoulos 2003, eqs. 1.32-1.33: d = S q_d, q_d = (..., d_i, ...)). The parameter domain
// u in [-pi/2, pi/2] (latitude), v in [-pi, pi) (longitude) has the topology of a sphere:
//   - cells_u by cells_v bilinear (C0) cells of equal size in parameter space;
//   - periodic in v: the node column at v = pi is the one at v = -pi;
//   - closed at the poles: the nodes of the rows u = -pi/2 and u = +pi/2 collapse to one node
//     each, so a displacement field is single-valued there.
// Nodes: 0 is the south pole (u = -pi/2); 1 + (i - 1) cells_v + j is the node of row
// i = 1..cells_u-1 (u_i = -pi/2 + i pi/cells_u) and column j = 0..cells_v-1
// (v_j = -pi + j 2pi/cells_v); the last node is the north pole (u = +pi/2).
// q_d stacks 3 displacements per node: q_d = (d_0x, d_0y, d_0z, d_1x, ...), 3 #nodes.
// Per-point evaluation uses fixed capacity and never allocates.

#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace dnurbs {

/// Shape functions active at one (u, v): d(u, v) = sum_a value[a] q_d(node[a]) and likewise
/// for the u and v derivatives. At most 4 nodes (3 in a cell touching a pole, where the two
/// pole corners are one node and their shape functions add). The values are a partition of unity.
struct FeShapeValues {
  static constexpr int kMaxActive = 4;
  int active_count = 0;
  std::array<int, kMaxActive> node{};               ///< node indices of the active shape functions
  Eigen::Vector4d value = Eigen::Vector4d::Zero();  ///< N_a(u, v)
  Eigen::Vector4d d_u = Eigen::Vector4d::Zero();    ///< dN_a/du
  Eigen::Vector4d d_v = Eigen::Vector4d::Zero();    ///< dN_a/dv
};

/// A displacement and its parametric derivatives.
struct FeDisplacement {
  Eigen::Vector3d value;  ///< d(u, v)
  Eigen::Vector3d d_u;    ///< dd/du
  Eigen::Vector3d d_v;    ///< dd/dv
};

/// Coefficients of the local-deformation energy
///   E = 1/2 q_d^T K_d q_d = 1/2 integral (w_u |d_u|^2 + w_v |d_v|^2 + k_0 |d|^2) du dv
/// over the parameter domain (a membrane plus a spring to the reference shape).
struct FeStiffnessCoefficients {
  double membrane_u = 1.0;  ///< w_u >= 0
  double membrane_v = 1.0;  ///< w_v >= 0
  double spring = 0.0;      ///< k_0 >= 0
};

/// A Gauss-Legendre point of the parameter domain: integral f du dv ~ sum weight f(u, v).
struct ParameterQuadraturePoint {
  double u = 0.0;
  double v = 0.0;
  double weight = 0.0;  ///< the rule's weight times the cell's Jacobian (du dv, no area element)
  int cell_u = 0;       ///< the cell holding the point
  int cell_v = 0;
};

/// The sphere-topology (u, v) mesh described at the top of this file. A value type.
class ParametricFeMesh {
 public:
  /// Throws Error unless cells_u >= 2 and cells_v >= 3.
  ParametricFeMesh(int cells_u, int cells_v);

  int cells_u() const { return cells_u_; }
  int cells_v() const { return cells_v_; }
  /// 2 + (cells_u - 1) cells_v.
  int node_count() const { return 2 + (cells_u_ - 1) * cells_v_; }
  /// 3 node_count(): the size of q_d.
  int coordinate_count() const { return 3 * node_count(); }
  int south_pole_node() const { return 0; }
  int north_pole_node() const { return node_count() - 1; }
  /// The node of row i (0..cells_u) and column j (any integer, taken modulo cells_v); rows 0
  /// and cells_u give the pole nodes for every j.
  int node_index(int row, int column) const;
  /// The (u, v) of a node; poles report v = 0. Throws Error for an index out of range.
  Eigen::Vector2d node_parameter(int node) const;
  /// The parameter box [u0, u1] x [v0, v1] of cell (i, j), i in 0..cells_u-1, j in
  /// 0..cells_v-1, as (u0, u1, v0, v1).
  Eigen::Vector4d cell_bounds(int cell_u, int cell_v) const;

  /// Tensor Gauss-Legendre points of every cell, points_per_direction^2 per cell, cell by cell
  /// (u outer): the points a model integrates over (multiplying by its own area element). No
  /// point lies on a cell edge or a pole. Throws Error unless 1 <= points <= kMaxGaussPoints.
  std::vector<ParameterQuadraturePoint> quadrature_points(int points_per_direction) const;

  /// The active shape functions and their derivatives at (u, v). u must lie in [-pi/2, pi/2]
  /// (up to 1e-12, then clamped); v is any finite value, wrapped into [-pi, pi). Where (u, v)
  /// is on a cell boundary the cell above (larger u, larger v) is used, except at u = pi/2.
  /// Throws Error for a u outside the domain or a non-finite u or v.
  FeShapeValues shape_values(double u, double v) const;

  /// d, d_u, d_v at the shape values from a q_d of size coordinate_count() (not checked).
  FeDisplacement displacement(const Eigen::Ref<const Eigen::VectorXd>& q_d,
                              const FeShapeValues& shape) const;

  /// S(u, v) as a sparse 3 by coordinate_count() matrix: the block of node a is N_a I_3.
  Eigen::SparseMatrix<double> shape_matrix(double u, double v) const;

  /// The scalar stiffness matrix k (node_count() square, symmetric):
  ///   k_ab = integral (w_u N_a,u N_b,u + w_v N_a,v N_b,v + k_0 N_a N_b) du dv,
  /// by Gauss-Legendre quadrature with `points_per_direction` points in u and v per cell (the
  /// default 2 integrates bilinear products exactly). Throws Error for a negative coefficient.
  Eigen::SparseMatrix<double> scalar_stiffness_matrix(const FeStiffnessCoefficients& coefficients,
                                                      int points_per_direction = 2) const;
  /// K_d = k (x) I_3 (coordinate_count() square), ordered like q_d.
  Eigen::SparseMatrix<double> stiffness_matrix(const FeStiffnessCoefficients& coefficients,
                                               int points_per_direction = 2) const;

  /// The scalar matrix m_ab = integral N_a N_b du dv over the parameter domain (unit density,
  /// no area element): handy for regularizing or projecting q_d.
  Eigen::SparseMatrix<double> scalar_mass_matrix(int points_per_direction = 2) const;

 private:
  int cells_u_;
  int cells_v_;
  double step_u_;
  double step_v_;
};

}  // namespace dnurbs
