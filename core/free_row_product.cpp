#include "dnurbs/core/free_row_product.h"

#include <algorithm>
#include <string>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

using RowMajorMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

constexpr int kMaxColumns = 8;

}  // namespace

FreeRowProduct::FreeRowProduct(const std::array<const SparseMatrix*, kMatrices>& matrices,
                               const std::vector<int>& free_rows, int columns)
    : columns_(columns), rows_(free_rows) {
  if (columns < 1 || columns > kMaxColumns) {
    throw make_error("free-row product: ", columns, " columns, must be 1..", kMaxColumns);
  }
  size_ = -1;
  std::array<RowMajorMatrix, kMatrices> rows_of;
  for (int m = 0; m < kMatrices; ++m) {
    const SparseMatrix* a = matrices[static_cast<size_t>(m)];
    if (a == nullptr) {
      continue;
    }
    if (a->rows() != a->cols() || (size_ >= 0 && a->rows() != size_)) {
      throw make_error("free-row product: matrix ", m, " is ", a->rows(), " by ", a->cols(),
                       size_ >= 0 ? ", the others " + std::to_string(size_) + " square"
                                  : std::string(", must be square"));
    }
    size_ = static_cast<int>(a->rows());
    present_[static_cast<size_t>(m)] = a->nonZeros() > 0;
    rows_of[static_cast<size_t>(m)] = *a;  // the rows of a, compressed
  }
  size_ = std::max(size_, 0);
  for (size_t k = 0; k < rows_.size(); ++k) {
    if (rows_[k] < 0 || rows_[k] >= size_ || (k > 0 && rows_[k] <= rows_[k - 1])) {
      throw make_error("free-row product: free row ", k, " is ", rows_[k],
                       ", rows must ascend within 0..", size_ - 1);
    }
  }
  // Merge the rows of the matrices: for each free row, the union of their columns (ascending)
  // with the value of every matrix at each (zero where it has no entry).
  row_start_.assign(1, 0);
  std::array<int, kMatrices> cursor{};
  std::array<int, kMatrices> end{};
  for (const int i : rows_) {
    for (int m = 0; m < kMatrices; ++m) {
      const RowMajorMatrix& a = rows_of[static_cast<size_t>(m)];
      const bool used = present_[static_cast<size_t>(m)];
      cursor[static_cast<size_t>(m)] = used ? a.outerIndexPtr()[i] : 0;
      end[static_cast<size_t>(m)] = used ? a.outerIndexPtr()[i + 1] : 0;
    }
    for (;;) {
      int column = size_;
      for (int m = 0; m < kMatrices; ++m) {
        const auto sm = static_cast<size_t>(m);
        if (cursor[sm] < end[sm]) {
          column = std::min(column, rows_of[sm].innerIndexPtr()[cursor[sm]]);
        }
      }
      if (column == size_) {
        break;
      }
      entry_column_.push_back(column);
      for (int m = 0; m < kMatrices; ++m) {
        const auto sm = static_cast<size_t>(m);
        double value = 0.0;
        if (cursor[sm] < end[sm] && rows_of[sm].innerIndexPtr()[cursor[sm]] == column) {
          value = rows_of[sm].valuePtr()[cursor[sm]];
          ++cursor[sm];
        }
        (m + 1 < kMatrices ? pair_values_ : last_values_).push_back(value);
      }
    }
    row_start_.push_back(static_cast<int>(entry_column_.size()));
  }
}

// One pass over the merged pattern; Columns = 0: columns_ at run time; Mask: bit m set if
// matrix m takes part (-1: those whose x[m] is not null, decided at run time).
template <int Columns, int Mask>
void FreeRowProduct::subtract_rows(const std::array<const double*, kMatrices>& x, double* r) const {
  const int k = Columns > 0 ? Columns : columns_;
  const int* column = entry_column_.data();
  const double* pairs = pair_values_.data();
  const double* last = last_values_.data();
  std::array<double, kMaxColumns> sum{};
  for (size_t f = 0; f < rows_.size(); ++f) {
    std::fill(sum.begin(), sum.begin() + k, 0.0);
    for (int p = row_start_[f]; p < row_start_[f + 1]; ++p) {
      const int j = column[p];
      const double* v = pairs + static_cast<ptrdiff_t>(p) * (kMatrices - 1);
      for (int m = 0; m < kMatrices; ++m) {
        const bool used = Mask >= 0 ? ((Mask >> m) & 1) != 0 : x[static_cast<size_t>(m)] != nullptr;
        if (used) {
          const double value = m + 1 < kMatrices ? v[m] : last[p];
          const double* xj = x[static_cast<size_t>(m)] + static_cast<ptrdiff_t>(j) * k;
          for (int c = 0; c < k; ++c) {
            sum[static_cast<size_t>(c)] += value * xj[c];
          }
        }
      }
    }
    double* ri = r + static_cast<ptrdiff_t>(rows_[f]) * k;
    for (int c = 0; c < k; ++c) {
      ri[c] -= sum[static_cast<size_t>(c)];
    }
  }
}

void FreeRowProduct::subtract(const std::array<const double*, kMatrices>& x, double* r) const {
  int mask = 0;
  for (int m = 0; m < kMatrices; ++m) {
    if (present_[static_cast<size_t>(m)] && x[static_cast<size_t>(m)] != nullptr) {
      mask |= 1 << m;
    }
  }
  // The common cases unrolled (x, y, z columns; K alone, K and D, K, D and M); any other
  // combination at run time.
  if (columns_ == 3 && mask == 1) {
    subtract_rows<3, 1>(x, r);
  } else if (columns_ == 3 && mask == 3) {
    subtract_rows<3, 3>(x, r);
  } else if (columns_ == 3 && mask == 7) {
    subtract_rows<3, 7>(x, r);
  } else if (mask != 0) {
    subtract_rows<0, -1>({(mask & 1) != 0 ? x[0] : nullptr, (mask & 2) != 0 ? x[1] : nullptr,
                          (mask & 4) != 0 ? x[2] : nullptr},
                         r);
  }
}

}  // namespace dnurbs
