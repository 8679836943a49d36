#pragma once
// The right-hand side of a step with fixed unknowns eliminated, in one pass: r -= K X + D V + M A
// on the free rows only, over the shared pattern of K, D and M (fixed rows are never touched; the
// columns of fixed unknowns still count, e.g. the stiffness coupling of a clamped border). Used by
// the integrators (dynamics/integrators/step_blocks.h) for the Kronecker-structured blocks of
// fixed-weight D-NURBS, where X, V, A are node by 3 (x, y, z columns of one scalar matrix).

#include <array>
#include <vector>

#include "dnurbs/core/sparse_matrix.h"

namespace dnurbs {

/// r(i, :) -= sum_m A_m(i, :) X_m for the free rows i of up to kMatrices square n by n sparse
/// matrices A_m, with X_m and r node-major n by `columns` arrays (row i at [i columns, (i + 1)
/// columns), the layout of a System vector of x, y, z triples when columns = 3).
///
/// The rows of every matrix are merged once (at construction) into one pattern over the free
/// rows with the values of each entry side by side, so that subtract() reads each column index
/// once for all matrices and each X_m row once per entry. Any matrix may be
/// unsymmetric (its rows are taken, not its columns) or empty (nullptr or no non-zeros: it adds
/// nothing). Rounding: the sum sum_m A_m(i, :) X_m is formed first and then subtracted, so r
/// differs from three separate products r -= A_0 X_0; r -= A_1 X_1; ... by rounding only (a few
/// 1e-16 relative to the largest term).
///
/// With three columns on an x86-64 processor with AVX2 and FMA (checked at run time), each
/// entry's x, y, z are multiplied four lanes at a time, with two entries in flight: on the
/// 2-core machine 1.6x (1e4 unknowns, in cache) to 1.9x (1e5, from memory) faster than the scalar
/// pass, which is compute-bound at its 12 flops per entry. The sums are the same to rounding.
class FreeRowProduct {
 public:
  static constexpr int kMatrices = 3;

  FreeRowProduct() = default;
  /// `matrices`: n by n each or nullptr; `free_rows`: distinct rows in 0..n-1, ascending;
  /// `columns`: 1..8; `vectorize`: false keeps the scalar pass (tests compare the two). Throws
  /// Error for a non-square matrix or sizes that differ, a row out of range or out of order, or
  /// columns outside 1..8.
  FreeRowProduct(const std::array<const SparseMatrix*, kMatrices>& matrices,
                 const std::vector<int>& free_rows, int columns, bool vectorize = true);

  int size() const { return size_; }
  int columns() const { return columns_; }
  int free_row_count() const { return static_cast<int>(rows_.size()); }
  /// Entries of the merged pattern (one per free row and column that some matrix has).
  int entry_count() const { return static_cast<int>(entry_column_.size()); }
  /// Whether subtract() multiplies four lanes at a time (three columns, AVX2 and FMA present).
  bool vectorized() const { return vectorized_; }

  /// r -= sum_m A_m X_m on the free rows; x[m] points to n * columns() values (nullptr: matrix m
  /// is skipped, as if X_m were zero); r to n * columns() values.
  void subtract(const std::array<const double*, kMatrices>& x, double* r) const;

 private:
  template <int Columns, int Mask>
  void subtract_rows(const std::array<const double*, kMatrices>& x, double* r) const;

  int size_ = 0;
  int columns_ = 0;
  bool vectorized_ = false;
  std::array<bool, kMatrices> present_{};  // matrix m has non-zeros
  std::vector<int> rows_;                  // the free rows
  std::vector<int> row_start_;             // entries of free row k: [row_start_[k], [k + 1])
  std::vector<int> entry_column_;
  // A_0(i, j), A_1(i, j) side by side per entry (stiffness and damping, read every step) and
  // A_2(i, j) apart (mass, read only with an acceleration), so that a pass without A_2 does not
  // stream its values.
  std::vector<double> pair_values_;
  std::vector<double> last_values_;
};

}  // namespace dnurbs
