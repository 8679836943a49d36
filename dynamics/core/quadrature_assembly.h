#pragma once
// Building blocks of D-NURBS assembly by Gauss quadrature (Terzopoulos 2003, eqs. 1.25-1.26): Gauss
// points over the non-empty knot spans of each parametric direction with their B-spline basis
// values cached once, the rational Jacobian of a point and of its parametric derivatives (eq 1.23
// and its surface analogue) evaluated from those cached values at any weights, and the pre-sized
// symmetric sparsity pattern into which element matrices are scattered.
//
// Curves and surfaces share this code: a curve is a tensor product with a trivial v direction
// (degree 0, one span, one point, basis value 1).

#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "dnurbs/dynamics/core/model.h"
#include "dnurbs/nurbs/knot_vector.h"

namespace dnurbs {

/// Parametric quantities, numbered as SurfaceQuantity: 0 x, 1 x_u, 2 x_v, 3 x_uu, 4 x_uv, 5 x_vv.
inline constexpr int kQuantityCount = 6;
/// Largest number of control points active at one material point.
inline constexpr int kMaxActiveControlPoints = (kMaxDegree + 1) * (kMaxDegree + 1);
/// Number of quantities of total derivative order <= order: 1, 3 or 6.
inline int quantity_count(int order) {
  return order == 0 ? 1 : (order == 1 ? 3 : 6);
}
/// Derivative order in u and in v of each quantity.
inline constexpr std::array<int, kQuantityCount> kQuantityOrderU = {0, 1, 0, 2, 1, 0};
inline constexpr std::array<int, kQuantityCount> kQuantityOrderV = {0, 0, 1, 0, 1, 2};

/// One term of the Leibniz rule D^alpha (f g) = sum_{beta <= alpha} C(alpha, beta) D^beta f
/// D^(alpha - beta) g over the quantities (C the binomial coefficient of the multi-indices).
struct LeibnizTerm {
  int alpha;
  int beta;
  int rest;  ///< alpha - beta
  double coefficient;
};
/// Every term of the quantities, ordered by alpha (terms of alpha from kLeibnizFirst[alpha] to
/// kLeibnizFirst[alpha + 1]); beta and alpha - beta of a term are quantities <= alpha.
inline constexpr std::array<LeibnizTerm, 15> kLeibnizTerms = {{
    {0, 0, 0, 1.0},  // x
    {1, 0, 1, 1.0},
    {1, 1, 0, 1.0},  // x_u
    {2, 0, 2, 1.0},
    {2, 2, 0, 1.0},  // x_v
    {3, 0, 3, 1.0},
    {3, 1, 1, 2.0},
    {3, 3, 0, 1.0},  // x_uu
    {4, 0, 4, 1.0},
    {4, 1, 2, 1.0},
    {4, 2, 1, 1.0},
    {4, 4, 0, 1.0},  // x_uv
    {5, 0, 5, 1.0},
    {5, 2, 2, 2.0},
    {5, 5, 0, 1.0},  // x_vv
}};
inline constexpr std::array<int, kQuantityCount + 1> kLeibnizFirst = {0, 1, 3, 5, 8, 12, 15};

/// Gauss-Legendre points over the non-empty spans of one parametric direction and the cached
/// B-spline basis (values, first and second derivatives) at each of them.
struct DirectionQuadrature {
  int degree = 0;           ///< p (0 for the trivial direction of a curve)
  int points_per_span = 1;  ///< Gauss points per non-empty span
  int span_count = 1;       ///< number of non-empty spans
  /// Distinct control point of basis function a on span s: control_point[s * (p + 1) + a].
  std::vector<int> control_point;
  /// Parameter and weight (Gauss weight times half the span length) of point g of span s, at
  /// index s * points_per_span + g.
  std::vector<double> parameter;
  std::vector<double> weight;
  /// d-th derivative (d = 0..2) of basis function a at point i = s * points_per_span + g:
  /// basis[(i * 3 + d) * (p + 1) + a].
  std::vector<double> basis;
  /// Left and right end of each non-empty span.
  std::vector<double> span_start;
  std::vector<double> span_end;
};

/// The table for one direction with `points_per_span` Gauss points (1..kMaxGaussPoints) per
/// non-empty span of `knots`.
DirectionQuadrature direction_quadrature(const KnotVector& knots, int points_per_span);
/// The trivial direction (degree 0, one span [0, 1] of one point of weight 1, basis value 1).
DirectionQuadrature trivial_direction_quadrature();

/// The non-zero B-spline basis functions of one direction at one parameter.
struct DirectionBasis {
  int degree = 0;
  std::array<int, kMaxDegree + 1> control_point{};
  /// value(d, a): d-th derivative (d = 0..2) of basis function a.
  Eigen::Matrix<double, 3, kMaxDegree + 1> value = Eigen::Matrix<double, 3, kMaxDegree + 1>::Zero();
};

/// Basis of `knots` at an arbitrary parameter u (throws Error if u is outside the domain).
void direction_basis(const KnotVector& knots, double u, DirectionBasis& basis);
/// Basis of the trivial direction (value 1, derivatives 0, control point 0).
void trivial_direction_basis(DirectionBasis& basis);
/// Basis at cached point g of span s of a quadrature table (no evaluation, a copy).
void direction_basis(const DirectionQuadrature& table, int span, int point, DirectionBasis& basis);

/// Tensor-product (non-rational) basis of the active control points at one material point:
/// N(quantity, a) for quantities 0..5 and active control points a = au * (q + 1) + av with the
/// flat control point index node[a] = i * count_v + j (u index outer).
struct PointBasis {
  int active_count = 0;
  std::array<int, kMaxActiveControlPoints> node{};
  Eigen::Matrix<double, kQuantityCount, Eigen::Dynamic, 0, kQuantityCount, kMaxActiveControlPoints>
      value;
};

/// Combines the bases of the two directions (count_v control points along v; 1 for curves).
void tensor_product_basis(const DirectionBasis& basis_u, const DirectionBasis& basis_v, int count_v,
                          PointBasis& basis);

/// The rational Jacobian at one material point (Terzopoulos 2003, eq. 1.23 and its surface
/// analogue) for quantities alpha = 0..quantity_count(order)-1 (x, x_u, x_v, x_uu, x_uv, x_vv):
///   d x^alpha / d P_a = R(alpha, a) I_3,   d x^alpha / d w_a = E[alpha].col(a)
/// with R_a = w_a N_a / W the rational basis, phi_a = N_a / W, and
///   E_a^alpha = D^alpha [phi_a (P_a - x)]   (filled only when weights are coordinates).
struct RationalJacobian {
  int order = 0;
  double weight_sum = 0.0;  ///< W = sum_a w_a N_a
  Eigen::Matrix<double, kQuantityCount, Eigen::Dynamic, 0, kQuantityCount,
                kMaxActiveControlPoints>
      rational;  ///< R(alpha, a)
  Eigen::Matrix<double, kQuantityCount, Eigen::Dynamic, 0, kQuantityCount,
                kMaxActiveControlPoints>
      phi;  ///< phi(alpha, a) = D^alpha (N_a / W)
  std::array<Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxActiveControlPoints>,
             kQuantityCount>
      weight_column;                                  ///< E[alpha].col(a)
  std::array<Eigen::Vector3d, kQuantityCount> point;  ///< x^alpha
};

/// Where a model keeps control point positions and weights: position of node i at
/// positions[i * position_stride + c], weight at weights[i * weight_stride].
struct ControlNet {
  const double* positions = nullptr;
  int position_stride = 3;
  const double* weights = nullptr;
  int weight_stride = 1;
};

/// Evaluates the rational Jacobian of quantities up to `order` (0..2) from the non-rational
/// basis; weight columns only if `with_weight_columns`. No allocation.
void rational_jacobian(const PointBasis& basis, int order, const ControlNet& net,
                       bool with_weight_columns, RationalJacobian& jacobian);

/// The symmetric node-to-node sparsity of an element-by-element assembly, pre-sized once, and
/// for every element the index into the value array of each local pair.
struct AssemblyPattern {
  int node_count = 0;
  int local_count = 0;  ///< active control points per element
  SparseMatrix scalar;  ///< node_count by node_count, both triangles, values zero
  /// local_to_value[(e * local_count + a) * local_count + b]: index in scalar.valuePtr() of
  /// entry (row node a, column node b) of element e.
  std::vector<int> local_to_value;
  std::vector<int> element_nodes;  ///< element_nodes[e * local_count + a]
};

/// Builds the pattern from the element connectivity (element_nodes of element_count elements,
/// local_count nodes each).
AssemblyPattern make_assembly_pattern(int node_count, int local_count,
                                      const std::vector<int>& element_nodes);

/// The pattern of a matrix whose every scalar non-zero is a dense b by b block (values zero).
SparseMatrix dense_block_pattern(const SparseMatrix& scalar, int block_size);
/// Value index, in a dense_block_pattern matrix, of entry (b i + r, b j + c) where the scalar
/// entry (i, j) has value index `scalar_index`.
inline int dense_block_value_index(const SparseMatrix& blocked, const SparseMatrix& scalar,
                                   int scalar_index, int j, int r, int c, int block_size) {
  return static_cast<int>(blocked.outerIndexPtr()[block_size * j + c]) +
         block_size * (scalar_index - static_cast<int>(scalar.outerIndexPtr()[j])) + r;
}

}  // namespace dnurbs
