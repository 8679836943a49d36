#pragma once
// Elimination of fixed coordinates: the unknowns of a linear system that are held fixed are
// removed from it, so that only the free rows and columns are factored and solved.

#include <vector>

#include "dnurbs/core/sparse_matrix.h"

namespace dnurbs {

/// The free unknowns among `count`, given the fixed ones: free_index(k) is the position of
/// unknown k among the free ones (-1 if fixed), free_unknown(i) the inverse map.
class FreeCoordinates {
 public:
  FreeCoordinates() = default;
  /// `fixed` lists fixed unknowns in 0..count-1 (any order, repeats allowed). Throws Error
  /// naming an index out of range.
  FreeCoordinates(int count, const std::vector<int>& fixed);

  int count() const { return static_cast<int>(free_index_.size()); }
  int free_count() const { return static_cast<int>(free_list_.size()); }
  int free_index(int unknown) const { return free_index_[static_cast<size_t>(unknown)]; }
  int free_unknown(int i) const { return free_list_[static_cast<size_t>(i)]; }
  const std::vector<int>& free_unknowns() const { return free_list_; }

  /// The free rows and columns of `matrix` (count() square), in order: free_count() square,
  /// compressed. The matrix itself when nothing is fixed.
  SparseMatrix reduce(const SparseMatrix& matrix) const;

 private:
  std::vector<int> free_index_;
  std::vector<int> free_list_;
};

}  // namespace dnurbs
