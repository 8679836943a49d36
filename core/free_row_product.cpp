#include "dnurbs/core/free_row_product.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define DNURBS_FREE_ROW_PRODUCT_AVX2 1
#endif

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

using RowMajorMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

constexpr int kMaxColumns = 8;

// The arrays of one merged pattern, as the vectorized kernel reads them.
struct MergedRows {
  const int* rows;
  const int* row_start;
  const int* column;
  const double* pairs;  // A_0, A_1 of each entry side by side
  const double* last;   // A_2 of each entry
  size_t row_count;
  int size;
};

#ifdef DNURBS_FREE_ROW_PRODUCT_AVX2

bool cpu_has_avx2_fma() {
  static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return has;
}

// The three accumulators of one entry stream, one per matrix.
struct Sums {
  __m256d a0;
  __m256d a1;
  __m256d a2;
};

// x, y, z of a node and one more lane; masked to the three for the last node of the array.
template <bool kLastNode>
__attribute__((target("avx2,fma"), always_inline)) inline __m256d load_node(const double* node) {
  if constexpr (kLastNode) {
    return _mm256_maskload_pd(node, _mm256_set_epi64x(0, -1, -1, -1));
  } else {
    return _mm256_loadu_pd(node);
  }
}

// One entry p of up to three matrices (Mask bit k: matrix k) into `sums`: the x, y, z of node j
// read as four doubles (the fourth lane, the next node's x, is never used); for the last node,
// whose fourth lane lies past the array, a masked load.
template <int Mask, bool kLastNode>
__attribute__((target("avx2,fma"), always_inline)) inline void add_entry(
    const MergedRows& m, const std::array<const double*, 3>& x, int p, Sums& sums) {
  const ptrdiff_t offset = static_cast<ptrdiff_t>(m.column[p]) * 3;
  if ((Mask & 1) != 0) {
    sums.a0 = _mm256_fmadd_pd(_mm256_broadcast_sd(m.pairs + static_cast<ptrdiff_t>(p) * 2),
                              load_node<kLastNode>(x[0] + offset), sums.a0);
  }
  if ((Mask & 2) != 0) {
    sums.a1 = _mm256_fmadd_pd(_mm256_broadcast_sd(m.pairs + static_cast<ptrdiff_t>(p) * 2 + 1),
                              load_node<kLastNode>(x[1] + offset), sums.a1);
  }
  if ((Mask & 4) != 0) {
    sums.a2 = _mm256_fmadd_pd(_mm256_broadcast_sd(m.last + p), load_node<kLastNode>(x[2] + offset),
                              sums.a2);
  }
}

// r(i, :) -= sum_m A_m(i, :) X_m for three columns, four lanes at a time: two entries in flight
// with their own accumulators (the fused multiply-adds of one accumulator wait on each other).
// The sums are those of the scalar kernel in another order and with fused rounding.
template <int Mask>
__attribute__((target("avx2,fma"))) void subtract_rows_avx2(const MergedRows& m,
                                                            const std::array<const double*, 3>& x,
                                                            double* r) {
  for (size_t f = 0; f < m.row_count; ++f) {
    Sums even{_mm256_setzero_pd(), _mm256_setzero_pd(), _mm256_setzero_pd()};
    Sums odd = even;
    int p = m.row_start[f];
    const int end = m.row_start[f + 1];
    // Columns ascend: only a row's last entry can be the last node.
    const int unmasked = end > p && m.column[end - 1] == m.size - 1 ? end - 1 : end;
    for (; p + 2 <= unmasked; p += 2) {
      add_entry<Mask, false>(m, x, p, even);
      add_entry<Mask, false>(m, x, p + 1, odd);
    }
    if (p < unmasked) {
      add_entry<Mask, false>(m, x, p++, even);
    }
    if (p < end) {
      add_entry<Mask, true>(m, x, p, odd);
    }
    const __m256d total =
        _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(even.a0, odd.a0), _mm256_add_pd(even.a1, odd.a1)),
                      _mm256_add_pd(even.a2, odd.a2));
    alignas(32) std::array<double, 4> lanes{};
    _mm256_store_pd(lanes.data(), total);
    double* ri = r + static_cast<ptrdiff_t>(m.rows[f]) * 3;
    for (int c = 0; c < 3; ++c) {
      ri[c] -= lanes[static_cast<size_t>(c)];
    }
  }
}

#endif

}  // namespace

FreeRowProduct::FreeRowProduct(const std::array<const SparseMatrix*, kMatrices>& matrices,
                               const std::vector<int>& free_rows, int columns, bool vectorize)
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
#ifdef DNURBS_FREE_ROW_PRODUCT_AVX2
  vectorized_ = vectorize && columns_ == 3 && cpu_has_avx2_fma();
#else
  static_cast<void>(vectorize);
#endif
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
#ifdef DNURBS_FREE_ROW_PRODUCT_AVX2
  if (vectorized_ && (mask == 1 || mask == 3 || mask == 7)) {
    const MergedRows merged{rows_.data(),
                            row_start_.data(),
                            entry_column_.data(),
                            pair_values_.data(),
                            last_values_.data(),
                            rows_.size(),
                            size_};
    if (mask == 1) {
      subtract_rows_avx2<1>(merged, x, r);
    } else if (mask == 3) {
      subtract_rows_avx2<3>(merged, x, r);
    } else {
      subtract_rows_avx2<7>(merged, x, r);
    }
    return;
  }
#endif
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
