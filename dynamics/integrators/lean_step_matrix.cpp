#include "dnurbs/dynamics/integrators/lean_step_matrix.h"

#include <algorithm>
#include <cmath>

#include <Eigen/OrderingMethods>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

using Permutation = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

bool same_outer(const SparseMatrix& a, const SparseMatrix& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && a.nonZeros() == b.nonZeros() &&
         a.isCompressed() && b.isCompressed() &&
         std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.cols() + 1, b.outerIndexPtr());
}

bool same_pattern(const SparseMatrix& a, const SparseMatrix& b) {
  return same_outer(a, b) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
}

// Whether the damping takes part: stored with values (an undamped model may leave it empty).
bool has_damping(const ModelMatrices& matrices) {
  return matrices.damping.nonZeros() > 0;
}

}  // namespace

bool LeanStepMatrix::analyze(const ModelMatrices& matrices, const FreeCoordinates& free,
                             bool supernodal) {
  analyzed_ = false;
  factored_ = false;
  supernodal_ = supernodal;
  const SparseMatrix& mass = matrices.mass;
  if (!mass.isCompressed() || mass.rows() != free.count() || mass.cols() != free.count() ||
      !same_pattern(mass, matrices.stiffness) ||
      (has_damping(matrices) && !same_pattern(mass, matrices.damping))) {
    return false;
  }
  ++analyses_;
  const int n = free.free_count();
  outer_.assign(mass.outerIndexPtr(), mass.outerIndexPtr() + mass.cols() + 1);
  inner_.assign(mass.innerIndexPtr(), mass.innerIndexPtr() + mass.nonZeros());
  if (supernodal) {
    analyze_lower(free);
    return true;
  }

  // Fill-reducing ordering of the free block: free unknown i becomes unknown position[i] of
  // P A P^T (Eigen's convention, P = (AMD's inverse permutation)^{-1}, as SimplicialLDLT).
  std::vector<int> position(static_cast<size_t>(n));
  if (n > 0) {
    const SparseMatrix reduced = free.reduce(mass);
    Permutation inverse;
    Eigen::AMDOrdering<int> amd;
    amd(reduced, inverse);
    const Permutation forward = inverse.inverse();
    for (int i = 0; i < n; ++i) {
      position[static_cast<size_t>(i)] = forward.indices()[i];
    }
  }
  unknown_of_.assign(static_cast<size_t>(n), 0);
  for (int i = 0; i < n; ++i) {
    unknown_of_[static_cast<size_t>(position[static_cast<size_t>(i)])] = free.free_unknown(i);
  }

  // Upper triangle of P A P^T from the lower triangle of A: entry (i, j), i >= j, goes to
  // column max(position[fi], position[fj]), row min. Visited in Eigen's order (columns j, then
  // rows i, ascending), so that each column of P A P^T lists its entries as SimplicialLDLT's
  // permuted copy does and the factorization sums in the same order.
  upper_start_.assign(static_cast<size_t>(n) + 1, 0);
  auto visit = [&](auto&& entry) {
    for (int j = 0; j < free.count(); ++j) {
      const int fj = free.free_index(j);
      if (fj < 0) {
        continue;
      }
      const int pj = position[static_cast<size_t>(fj)];
      for (int p = outer_[static_cast<size_t>(j)]; p < outer_[static_cast<size_t>(j) + 1]; ++p) {
        const int i = inner_[static_cast<size_t>(p)];
        const int fi = i >= j ? free.free_index(i) : -1;
        if (fi >= 0) {
          const int pi = position[static_cast<size_t>(fi)];
          entry(std::min(pi, pj), std::max(pi, pj), p);
        }
      }
    }
  };
  visit(
      [&](int /*row*/, int column, int /*p*/) { ++upper_start_[static_cast<size_t>(column) + 1]; });
  for (int k = 0; k < n; ++k) {
    upper_start_[static_cast<size_t>(k) + 1] += upper_start_[static_cast<size_t>(k)];
  }
  const auto upper_count = static_cast<size_t>(upper_start_[static_cast<size_t>(n)]);
  upper_row_.assign(upper_count, 0);
  source_.assign(upper_count, 0);
  upper_value_.assign(upper_count, 0.0);
  std::vector<int> next(upper_start_.begin(), upper_start_.end() - 1);
  visit([&](int row, int column, int p) {
    const auto at = static_cast<size_t>(next[static_cast<size_t>(column)]++);
    upper_row_[at] = row;
    source_[at] = p;
  });

  // Elimination tree and column counts of L (Davis 2005, ldl_symbolic)
  parent_.assign(static_cast<size_t>(n), -1);
  l_count_.assign(static_cast<size_t>(n), 0);
  flag_.assign(static_cast<size_t>(n), 0);
  for (int k = 0; k < n; ++k) {
    flag_[static_cast<size_t>(k)] = k;
    for (int p = upper_start_[static_cast<size_t>(k)]; p < upper_start_[static_cast<size_t>(k) + 1];
         ++p) {
      for (int i = upper_row_[static_cast<size_t>(p)]; i < k && flag_[static_cast<size_t>(i)] != k;
           i = parent_[static_cast<size_t>(i)]) {
        if (parent_[static_cast<size_t>(i)] == -1) {
          parent_[static_cast<size_t>(i)] = k;
        }
        ++l_count_[static_cast<size_t>(i)];
        flag_[static_cast<size_t>(i)] = k;
      }
    }
  }
  l_start_.assign(static_cast<size_t>(n) + 1, 0);
  for (int k = 0; k < n; ++k) {
    l_start_[static_cast<size_t>(k) + 1] =
        l_start_[static_cast<size_t>(k)] + l_count_[static_cast<size_t>(k)];
  }
  l_row_.assign(static_cast<size_t>(l_start_[static_cast<size_t>(n)]), 0);
  l_value_.assign(l_row_.size(), 0.0);
  d_.assign(static_cast<size_t>(n), 0.0);
  inverse_d_.assign(static_cast<size_t>(n), 0.0);
  stack_.assign(static_cast<size_t>(n), 0);
  work_.assign(static_cast<size_t>(n), 0.0);
  analyzed_ = true;
  return true;
}

void LeanStepMatrix::analyze_lower(const FreeCoordinates& free) {
  // Lower triangle of A in the free unknowns' order: entry (i, j), i >= j, of the model matrices
  // goes to column free_index(j), row free_index(i); visited by columns, rows ascending, so each
  // column of lower_ is sorted as CHOLMOD expects.
  const int n = free.free_count();
  unknown_of_.assign(static_cast<size_t>(n), 0);
  std::vector<int> start(static_cast<size_t>(n) + 1, 0);
  std::vector<int> rows;
  source_.clear();
  for (int j = 0; j < free.count(); ++j) {
    const int fj = free.free_index(j);
    if (fj < 0) {
      continue;
    }
    unknown_of_[static_cast<size_t>(fj)] = j;
    for (int p = outer_[static_cast<size_t>(j)]; p < outer_[static_cast<size_t>(j) + 1]; ++p) {
      const int i = inner_[static_cast<size_t>(p)];
      const int fi = i >= j ? free.free_index(i) : -1;
      if (fi >= 0) {
        rows.push_back(fi);
        source_.push_back(p);
        ++start[static_cast<size_t>(fj) + 1];
      }
    }
  }
  for (int k = 0; k < n; ++k) {
    start[static_cast<size_t>(k) + 1] += start[static_cast<size_t>(k)];
  }
  lower_.resize(n, n);
  lower_.resizeNonZeros(static_cast<Eigen::Index>(rows.size()));
  std::copy(start.begin(), start.end(), lower_.outerIndexPtr());
  std::copy(rows.begin(), rows.end(), lower_.innerIndexPtr());
  std::fill(lower_.valuePtr(), lower_.valuePtr() + rows.size(), 0.0);
  cholmod_ = CholmodFactor();
  cholmod_.analyze(lower_);
  column_.setZero(n);
  analyzed_ = true;
}

bool LeanStepMatrix::fits(const ModelMatrices& matrices, bool supernodal) const {
  // The full comparison for the mass; the others share the model's pattern when their column
  // starts agree (a model assembles all three into one pattern, analyze() checked it).
  return analyzed_ && supernodal == supernodal_ &&
         matrices.mass.rows() + 1 == static_cast<Eigen::Index>(outer_.size()) &&
         matrices.mass.nonZeros() == static_cast<Eigen::Index>(inner_.size()) &&
         matrices.mass.isCompressed() &&
         std::equal(outer_.begin(), outer_.end(), matrices.mass.outerIndexPtr()) &&
         std::equal(inner_.begin(), inner_.end(), matrices.mass.innerIndexPtr()) &&
         same_outer(matrices.mass, matrices.stiffness) &&
         (!has_damping(matrices) || same_outer(matrices.mass, matrices.damping));
}

void LeanStepMatrix::factorize(const ModelMatrices& matrices, double damping_coefficient,
                               double stiffness_coefficient) {
  if (!analyzed_) {
    throw make_error("LeanStepMatrix::factorize before a successful analyze");
  }
  factored_ = false;
  ++factorizations_;
  // Values of P A P^T, summed as (M + c_K K) + c_D D (the order of step_blocks' sparse sums)
  const double* mass = matrices.mass.valuePtr();
  const double* stiffness = matrices.stiffness.valuePtr();
  const bool damped = damping_coefficient != 0.0 && has_damping(matrices);
  const double* damping = damped ? matrices.damping.valuePtr() : nullptr;
  double* values = supernodal_ ? lower_.valuePtr() : upper_value_.data();
  for (size_t e = 0; e < source_.size(); ++e) {
    const int p = source_[e];
    double value = mass[p];
    if (stiffness_coefficient != 0.0) {
      value += stiffness_coefficient * stiffness[p];
    }
    if (damped) {
      value += damping_coefficient * damping[p];
    }
    values[e] = value;
  }
  if (supernodal_) {
    cholmod_.factorize(lower_);  // throws Error naming the free column of a non-positive pivot
    factored_ = true;
    return;
  }
  // Up-looking L D L^T, row k of L from the sparse triangular solve along the elimination tree
  // (Davis 2005, ldl_numeric)
  const auto n = static_cast<int>(unknown_of_.size());
  for (int k = 0; k < n; ++k) {
    int top = n;
    flag_[static_cast<size_t>(k)] = k;
    l_count_[static_cast<size_t>(k)] = 0;
    for (int p = upper_start_[static_cast<size_t>(k)]; p < upper_start_[static_cast<size_t>(k) + 1];
         ++p) {
      int i = upper_row_[static_cast<size_t>(p)];
      work_[static_cast<size_t>(i)] += upper_value_[static_cast<size_t>(p)];
      int length = 0;
      for (; flag_[static_cast<size_t>(i)] != k; i = parent_[static_cast<size_t>(i)]) {
        stack_[static_cast<size_t>(length++)] = i;
        flag_[static_cast<size_t>(i)] = k;
      }
      while (length > 0) {
        stack_[static_cast<size_t>(--top)] = stack_[static_cast<size_t>(--length)];
      }
    }
    double d = work_[static_cast<size_t>(k)];
    work_[static_cast<size_t>(k)] = 0.0;
    for (; top < n; ++top) {
      const int i = stack_[static_cast<size_t>(top)];
      const double yi = work_[static_cast<size_t>(i)];
      work_[static_cast<size_t>(i)] = 0.0;
      const int end = l_start_[static_cast<size_t>(i)] + l_count_[static_cast<size_t>(i)];
      for (int p = l_start_[static_cast<size_t>(i)]; p < end; ++p) {
        work_[static_cast<size_t>(l_row_[static_cast<size_t>(p)])] -=
            l_value_[static_cast<size_t>(p)] * yi;
      }
      const double l_ki = yi / d_[static_cast<size_t>(i)];
      d -= l_ki * yi;
      l_row_[static_cast<size_t>(end)] = k;
      l_value_[static_cast<size_t>(end)] = l_ki;
      ++l_count_[static_cast<size_t>(i)];
    }
    if (!(d > 0.0) || !std::isfinite(d)) {
      std::fill(work_.begin(), work_.end(), 0.0);
      throw make_error("pivot ", d, " of free unknown ", unknown_of_[static_cast<size_t>(k)],
                       " (elimination step ", k, " of ", n,
                       "): the step matrix is not positive definite");
    }
    d_[static_cast<size_t>(k)] = d;
    inverse_d_[static_cast<size_t>(k)] = 1.0 / d;
  }
  factored_ = true;
}

void LeanStepMatrix::solve(const double* r, double* x) {
  if (!factored_) {
    throw make_error("LeanStepMatrix::solve without a factorization");
  }
  const auto n = static_cast<int>(unknown_of_.size());
  if (supernodal_) {
    for (int k = 0; k < n; ++k) {
      column_[k] = r[unknown_of_[static_cast<size_t>(k)]];
    }
    cholmod_.solve_in_place(column_);
    for (int k = 0; k < n; ++k) {
      x[unknown_of_[static_cast<size_t>(k)]] = column_[k];
    }
    return;
  }
  for (int k = 0; k < n; ++k) {
    work_[static_cast<size_t>(k)] = r[unknown_of_[static_cast<size_t>(k)]];
  }
  for (int j = 0; j < n; ++j) {  // L y = P r
    const double y = work_[static_cast<size_t>(j)];
    for (int p = l_start_[static_cast<size_t>(j)]; p < l_start_[static_cast<size_t>(j) + 1]; ++p) {
      work_[static_cast<size_t>(l_row_[static_cast<size_t>(p)])] -=
          l_value_[static_cast<size_t>(p)] * y;
    }
  }
  for (int j = 0; j < n; ++j) {  // D z = y
    work_[static_cast<size_t>(j)] *= inverse_d_[static_cast<size_t>(j)];
  }
  for (int j = n - 1; j >= 0; --j) {  // L^T w = z
    double sum = work_[static_cast<size_t>(j)];
    for (int p = l_start_[static_cast<size_t>(j)]; p < l_start_[static_cast<size_t>(j) + 1]; ++p) {
      sum -= l_value_[static_cast<size_t>(p)] *
             work_[static_cast<size_t>(l_row_[static_cast<size_t>(p)])];
    }
    work_[static_cast<size_t>(j)] = sum;
  }
  for (int k = 0; k < n; ++k) {
    x[unknown_of_[static_cast<size_t>(k)]] = work_[static_cast<size_t>(k)];
    work_[static_cast<size_t>(k)] = 0.0;  // factorize() expects a zero workspace
  }
}

}  // namespace dnurbs
