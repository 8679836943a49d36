#pragma once
// Material points of node models (snakes, grid surfaces, generalized splines): x(u) interpolates
// the nodes with weights w_k (linear along a chain, bilinear on a grid), q = [u_0, u_1, ...] with
// 3 coordinates per node, so L(u) = dx/dq = sum_k w_k (e_{n_k}^T (x) I_3).

#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "dnurbs/dynamics/core/model.h"

namespace dnurbs {

/// x = sum_k w_k q.segment<3>(3 n_k) over the (node n_k, weight w_k) pairs with w_k != 0.
template <typename NodeWeights>
Eigen::Vector3d interpolate_nodes(ConstVectorRef q, const NodeWeights& weights) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (const auto& [node, weight] : weights) {
    if (weight != 0.0) {  // (a node beyond the ends of the weights is not read)
      x += weight * q.template segment<3>(3 * node);
    }
  }
  return x;
}

/// L = dx/dq of interpolate_nodes: 3 by coordinate_count, the entries w_k at (c, 3 n_k + c) for
/// the non-zero weights.
template <typename NodeWeights>
SparseMatrix node_interpolation_jacobian(const NodeWeights& weights, int coordinate_count) {
  std::vector<Eigen::Triplet<double>> triplets;
  for (const auto& [node, weight] : weights) {
    if (weight != 0.0) {
      for (int c = 0; c < 3; ++c) {
        triplets.emplace_back(c, 3 * node + c, weight);
      }
    }
  }
  SparseMatrix jacobian(3, coordinate_count);
  jacobian.setFromTriplets(triplets.begin(), triplets.end());
  return jacobian;
}

}  // namespace dnurbs
