#include "dnurbs/core/sparse_cholesky.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <vector>

#include "dnurbs/core/cholmod_factor.h"
#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

using SparseMatrix = SparseCholesky::SparseMatrix;

// Entries [begin, end) of column j of a (compressed or not).
std::pair<int, int> column_range(const SparseMatrix& a, Eigen::Index j) {
  const int begin = a.outerIndexPtr()[j];
  const int end = a.isCompressed() ? a.outerIndexPtr()[j + 1] : begin + a.innerNonZeroPtr()[j];
  return {begin, end};
}

void check_square(const SparseMatrix& a, const char* step) {
  if (a.rows() != a.cols()) {
    throw make_error("sparse Cholesky ", step, ": the matrix is ", a.rows(), " by ", a.cols(),
                     ", must be square");
  }
}

// Every stored entry must be finite (a NaN would pass a BLAS pivot test "ajj <= 0" unnoticed).
void check_finite(const SparseMatrix& a) {
  for (Eigen::Index j = 0; j < a.outerSize(); ++j) {
    const auto [begin, end] = column_range(a, j);
    for (int p = begin; p < end; ++p) {
      const double value = a.valuePtr()[p];
      if (!std::isfinite(value)) {
        throw make_error("sparse Cholesky: entry (", a.innerIndexPtr()[p], ", ", j,
                         ") of the matrix is ", value, ", must be finite");
      }
    }
  }
}

void check_finite(const Eigen::Ref<Eigen::MatrixXd>& b) {
  for (Eigen::Index c = 0; c < b.cols(); ++c) {
    for (Eigen::Index i = 0; i < b.rows(); ++i) {
      if (!std::isfinite(b(i, c))) {
        throw make_error("sparse Cholesky solve: entry (", i, ", ", c,
                         ") of the right-hand side is ", b(i, c), ", must be finite");
      }
    }
  }
}

}  // namespace

// Eigen's SimplicialLDLT (AMD ordering), with a solve that permutes into a kept workspace so
// that it allocates nothing (Eigen's own solve returns a new matrix).
class SparseCholesky::Simplicial {
 public:
  void analyze(const SparseMatrix& a) {
    ldlt_.analyzePattern(a);
    factored_ = false;
  }

  void factorize(const SparseMatrix& a) {
    factored_ = false;
    ldlt_.factorize(a);
    // Eigen stops at an exactly zero pivot (NumericalIssue) and accepts negative ones (it is an
    // L D L^T): either way the first pivot d_k <= 0 of the permuted matrix P A P^T names the
    // column Pinv(k) of A where the leading block stops being positive definite.
    const Eigen::VectorXd& d = ldlt_.vectorD();
    for (Eigen::Index k = 0; k < d.size(); ++k) {
      if (!(d[k] > 0.0)) {
        const Eigen::Index column =
            ldlt_.permutationPinv().size() > 0 ? ldlt_.permutationPinv().indices()[k] : k;
        throw make_error("the matrix is not positive definite: L D L^T pivot ", k, " of ", d.size(),
                         " (column ", column, " of the matrix) is ", d[k]);
      }
    }
    if (ldlt_.info() != Eigen::Success) {
      throw make_error("the matrix could not be factored by SimplicialLDLT");
    }
    inverse_d_ = ldlt_.vectorD().cwiseInverse();
    factored_ = true;
  }

  // x = P^T L^{-T} D^{-1} L^{-1} P b (the steps of Eigen's SimplicialCholeskyBase::_solve_impl),
  // with the k columns interleaved in a row-major workspace so that one pass over L serves all of
  // them (Eigen's own triangular solve makes one pass per column).
  // A writable Eigen::Ref is a view: passed by value, as Eigen documents.
  // NOLINTNEXTLINE(performance-unnecessary-value-param)
  void solve_in_place(Eigen::Ref<Eigen::MatrixXd> b) {
    const auto size = static_cast<size_t>(b.rows() * b.cols());
    if (work_.size() < size) {
      work_.resize(size);
    }
    switch (b.cols()) {
      case 1:
        solve_columns<1>(b);
        break;
      case 2:
        solve_columns<2>(b);
        break;
      case 3:
        solve_columns<3>(b);
        break;
      case 4:
        solve_columns<4>(b);
        break;
      default:
        solve_columns<Eigen::Dynamic>(b);
    }
  }

  bool factored() const { return factored_; }
  double factor_nonzeros() const {
    return static_cast<double>(ldlt_.matrixL().nestedExpression().nonZeros() +
                               ldlt_.vectorD().size());
  }
  double reciprocal_condition_estimate() const {
    if (!factored_ || ldlt_.vectorD().size() == 0) {
      return 0.0;
    }
    return ldlt_.vectorD().minCoeff() / ldlt_.vectorD().maxCoeff();
  }

 private:
  // Columns known at compile time (K > 0) unroll the innermost loop.
  template <int K>
  void solve_columns(Eigen::Ref<Eigen::MatrixXd> b) {
    const Eigen::Index n = b.rows();
    const Eigen::Index k = K > 0 ? K : b.cols();
    double* w = work_.data();
    const bool permuted = ldlt_.permutationP().size() > 0;
    const int* p = ldlt_.permutationP().indices().data();
    for (Eigen::Index i = 0; i < n; ++i) {  // row P(i) of W = row i of B
      double* row = w + (permuted ? p[i] : i) * k;
      for (Eigen::Index c = 0; c < k; ++c) {
        row[c] = b(i, c);
      }
    }
    // L is unit lower triangular, stored by columns without its diagonal.
    const SparseMatrix& l = ldlt_.matrixL().nestedExpression();
    const int* rows = l.innerIndexPtr();
    const double* values = l.valuePtr();
    for (Eigen::Index j = 0; j < n; ++j) {  // forward: L Y = W
      const double* wj = w + j * k;
      const auto [begin, end] = column_range(l, j);
      for (int q = begin; q < end; ++q) {
        if (rows[q] > j) {
          double* wi = w + rows[q] * k;
          for (Eigen::Index c = 0; c < k; ++c) {
            wi[c] -= values[q] * wj[c];
          }
        }
      }
    }
    // D^{-1} as the product with 1 / d_j, as Eigen's own solve does (the same rounding: a
    // system solved here or by SimplicialLDLT::solve gives the same digits)
    for (Eigen::Index j = 0; j < n; ++j) {
      for (Eigen::Index c = 0; c < k; ++c) {
        w[j * k + c] *= inverse_d_[j];
      }
    }
    for (Eigen::Index j = n - 1; j >= 0; --j) {  // backward: L^T X = Y
      double* wj = w + j * k;
      const auto [begin, end] = column_range(l, j);
      for (int q = begin; q < end; ++q) {
        if (rows[q] > j) {
          const double* wi = w + rows[q] * k;
          for (Eigen::Index c = 0; c < k; ++c) {
            wj[c] -= values[q] * wi[c];
          }
        }
      }
    }
    for (Eigen::Index i = 0; i < n; ++i) {
      const double* row = w + (permuted ? p[i] : i) * k;
      for (Eigen::Index c = 0; c < k; ++c) {
        b(i, c) = row[c];
      }
    }
  }

  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt_;
  Eigen::VectorXd inverse_d_;  // 1 / d_j, set by factorize
  std::vector<double> work_;
  bool factored_ = false;
};

struct SparseCholesky::Backends {
  CholeskyBackend active = CholeskyBackend::kAutomatic;
  Simplicial simplicial;
  std::unique_ptr<CholmodFactor> cholmod;  // created when first used
  // The analyzed pattern: rows, column starts and row indices (compressed).
  Eigen::Index rows = -1;
  std::vector<int> outer, inner;
  int analyses = 0;

  bool same_pattern(const SparseMatrix& a) const {
    if (a.rows() != rows || a.cols() != rows) {
      return false;
    }
    for (Eigen::Index j = 0; j < a.outerSize(); ++j) {
      const auto [begin, end] = column_range(a, j);
      const auto kept_begin = static_cast<size_t>(outer[static_cast<size_t>(j)]);
      if (end - begin != outer[static_cast<size_t>(j) + 1] - outer[static_cast<size_t>(j)] ||
          !std::equal(a.innerIndexPtr() + begin, a.innerIndexPtr() + end,
                      inner.begin() + static_cast<std::ptrdiff_t>(kept_begin))) {
        return false;
      }
    }
    return true;
  }

  void keep_pattern(const SparseMatrix& a) {
    rows = a.rows();
    outer.assign(1, 0);
    inner.clear();
    for (Eigen::Index j = 0; j < a.outerSize(); ++j) {
      const auto [begin, end] = column_range(a, j);
      inner.insert(inner.end(), a.innerIndexPtr() + begin, a.innerIndexPtr() + end);
      outer.push_back(static_cast<int>(inner.size()));
    }
  }
};

SparseCholesky::SparseCholesky(const SparseCholeskySettings& settings)
    : settings_(settings), backends_(std::make_unique<Backends>()) {
  if (settings.supernodal_threshold < 0 || settings.constant_supernodal_threshold < 0) {
    throw make_error("sparse Cholesky: supernodal_threshold is ", settings.supernodal_threshold,
                     " and constant_supernodal_threshold ", settings.constant_supernodal_threshold,
                     ", both must be >= 0");
  }
}
CholeskyBackend resolve_backend(const SparseCholeskySettings& settings, Eigen::Index rows) {
  if (settings.backend != CholeskyBackend::kAutomatic) {
    return settings.backend;
  }
  return rows >= settings.supernodal_threshold ? CholeskyBackend::kCholmodSupernodal
                                               : CholeskyBackend::kSimplicialLdlt;
}

SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&& other) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&& other) noexcept = default;

void SparseCholesky::analyze(const SparseMatrix& a) {
  check_square(a, "analysis");
  Backends& b = *backends_;
  b.active = resolve_backend(settings_, a.rows());
  b.rows = -1;  // no valid analysis until this one succeeds
  if (b.active == CholeskyBackend::kCholmodSupernodal) {
    if (!b.cholmod) {
      b.cholmod = std::make_unique<CholmodFactor>(settings_.triangular_solve);
    }
    b.cholmod->analyze(a);
  } else {
    b.simplicial.analyze(a);
  }
  b.keep_pattern(a);
  ++b.analyses;
}

void SparseCholesky::factorize(const SparseMatrix& a) {
  check_square(a, "factorization");
  check_finite(a);
  Backends& b = *backends_;
  if (!b.same_pattern(a)) {
    analyze(a);
  }
  if (b.active == CholeskyBackend::kCholmodSupernodal) {
    b.cholmod->factorize(a);
  } else {
    b.simplicial.factorize(a);
  }
}

// A writable Eigen::Ref is a view: passed by value, as Eigen documents.
// NOLINTNEXTLINE(performance-unnecessary-value-param)
void SparseCholesky::solve_in_place(Eigen::Ref<Eigen::MatrixXd> b) {
  if (!is_factored()) {
    throw make_error(
        "sparse Cholesky solve: the matrix is not factored (or its factorization "
        "failed)");
  }
  if (b.rows() != backends_->rows) {
    throw make_error("sparse Cholesky solve: the right-hand side has ", b.rows(),
                     " rows, the matrix ", backends_->rows);
  }
  check_finite(b);
  if (backends_->active == CholeskyBackend::kCholmodSupernodal) {
    backends_->cholmod->solve_in_place(b);
  } else {
    backends_->simplicial.solve_in_place(b);
  }
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& b) {
  Eigen::MatrixXd x = b;
  solve_in_place(x);
  return x;
}

void SparseCholesky::rank_update(const SparseMatrix& c, bool downdate) {
  if (backends_->active != CholeskyBackend::kCholmodSupernodal) {
    throw make_error(
        "sparse Cholesky: rank updates need the CHOLMOD backend (this factor uses ",
        backends_->active == CholeskyBackend::kAutomatic ? "none yet" : "SimplicialLDLT", ")");
  }
  backends_->cholmod->rank_update(c, downdate);
}

int SparseCholesky::size() const {
  return backends_->rows < 0 ? 0 : static_cast<int>(backends_->rows);
}

bool SparseCholesky::is_factored() const {
  const Backends& b = *backends_;
  if (b.rows < 0) {
    return false;
  }
  return b.active == CholeskyBackend::kCholmodSupernodal ? b.cholmod->is_factored()
                                                         : b.simplicial.factored();
}

CholeskyBackend SparseCholesky::backend() const {
  return backends_->active;
}

int SparseCholesky::analysis_count() const {
  return backends_->analyses;
}

double SparseCholesky::factor_nonzeros() const {
  const Backends& b = *backends_;
  if (b.rows < 0) {
    return 0.0;
  }
  return b.active == CholeskyBackend::kCholmodSupernodal ? b.cholmod->factor_nonzeros()
                                                         : b.simplicial.factor_nonzeros();
}

double SparseCholesky::reciprocal_condition_estimate() const {
  if (!is_factored()) {
    return 0.0;
  }
  const Backends& b = *backends_;
  return b.active == CholeskyBackend::kCholmodSupernodal
             ? b.cholmod->reciprocal_condition_estimate()
             : b.simplicial.reciprocal_condition_estimate();
}

}  // namespace dnurbs
