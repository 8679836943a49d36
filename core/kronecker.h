#pragma once
// The Kronecker layout of nodal models: when every node carries b coordinates (x, y, z: b = 3)
// that share one scalar matrix S (D-NURBS with fixed weights, snakes, grid surfaces), the
// velocity-space matrix is S (x) I_b with the coordinates grouped node by node, and the solvers
// work on S with b right-hand sides.

#include <optional>
#include <vector>

#include "core/sparse_matrix.h"

namespace dnurbs {

/// S (x) I_b: entry (i, j) of `scalar` (n by n) becomes the b diagonal entries (b i + c, b j + c),
/// c = 0..b-1, of the result (b n by b n, compressed). Throws Error if block_size < 1.
SparseMatrix kronecker_identity(const SparseMatrix& scalar, int block_size);

/// The nodes of a sorted list of fixed velocity indices when it consists of whole nodes (every
/// fixed node has all of its b coordinates b k .. b k + b - 1 fixed), ascending; nullopt if some
/// node is only partly fixed. Throws Error if block_size < 1.
std::optional<std::vector<int>> fixed_nodes(const std::vector<int>& fixed, int block_size);

}  // namespace dnurbs
