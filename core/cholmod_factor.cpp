#include "dnurbs/core/cholmod_factor.h"

#include <cholmod.h>
#include <dlfcn.h>

#include <algorithm>
#include <mutex>
#include <utility>
#include <vector>

#include "dnurbs/core/error.h"

namespace dnurbs {

bool limit_blas_to_one_thread() {
  static bool found = false;
  static std::once_flag once;
  std::call_once(once, [] {
    // OpenBLAS exports both names (goto_set_num_threads is its GotoBLAS-era alias); the symbols
    // are searched in the libraries already loaded (libcholmod pulls in libblas.so.3).
    for (const char* name : {"openblas_set_num_threads", "goto_set_num_threads"}) {
      void* symbol = dlsym(RTLD_DEFAULT, name);
      if (symbol != nullptr) {
        using SetThreads = void (*)(int);
        reinterpret_cast<SetThreads>(symbol)(1);
        found = true;
        break;
      }
    }
  });
  return found;
}

namespace {

// Debian's libcholmod is built with OpenMP and some loops of its supernodal factorization carry
// "num_threads(CHOLMOD_OMP_NUM_THREADS)" (4), which OMP_NUM_THREADS and omp_set_num_threads do
// not override: every factorization wakes 3 extra libgomp threads that then spin. Measured by
// bench/solver on the 2-core machine, this made the factorization 2.4-6x slower than with
// OMP_THREAD_LIMIT=1 (1024 unknowns: 11.3 ms against 1.9 ms; 1e4: 158 ms against 40 ms). Setting
// max-active-levels to 0
// makes every parallel region inactive (one thread) without an environment variable; it is a
// process-wide setting in libgomp, so it is held only while a CHOLMOD call runs and restored
// after. The functions are looked up in the loaded libgomp (none: nothing to do).
class SerialOpenMp {
 public:
  SerialOpenMp() {
    static const Functions functions = find();
    functions_ = &functions;
    if (functions.set != nullptr && functions.get != nullptr) {
      saved_ = functions.get();
      functions.set(0);
    }
  }
  ~SerialOpenMp() {
    if (functions_->set != nullptr && functions_->get != nullptr) {
      functions_->set(saved_);
    }
  }
  SerialOpenMp(const SerialOpenMp&) = delete;
  SerialOpenMp& operator=(const SerialOpenMp&) = delete;

 private:
  struct Functions {
    int (*get)() = nullptr;
    void (*set)(int) = nullptr;
  };
  static Functions find() {
    Functions f;
    f.get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
    f.set = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
    return f;
  }
  const Functions* functions_ = nullptr;
  int saved_ = 0;
};

const char* cholmod_status_name(int status) {
  switch (status) {
    case CHOLMOD_OUT_OF_MEMORY:
      return "out of memory";
    case CHOLMOD_TOO_LARGE:
      return "problem too large";
    case CHOLMOD_INVALID:
      return "invalid input";
    case CHOLMOD_NOT_POSDEF:
      return "matrix not positive definite";
    default:
      return "failure";
  }
}

// A cholmod_sparse header over an Eigen matrix's arrays (no copy). stype -1: CHOLMOD reads the
// lower triangle only.
cholmod_sparse wrap_lower(const CholmodFactor::SparseMatrix& a) {
  cholmod_sparse header{};
  header.nrow = static_cast<size_t>(a.rows());
  header.ncol = static_cast<size_t>(a.cols());
  header.nzmax = static_cast<size_t>(a.outerIndexPtr()[a.cols()]);
  // CHOLMOD's API takes non-const pointers; it does not write to an input matrix.
  header.p = const_cast<int*>(a.outerIndexPtr());
  header.i = const_cast<int*>(a.innerIndexPtr());
  header.nz = const_cast<int*>(a.innerNonZeroPtr());
  header.x = const_cast<double*>(a.valuePtr());
  header.stype = -1;
  header.itype = CHOLMOD_INT;
  header.xtype = CHOLMOD_REAL;
  header.dtype = CHOLMOD_DOUBLE;
  header.sorted = 1;  // Eigen keeps the inner indices of every column increasing
  header.packed = a.isCompressed() ? 1 : 0;
  return header;
}

// A cholmod_dense header over caller memory: rows by columns, leading dimension `stride`.
cholmod_dense wrap_dense(double* data, size_t rows, size_t columns, size_t stride) {
  cholmod_dense header{};
  header.nrow = rows;
  header.ncol = columns;
  header.nzmax = stride * columns;
  header.d = stride;
  header.x = data;
  header.xtype = CHOLMOD_REAL;
  header.dtype = CHOLMOD_DOUBLE;
  return header;
}

}  // namespace

struct CholmodFactor::State {
  TriangularSolve triangular_solve = TriangularSolve::kPanels;
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  bool factored = false;
  std::vector<int> permutation;          // P: row k of L is row permutation[k] of A
  std::vector<int> inverse_permutation;  // row i of A is row inverse_permutation[i] of L
  // Supernodal solve workspace: Y = P B (n by k), node-major for supernodal_solve (k <= 4) or
  // column-major with CHOLMOD's E (k by maxesize) for wider B; supernodal_solve's panel buffer.
  std::vector<double> y, e, panel;
  int largest_supernode_rows = -1;  // of the analyzed factor; -1: not yet counted
  // Simplicial solve workspaces (after a rank update), one set per right-hand-side width.
  struct SimplicialWorkspace {
    Eigen::Index columns = 0;
    cholmod_dense* x = nullptr;
    cholmod_dense* y = nullptr;
    cholmod_dense* e = nullptr;
  };
  std::vector<SimplicialWorkspace> simplicial;
  // Rank-update scratch: C permuted into L's row order.
  std::vector<int> c_columns, c_rows;
  std::vector<double> c_values;
  std::vector<std::pair<int, double>> c_column;

  State() {
    cholmod_start(&common);
    common.print = 0;  // errors are reported as dnurbs::Error, not printed
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.quick_return_if_not_posdef = 1;
  }
  ~State() {
    free_simplicial_workspaces();
    cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
  State(const State&) = delete;
  State& operator=(const State&) = delete;

  void free_simplicial_workspaces() {
    for (SimplicialWorkspace& w : simplicial) {
      cholmod_free_dense(&w.x, &common);
      cholmod_free_dense(&w.y, &common);
      cholmod_free_dense(&w.e, &common);
    }
    simplicial.clear();
  }

  void check(bool ok, const char* step) const {
    if (!ok || common.status < CHOLMOD_OK) {
      throw make_error("CHOLMOD ", step, " failed: ", cholmod_status_name(common.status),
                       " (status ", common.status, ")");
    }
  }

  void keep_permutation() {
    largest_supernode_rows = -1;
    const auto n = static_cast<size_t>(factor->n);
    const int* perm = static_cast<const int*>(factor->Perm);
    permutation.resize(n);
    inverse_permutation.resize(n);
    for (size_t k = 0; k < n; ++k) {
      permutation[k] = factor->ordering == CHOLMOD_NATURAL ? static_cast<int>(k) : perm[k];
      inverse_permutation[static_cast<size_t>(permutation[k])] = static_cast<int>(k);
    }
  }

  // Symbolic supernodal analysis with the ordering already chosen (after a rank update turned
  // the factor simplicial): no new ordering search, only the elimination tree and supernodes.
  void reanalyze_with_kept_ordering(cholmod_sparse* a) {
    const int saved_methods = common.nmethods;
    const int saved_ordering = common.method[0].ordering;
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_GIVEN;
    std::vector<int> given = permutation;
    cholmod_free_factor(&factor, &common);
    factor = cholmod_analyze_p(a, given.data(), nullptr, 0, &common);
    common.nmethods = saved_methods;
    common.method[0].ordering = saved_ordering;
    check(factor != nullptr, "analysis");
    keep_permutation();
  }

  // The first pivot <= 0 of a simplicial L D L^T factor (-1 if none): a downdate may leave one.
  long first_nonpositive_pivot() const {
    if (factor->is_super || factor->is_ll) {
      return -1;
    }
    const int* column_start = static_cast<const int*>(factor->p);
    const double* values = static_cast<const double*>(factor->x);
    for (size_t j = 0; j < factor->n; ++j) {
      if (!(values[column_start[j]] > 0.0)) {
        return static_cast<long>(j);
      }
    }
    return -1;
  }

  SupernodalFactor supernodal_view() {
    const auto count = static_cast<int>(factor->nsuper);
    const int* row_start = static_cast<const int*>(factor->pi);
    if (largest_supernode_rows < 0) {
      largest_supernode_rows = 0;
      for (int s = 0; s < count; ++s) {
        largest_supernode_rows = std::max(largest_supernode_rows, row_start[s + 1] - row_start[s]);
      }
    }
    return SupernodalFactor{count,
                            static_cast<const int*>(factor->super),
                            row_start,
                            static_cast<const int*>(factor->px),
                            static_cast<const int*>(factor->s),
                            static_cast<const double*>(factor->x),
                            largest_supernode_rows};
  }

  void solve_supernodal(Eigen::Ref<Eigen::MatrixXd> b);
  void solve_simplicial(Eigen::Ref<Eigen::MatrixXd> b);
};

CholmodFactor::CholmodFactor(TriangularSolve solve) : state_(std::make_unique<State>()) {
  state_->triangular_solve = solve;
  limit_blas_to_one_thread();
}
CholmodFactor::~CholmodFactor() = default;
CholmodFactor::CholmodFactor(CholmodFactor&& other) noexcept = default;
CholmodFactor& CholmodFactor::operator=(CholmodFactor&& other) noexcept = default;

void CholmodFactor::analyze(const SparseMatrix& a) {
  if (a.rows() != a.cols()) {
    throw make_error("CHOLMOD analysis: the matrix is ", a.rows(), " by ", a.cols(),
                     ", must be square");
  }
  State& s = *state_;
  cholmod_sparse wrapped = wrap_lower(a);
  s.factored = false;
  s.free_simplicial_workspaces();
  cholmod_free_factor(&s.factor, &s.common);
  const SerialOpenMp serial;
  s.factor = cholmod_analyze(&wrapped, &s.common);
  s.check(s.factor != nullptr, "analysis");
  s.keep_permutation();
}

void CholmodFactor::factorize(const SparseMatrix& a) {
  State& s = *state_;
  if (s.factor == nullptr) {
    analyze(a);
  }
  if (a.rows() != static_cast<Eigen::Index>(s.factor->n) || a.cols() != a.rows()) {
    throw make_error("CHOLMOD factorization: the matrix is ", a.rows(), " by ", a.cols(),
                     ", the analyzed one ", s.factor->n, " by ", s.factor->n);
  }
  const SerialOpenMp serial;
  cholmod_sparse wrapped = wrap_lower(a);
  s.factored = false;
  if (!s.factor->is_super) {
    s.free_simplicial_workspaces();
    s.reanalyze_with_kept_ordering(&wrapped);
  }
  const int ok = cholmod_factorize(&wrapped, s.factor, &s.common);
  if (s.common.status == CHOLMOD_NOT_POSDEF) {
    const auto pivot = static_cast<size_t>(s.factor->minor);
    throw make_error("the matrix is not positive definite: CHOLMOD's Cholesky pivot ", pivot,
                     " of ", s.factor->n, " (column ", s.permutation[pivot],
                     " of the matrix) is not positive");
  }
  s.check(ok != 0, "factorization");
  s.factored = true;
}

void CholmodFactor::State::solve_supernodal(Eigen::Ref<Eigen::MatrixXd> b) {
  const Eigen::Index n = b.rows();
  const Eigen::Index k = b.cols();
  const auto nk = static_cast<size_t>(n * k);
  if (y.size() < nk) {
    y.resize(nk);
  }
  if (triangular_solve == TriangularSolve::kPanels && k <= kSupernodalSolveMaxColumns) {
    // Y = P B node-major, L \ Y and L^T \ Y reading each value of L once (supernodal_solve.h),
    // then B = P^T Y.
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Index row = permutation[static_cast<size_t>(i)];
      for (Eigen::Index c = 0; c < k; ++c) {
        y[static_cast<size_t>(i * k + c)] = b(row, c);
      }
    }
    supernodal_solve(supernodal_view(), static_cast<int>(k), y.data(), panel);
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Index row = permutation[static_cast<size_t>(i)];
      for (Eigen::Index c = 0; c < k; ++c) {
        b(row, c) = y[static_cast<size_t>(i * k + c)];
      }
    }
    return;
  }
  const size_t e_size = std::max<size_t>(1, static_cast<size_t>(k) * factor->maxesize);
  if (e.size() < e_size) {
    e.resize(e_size);
  }
  // Wider B (or kBlas): Y = P B, then L \ Y and L^T \ Y with CHOLMOD's supernodal triangular solves
  // (dense BLAS on each supernode), then B = P^T Y.
  for (Eigen::Index c = 0; c < k; ++c) {
    double* column = y.data() + c * n;
    for (Eigen::Index i = 0; i < n; ++i) {
      column[i] = b(permutation[static_cast<size_t>(i)], c);
    }
  }
  cholmod_dense y_header =
      wrap_dense(y.data(), static_cast<size_t>(n), static_cast<size_t>(k), static_cast<size_t>(n));
  cholmod_dense e_header =
      wrap_dense(e.data(), static_cast<size_t>(k), factor->maxesize, static_cast<size_t>(k));
  e_header.nzmax = e_size;
  check(cholmod_super_lsolve(factor, &y_header, &e_header, &common) != 0, "forward solve");
  check(cholmod_super_ltsolve(factor, &y_header, &e_header, &common) != 0, "backward solve");
  for (Eigen::Index c = 0; c < k; ++c) {
    const double* column = y.data() + c * n;
    for (Eigen::Index i = 0; i < n; ++i) {
      b(permutation[static_cast<size_t>(i)], c) = column[i];
    }
  }
}

void CholmodFactor::State::solve_simplicial(Eigen::Ref<Eigen::MatrixXd> b) {
  const Eigen::Index k = b.cols();
  auto found = std::find_if(simplicial.begin(), simplicial.end(),
                            [k](const SimplicialWorkspace& w) { return w.columns == k; });
  if (found == simplicial.end()) {
    simplicial.push_back({k, nullptr, nullptr, nullptr});
    found = simplicial.end() - 1;
  }
  cholmod_dense b_header = wrap_dense(b.data(), static_cast<size_t>(b.rows()),
                                      static_cast<size_t>(k), static_cast<size_t>(b.outerStride()));
  // cholmod_solve2 reuses X, Y and E when their sizes match (one set per width k).
  check(cholmod_solve2(CHOLMOD_A, factor, &b_header, nullptr, &found->x, nullptr, &found->y,
                       &found->e, &common) != 0,
        "solve");
  b = Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(found->x->x), b.rows(), k);
}

// A writable Eigen::Ref is a view: passed by value, as Eigen documents.
// NOLINTNEXTLINE(performance-unnecessary-value-param)
void CholmodFactor::solve_in_place(Eigen::Ref<Eigen::MatrixXd> b) {
  State& s = *state_;
  if (!s.factored) {
    throw make_error("CHOLMOD solve: the matrix is not factored (or its factorization failed)");
  }
  if (b.rows() != static_cast<Eigen::Index>(s.factor->n)) {
    throw make_error("CHOLMOD solve: the right-hand side has ", b.rows(), " rows, the matrix ",
                     s.factor->n);
  }
  if (b.cols() == 0 || b.rows() == 0) {
    return;
  }
  if (s.factor->is_super) {
    s.solve_supernodal(b);
  } else {
    s.solve_simplicial(b);
  }
}

void CholmodFactor::rank_update(const SparseMatrix& c, bool downdate) {
  State& s = *state_;
  if (!s.factored) {
    throw make_error("CHOLMOD rank update: the matrix is not factored");
  }
  if (c.rows() != static_cast<Eigen::Index>(s.factor->n)) {
    throw make_error("CHOLMOD rank update: C has ", c.rows(), " rows, the matrix ", s.factor->n);
  }
  // C in L's row order (P C), each column sorted, as cholmod_updown requires.
  s.c_columns.assign(1, 0);
  s.c_rows.clear();
  s.c_values.clear();
  for (Eigen::Index j = 0; j < c.outerSize(); ++j) {
    s.c_column.clear();
    for (SparseMatrix::InnerIterator it(c, j); it; ++it) {
      s.c_column.emplace_back(s.inverse_permutation[static_cast<size_t>(it.row())], it.value());
    }
    std::sort(s.c_column.begin(), s.c_column.end());
    for (const auto& [row, value] : s.c_column) {
      s.c_rows.push_back(row);
      s.c_values.push_back(value);
    }
    s.c_columns.push_back(static_cast<int>(s.c_rows.size()));
  }
  cholmod_sparse header{};
  header.nrow = s.factor->n;
  header.ncol = static_cast<size_t>(c.cols());
  header.nzmax = std::max<size_t>(1, s.c_rows.size());
  header.p = s.c_columns.data();
  header.i = s.c_rows.data();
  header.x = s.c_values.data();
  header.itype = CHOLMOD_INT;
  header.xtype = CHOLMOD_REAL;
  header.dtype = CHOLMOD_DOUBLE;
  header.sorted = 1;
  header.packed = 1;
  if (s.factor->is_super) {
    s.free_simplicial_workspaces();
  }
  const SerialOpenMp serial;
  const int ok = cholmod_updown(downdate ? 0 : 1, &header, s.factor, &s.common);
  s.check(ok != 0, downdate ? "downdate" : "update");
  const long pivot = s.first_nonpositive_pivot();
  if (pivot >= 0) {
    s.factored = false;
    throw make_error("the downdated matrix is not positive definite: pivot ", pivot, " of ",
                     s.factor->n, " (column ", s.permutation[static_cast<size_t>(pivot)],
                     " of the matrix) is not positive");
  }
}

SupernodalFactor CholmodFactor::supernodal_factor() const {
  State& s = *state_;
  if (!s.factored || s.factor->is_super == 0) {
    throw make_error("CHOLMOD factor: ",
                     s.factored ? "not supernodal (after a rank update)" : "nothing is factored");
  }
  return s.supernodal_view();
}

int CholmodFactor::size() const {
  return state_->factor == nullptr ? 0 : static_cast<int>(state_->factor->n);
}

bool CholmodFactor::is_factored() const {
  return state_->factored;
}

bool CholmodFactor::is_supernodal() const {
  return state_->factor != nullptr && state_->factor->is_super != 0;
}

double CholmodFactor::factor_nonzeros() const {
  const cholmod_factor* f = state_->factor;
  if (f == nullptr) {
    return 0.0;
  }
  if (f->is_super) {
    return static_cast<double>(f->xsize);
  }
  const int* counts = static_cast<const int*>(f->nz);
  double total = 0.0;
  for (size_t j = 0; j < f->n; ++j) {
    total += counts[j];
  }
  return total;
}

double CholmodFactor::reciprocal_condition_estimate() const {
  State& s = *state_;
  if (!s.factored) {
    return 0.0;
  }
  return cholmod_rcond(s.factor, &s.common);
}

}  // namespace dnurbs
