#include "dnurbs/core/supernodal_solve.h"

#include <array>
#include <cstddef>

#include "dnurbs/core/error.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define DNURBS_SUPERNODAL_SOLVE_AVX2 1
#endif

namespace dnurbs {

namespace {

// One supernode: `rows` x `columns` values, column-major; the first `columns` rows are the
// supernode's own columns (L's rows first .. first + columns - 1), the others `below`.
struct Panel {
  const double* values;
  const int* below;
  int first;
  int columns;
  int rows;

  const double* column(int j) const { return values + static_cast<ptrdiff_t>(j) * rows; }
};

Panel panel(const SupernodalFactor& f, int s) {
  const int first = f.first_column[s];
  const int columns = f.first_column[s + 1] - first;
  const int rows = f.row_start[s + 1] - f.row_start[s];
  return Panel{f.values + f.value_start[s], f.row_index + f.row_start[s] + columns, first, columns,
               rows};
}

// The bodies below are inlined into a generic and an AVX2 entry point, so that the compiler
// vectorizes their loops along the panel's rows for each. The right-hand sides of a panel are
// gathered into `t`, one array of `rows` per column (t + c rows): contiguous like L's columns.

// The panel's own rows of y into t (one array of `rows` per column) and back.
template <int K>
__attribute__((always_inline)) inline void gather_own_rows(const Panel& p, const double* y,
                                                           double* t) {
  for (int c = 0; c < K; ++c) {
    double* tc = t + static_cast<ptrdiff_t>(c) * p.rows;
    for (int i = 0; i < p.columns; ++i) {
      tc[i] = y[static_cast<ptrdiff_t>(p.first + i) * K + c];
    }
  }
}

template <int K>
__attribute__((always_inline)) inline void scatter_own_rows(const Panel& p, const double* t,
                                                            double* y) {
  for (int c = 0; c < K; ++c) {
    const double* tc = t + static_cast<ptrdiff_t>(c) * p.rows;
    for (int i = 0; i < p.columns; ++i) {
      y[static_cast<ptrdiff_t>(p.first + i) * K + c] = tc[i];
    }
  }
}

// Forward substitution with one panel (L y = b restricted to its columns): the diagonal block's
// triangle four columns at a time, each group then subtracted from all rows below it in one pass
// over those four columns of L; the rows below the panel receive their sums by scatter.
template <int K>
__attribute__((always_inline)) inline void forward_panel(const Panel& p, double* y, double* t) {
  const int rows = p.rows;
  gather_own_rows<K>(p, y, t);
  for (int c = 0; c < K; ++c) {
    double* tc = t + static_cast<ptrdiff_t>(c) * rows;
    for (int i = p.columns; i < rows; ++i) {
      tc[i] = 0.0;
    }
  }
  int j = 0;
  for (; j + 4 <= p.columns; j += 4) {
    const double* l0 = p.column(j);
    const double* l1 = p.column(j + 1);
    const double* l2 = p.column(j + 2);
    const double* l3 = p.column(j + 3);
    for (int c = 0; c < K; ++c) {
      double* tc = t + static_cast<ptrdiff_t>(c) * rows;
      const double x0 = tc[j] / l0[j];
      const double x1 = (tc[j + 1] - l0[j + 1] * x0) / l1[j + 1];
      const double x2 = (tc[j + 2] - l0[j + 2] * x0 - l1[j + 2] * x1) / l2[j + 2];
      const double x3 = (tc[j + 3] - l0[j + 3] * x0 - l1[j + 3] * x1 - l2[j + 3] * x2) / l3[j + 3];
      tc[j] = x0;
      tc[j + 1] = x1;
      tc[j + 2] = x2;
      tc[j + 3] = x3;
      for (int i = j + 4; i < rows; ++i) {
        tc[i] -= l0[i] * x0 + l1[i] * x1 + l2[i] * x2 + l3[i] * x3;
      }
    }
  }
  for (; j < p.columns; ++j) {
    const double* l = p.column(j);
    for (int c = 0; c < K; ++c) {
      double* tc = t + static_cast<ptrdiff_t>(c) * rows;
      const double x = tc[j] / l[j];
      tc[j] = x;
      for (int i = j + 1; i < rows; ++i) {
        tc[i] -= l[i] * x;
      }
    }
  }
  scatter_own_rows<K>(p, t, y);
  for (int c = 0; c < K; ++c) {
    const double* tc = t + static_cast<ptrdiff_t>(c) * rows;
    for (int i = p.columns; i < rows; ++i) {
      y[static_cast<ptrdiff_t>(p.below[i - p.columns]) * K + c] += tc[i];
    }
  }
}

// Backward substitution with one panel (L^T x = y restricted to its columns), its columns from
// the last: the rows below hold solved values (gathered), each group of four columns takes its
// dot products with everything after it in one pass, then its 4 x 4 triangle.
template <int K>
__attribute__((always_inline)) inline void backward_panel(const Panel& p, double* y, double* t) {
  const int rows = p.rows;
  gather_own_rows<K>(p, y, t);
  for (int c = 0; c < K; ++c) {
    double* tc = t + static_cast<ptrdiff_t>(c) * rows;
    for (int i = p.columns; i < rows; ++i) {
      tc[i] = y[static_cast<ptrdiff_t>(p.below[i - p.columns]) * K + c];
    }
  }
  int j = p.columns;
  for (; j >= 4; j -= 4) {
    const int b = j - 4;
    const std::array<const double*, 4> l{p.column(b), p.column(b + 1), p.column(b + 2),
                                         p.column(b + 3)};
    std::array<std::array<double, K>, 4> dot{};
    for (int i = j; i < rows; ++i) {
      for (int q = 0; q < 4; ++q) {
        for (int c = 0; c < K; ++c) {
          dot[static_cast<size_t>(q)][static_cast<size_t>(c)] +=
              l[static_cast<size_t>(q)][i] * t[static_cast<ptrdiff_t>(c) * rows + i];
        }
      }
    }
    for (int c = 0; c < K; ++c) {
      double* tc = t + static_cast<ptrdiff_t>(c) * rows;
      const auto& d = dot;
      const auto sc = static_cast<size_t>(c);
      const double x3 = (tc[b + 3] - d[3][sc]) / l[3][b + 3];
      const double x2 = (tc[b + 2] - d[2][sc] - l[2][b + 3] * x3) / l[2][b + 2];
      const double x1 = (tc[b + 1] - d[1][sc] - l[1][b + 2] * x2 - l[1][b + 3] * x3) / l[1][b + 1];
      const double x0 =
          (tc[b] - d[0][sc] - l[0][b + 1] * x1 - l[0][b + 2] * x2 - l[0][b + 3] * x3) / l[0][b];
      tc[b] = x0;
      tc[b + 1] = x1;
      tc[b + 2] = x2;
      tc[b + 3] = x3;
    }
  }
  for (--j; j >= 0; --j) {
    const double* l = p.column(j);
    for (int c = 0; c < K; ++c) {
      double* tc = t + static_cast<ptrdiff_t>(c) * rows;
      double dot = 0.0;
      for (int i = j + 1; i < rows; ++i) {
        dot += l[i] * tc[i];
      }
      tc[j] = (tc[j] - dot) / l[j];
    }
  }
  scatter_own_rows<K>(p, t, y);
}

template <int K>
__attribute__((always_inline)) inline void solve_body(const SupernodalFactor& f, double* y,
                                                      double* t) {
  for (int s = 0; s < f.supernode_count; ++s) {
    forward_panel<K>(panel(f, s), y, t);
  }
  for (int s = f.supernode_count - 1; s >= 0; --s) {
    backward_panel<K>(panel(f, s), y, t);
  }
}

template <int K>
void solve_generic(const SupernodalFactor& f, double* y, double* t) {
  solve_body<K>(f, y, t);
}

#ifdef DNURBS_SUPERNODAL_SOLVE_AVX2
template <int K>
__attribute__((target("avx2,fma"))) void solve_avx2(const SupernodalFactor& f, double* y,
                                                    double* t) {
  solve_body<K>(f, y, t);
}
#endif

template <int K>
void solve_columns(const SupernodalFactor& f, double* y, double* t, bool vectorize) {
#ifdef DNURBS_SUPERNODAL_SOLVE_AVX2
  if (vectorize && supernodal_solve_vectorized()) {
    solve_avx2<K>(f, y, t);
    return;
  }
#else
  static_cast<void>(vectorize);
#endif
  solve_generic<K>(f, y, t);
}

}  // namespace

bool supernodal_solve_vectorized() {
#ifdef DNURBS_SUPERNODAL_SOLVE_AVX2
  static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return has;
#else
  return false;
#endif
}

void supernodal_solve(const SupernodalFactor& factor, int columns, double* y,
                      std::vector<double>& workspace, bool vectorize) {
  if (columns < 1 || columns > kSupernodalSolveMaxColumns) {
    throw make_error("supernodal solve: ", columns, " right-hand sides, must be 1..",
                     kSupernodalSolveMaxColumns);
  }
  const auto size = static_cast<size_t>(columns) * static_cast<size_t>(factor.largest_row_count);
  if (workspace.size() < size) {
    workspace.resize(size);
  }
  double* t = workspace.data();
  switch (columns) {
    case 1:
      solve_columns<1>(factor, y, t, vectorize);
      break;
    case 2:
      solve_columns<2>(factor, y, t, vectorize);
      break;
    case 3:
      solve_columns<3>(factor, y, t, vectorize);
      break;
    default:
      solve_columns<4>(factor, y, t, vectorize);
  }
}

}  // namespace dnurbs
