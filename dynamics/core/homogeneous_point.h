#pragma once
// A material point of a rational (NURBS) patch in homogeneous form, for generalized forces of free
// weights without the rational Jacobian's columns (Terzopoulos 2003, eqs. 1.21-1.23 and their
// surface analogues: x = A / W with A = sum_a w_a N_a P_a and W = sum_a w_a N_a, i.e. the
// homogeneous control points (w_a P_a, w_a) combined by the B-spline basis).
//
// The generalized force of vectors h_alpha applied to the quantities x^alpha (x, x_u, x_v, x_uu,
// x_uv, x_vv), F = sum_alpha J_alpha^T h_alpha, is with V = 1 / W and the Leibniz rule (C the
// binomial coefficients of the multi-indices) on the homogeneous control point a
//   F^h_a = sum_beta N_a^beta (H_beta, -T_beta),
//   H_beta = sum_{alpha >= beta} C(alpha, beta) V^(alpha - beta) h_alpha,
//   s_beta = sum_{alpha >= beta} C(alpha, beta) x^(alpha - beta) . h_alpha,
//   T_gamma = sum_{beta >= gamma} C(beta, gamma) V^(beta - gamma) s_beta,
// and on the coordinates (P_a, w_a), by the chain rule through (w_a P_a, w_a),
//   F_{P_a} = w_a F^h_a,xyz,   F_{w_a} = P_a . F^h_a,xyz + F^h_a,w.
// Derivation: d x^alpha / d(w P)_a = D^alpha (N_a V) I_3 and d x^alpha / d w-component_a =
// -D^alpha (N_a V x); expanding both derivatives of products gives the sums above. The point's
// density (H, -T) is 4 numbers per quantity, so a quadrature point costs 4 multiply-adds per
// active control point and quantity, where the Jacobian's columns cost 3 per quantity to form and
// as many again to apply.

#include <array>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/quadrature_assembly.h"

namespace dnurbs {

/// The homogeneous sums S^alpha = sum_a N_a^alpha (w_a P_a, w_a) of one point, alpha = 0..5.
using HomogeneousSums = std::array<Eigen::Vector4d, kQuantityCount>;

/// The rational quantities of one material point for derivatives of total order <= `order`.
struct HomogeneousPoint {
  int quantities = 1;  ///< quantity_count(order)
  int order_v = 2;     ///< highest derivative order in v with a basis (0 for curves)
  std::array<double, kQuantityCount> inverse_weight{};  ///< V^alpha = D^alpha (1 / W)
  std::array<Eigen::Vector3d, kQuantityCount> point{};  ///< x^alpha
};

/// V^alpha and x^alpha from the sums S^alpha, for the quantities alpha < quantity_count(order)
/// whose derivative in v is of order <= order_v (0 for a curve, whose basis has no v
/// derivatives: the others are left zero and skipped by homogeneous_force_density). No
/// allocation.
void homogeneous_point(const HomogeneousSums& sums, int order, int order_v,
                       HomogeneousPoint& point);

/// The rate of x for the rate sum sum_a N_a (w_a Pdot_a + wdot_a P_a, wdot_a) of the homogeneous
/// control points: xdot = V (Adot - x Wdot).
Eigen::Vector3d rational_rate(const HomogeneousPoint& point, const Eigen::Vector4d& rate_sum);

/// The point's force density (H_beta, -T_beta) for the vectors h_alpha, alpha < point.quantities
/// (the file comment): F^h_a = sum_beta N_a^beta density[beta] (zero for the quantities that
/// homogeneous_point skipped).
void homogeneous_force_density(const HomogeneousPoint& point,
                               const std::array<Eigen::Vector3d, kQuantityCount>& h,
                               HomogeneousSums& density);

}  // namespace dnurbs
