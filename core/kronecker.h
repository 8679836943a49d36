#pragma once
// The Kronecker layout of nodal models: when every node carries b coordinates (x, y, z: b = 3)
// that share one scalar matrix S (D-NURBS with fixed weights, snakes, grid surfaces), the
// velocity-space matrix is S (x) I_b with the coordinates grouped node by node, and the solvers
// work on S with b right-hand sides.

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/core/sparse_matrix.h"

namespace dnurbs {

/// S (x) I_b: entry (i, j) of `scalar` (n by n) becomes the b diagonal entries (b i + c, b j + c),
/// c = 0..b-1, of the result (b n by b n, compressed). Throws Error if block_size < 1.
SparseMatrix kronecker_identity(const SparseMatrix& scalar, int block_size);

/// x^T (S (x) I_b) x = sum_ij S_ij <x_i, x_j> with x node-major (node i's b values at [b i, b i +
/// b)), in one pass over S (n by n) without forming S (x) I_b or a temporary: the kinetic energy
/// (1/2) qd^T M qd and the potential energy (1/2) q^T K q of Kronecker-structured models. Throws
/// Error if S is not square, x's size is not b n, or block_size < 1.
double kronecker_quadratic_form(const SparseMatrix& scalar,
                                const Eigen::Ref<const Eigen::VectorXd>& x, int block_size);

/// (x - y)^T (S (x) I_b) (x - y) in one pass over S without forming x - y: the energy of a
/// displacement from a reference state y. Throws Error as kronecker_quadratic_form, or if y's size
/// differs from x's.
double kronecker_quadratic_form_of_difference(const SparseMatrix& scalar,
                                              const Eigen::Ref<const Eigen::VectorXd>& x,
                                              const Eigen::Ref<const Eigen::VectorXd>& y,
                                              int block_size);

/// The nodes of a sorted list of fixed velocity indices when it consists of whole nodes (every
/// fixed node has all of its b coordinates b k .. b k + b - 1 fixed), ascending; nullopt if some
/// node is only partly fixed. Throws Error if block_size < 1.
std::optional<std::vector<int>> fixed_nodes(const std::vector<int>& fixed, int block_size);

}  // namespace dnurbs
