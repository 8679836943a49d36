#pragma once
// Building blocks of the triangular D-NURBS model (triangular_dnurbs_surface.h) that work on
// the rational Jacobian of one point (Qin & Terzopoulos, "Triangular NURBS and their dynamic
// generalizations", Computer Aided Geometric Design 14, 1997, section 4): J^T f and the 4 x 4
// control-point-and-weight blocks of sum_alpha c_alpha J_alpha^T J_alpha with their scatter
// into a pre-sized block pattern. The velocity product Jdot qd of free weights is
// free_weight_acceleration (dynamics/dnurbs/rational_control_net_model.h).

#include <array>
#include <vector>

#include "dnurbs/dynamics/core/model.h"
#include "dnurbs/dynamics/core/quadrature_assembly.h"
#include "dnurbs/nurbs/triangular_nurbs_surface.h"

namespace dnurbs {

/// force += J_alpha^T f for the listed B-splines: R(alpha, a) f on the position coordinates of
/// control point function[a] and, with `free_weights` (4 coordinates per control point),
/// E[alpha].col(a) . f on its weight; 3 coordinates per control point otherwise.
void add_transposed_jacobian_times(const TriangularBasisValues& basis,
                                   const TriangularRationalJacobian& jacobian, int alpha,
                                   bool free_weights, const Eigen::Vector3d& f, VectorRef force);

/// Adds sum_alpha c_alpha J_alpha^T J_alpha of one point into an element block matrix laid out
/// in 4 x 4 blocks: block[(4 la + r) * 4 L + 4 lb + s] for the local B-splines la, lb
/// (local[i] is the local index of listed B-spline i, L the padded local count). Every entry is
/// c * (product of two factors), so the element matrix is exactly symmetric.
void add_free_weight_terms(const TriangularRationalJacobian& jacobian,
                           const std::array<double, 6>& coefficient, int count,
                           const std::vector<int>& local, int local_count,
                           std::vector<double>& block);

/// Scatters element e's block matrix (element_local B-splines) into a dense_block_pattern
/// matrix of the assembly pattern.
void scatter_free_weight_block(const AssemblyPattern& pattern, const SparseMatrix& block_pattern,
                               int element, int element_local, const std::vector<double>& block,
                               SparseMatrix& matrix);

/// Prepares `matrix` for accumulation into `pattern`'s entries: the pattern's structure with
/// zero values (its storage reused when it already has that structure), or an empty matrix of
/// the same size if `used` is false.
void reset_to_pattern(const SparseMatrix& pattern, bool used, SparseMatrix& matrix);

}  // namespace dnurbs
