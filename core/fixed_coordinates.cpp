#include "dnurbs/core/fixed_coordinates.h"

#include "dnurbs/core/error.h"

namespace dnurbs {

FreeCoordinates::FreeCoordinates(int count, const std::vector<int>& fixed)
    : free_index_(static_cast<size_t>(count), 0) {
  for (const int unknown : fixed) {
    if (unknown < 0 || unknown >= count) {
      throw make_error("fixed unknown ", unknown, " is outside 0..", count - 1);
    }
    free_index_[static_cast<size_t>(unknown)] = -1;
  }
  for (size_t k = 0; k < free_index_.size(); ++k) {
    if (free_index_[k] >= 0) {
      free_index_[k] = static_cast<int>(free_list_.size());
      free_list_.push_back(static_cast<int>(k));
    }
  }
}

SparseMatrix FreeCoordinates::reduce(const SparseMatrix& matrix) const {
  if (free_count() == matrix.rows()) {
    return matrix;
  }
  SparseMatrix result(free_count(), free_count());
  if (free_count() == 0) {
    // Eigen's makeCompressed reads one past the outer index of a reserved 0 x 0 matrix.
    return result;
  }
  Eigen::VectorXi sizes = Eigen::VectorXi::Zero(free_count());
  for (Eigen::Index j = 0; j < matrix.outerSize(); ++j) {
    const int fj = free_index(static_cast<int>(j));
    if (fj < 0) {
      continue;
    }
    for (SparseMatrix::InnerIterator it(matrix, j); it; ++it) {
      sizes[fj] += free_index(static_cast<int>(it.row())) >= 0 ? 1 : 0;
    }
  }
  result.reserve(sizes);
  for (Eigen::Index j = 0; j < matrix.outerSize(); ++j) {
    const int fj = free_index(static_cast<int>(j));
    if (fj < 0) {
      continue;
    }
    for (SparseMatrix::InnerIterator it(matrix, j); it; ++it) {
      const int fi = free_index(static_cast<int>(it.row()));
      if (fi >= 0) {
        result.insert(fi, fj) = it.value();
      }
    }
  }
  result.makeCompressed();
  return result;
}

}  // namespace dnurbs
