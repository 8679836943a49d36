#pragma once
// The sparse matrix type of every dnurbs API: column-major, double, int indices.

#include <Eigen/SparseCore>

namespace dnurbs {

/// Column-major sparse matrix used by every dynamics and constraint API.
using SparseMatrix = Eigen::SparseMatrix<double>;

}  // namespace dnurbs
