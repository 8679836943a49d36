#pragma once
// Forward and backward substitution with a supernodal Cholesky factor L (A = L L^T) for a few
// right-hand sides stored node-major, the layout of the x, y, z columns of a step: the supernodal
// triangular solve of Chen, Davis, Hager & Rajamanickam (Algorithm 887: CHOLMOD, Supernodal Sparse
// Cholesky Factorization and Update/Downdate, ACM TOMS 35(3) 2008, section 3.2), blocked by four
// columns of each supernode and vectorized along the supernode's rows.
//
// CHOLMOD's own cholmod_super_lsolve / ltsolve hand every supernode to BLAS (dtrsm and dgemm):
// with 1 to 4 right-hand sides BLAS packs the supernode into a buffer before it multiplies, so
// the solve reads L about twice and pays a library call per supernode. Here every value of L is
// read once per substitution: on the 2-core machine a three-column solve takes 0.55-0.8 of
// CHOLMOD's (bench/floor/README.md).

#include <vector>

namespace dnurbs {

/// The most right-hand sides supernodal_solve takes in one pass.
inline constexpr int kSupernodalSolveMaxColumns = 4;

/// A supernodal factor L in CHOLMOD's layout (cholmod_factor with is_super set and int indices;
/// the arrays are CHOLMOD's super, pi, px, s and x, not copied). Supernode s holds the columns
/// [first_column[s], first_column[s + 1]) of L; their rows are row_index[row_start[s] ..
/// row_start[s + 1]), first the supernode's own columns in order, then the rows below it; the
/// values are a dense column-major rows x columns panel at values[value_start[s]] (the upper
/// triangle of its diagonal block is not read).
struct SupernodalFactor {
  int supernode_count = 0;
  const int* first_column = nullptr;  ///< supernode_count + 1 entries
  const int* row_start = nullptr;     ///< supernode_count + 1 entries
  const int* value_start = nullptr;   ///< supernode_count entries
  const int* row_index = nullptr;
  const double* values = nullptr;
  int largest_row_count = 0;  ///< max over s of row_start[s + 1] - row_start[s]
};

/// Solves L L^T Y = B in place: y holds B on entry and Y on return, n rows of `columns` values
/// each (row i at y[i columns .. i columns + columns), the rows in L's order, i.e. already
/// permuted), columns in 1..kSupernodalSolveMaxColumns. `workspace` grows to columns x
/// largest_row_count and is reused. `vectorize` = false keeps the generic x86-64 code even where
/// AVX2 and FMA are present (the tests compare the two). The result equals CHOLMOD's solve to
/// rounding (another order of the same sums).
void supernodal_solve(const SupernodalFactor& factor, int columns, double* y,
                      std::vector<double>& workspace, bool vectorize = true);

/// Whether supernodal_solve runs its AVX2 and FMA code on this processor.
bool supernodal_solve_vectorized();

}  // namespace dnurbs
