#include "dnurbs/core/low_rank_update.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

LowRankUpdate::LowRankUpdate(const LowRankSettings& settings) : settings_(settings) {
  if (settings_.method == LowRankMethod::kFactorUpdate) {
    settings_.cholesky.backend = CholeskyBackend::kCholmodSupernodal;
  }
  if (settings_.max_woodbury_terms < 0) {
    throw make_error("low-rank update: max_woodbury_terms is ", settings_.max_woodbury_terms,
                     ", must be >= 0");
  }
  if (!(settings_.min_capacitance_rcond >= 0.0 && settings_.min_capacitance_rcond < 1.0)) {
    throw make_error("low-rank update: min_capacitance_rcond is ", settings_.min_capacitance_rcond,
                     ", must be in [0, 1)");
  }
  cholesky_ = SparseCholesky(settings_.cholesky);
}

int LowRankUpdate::term_count() const {
  return static_cast<int>(std::count_if(terms_.begin(), terms_.end(),
                                        [](const Term& t) { return t.place != Place::kUnused; }));
}

void LowRankUpdate::check_term(std::span<const int> rows, std::span<const double> values,
                               double stiffness, std::span<const double> target) const {
  if (!(stiffness > 0.0) || !std::isfinite(stiffness)) {
    throw make_error("low-rank term: stiffness is ", stiffness, ", must be > 0 and finite");
  }
  if (rows.size() != values.size()) {
    throw make_error("low-rank term: ", rows.size(), " rows but ", values.size(), " values");
  }
  for (size_t p = 0; p < rows.size(); ++p) {
    if (rows[p] < 0) {
      throw make_error("low-rank term: row ", rows[p], " (entry ", p, ") is negative");
    }
    if (factored_ && rows[p] >= size()) {
      throw make_error("low-rank term: row ", rows[p], " (entry ", p, ") is outside 0..",
                       size() - 1);
    }
    if (!std::isfinite(values[p])) {
      throw make_error("low-rank term: value ", p, " (row ", rows[p], ") is ", values[p]);
    }
    if (std::find(rows.begin(), rows.begin() + static_cast<std::ptrdiff_t>(p), rows[p]) !=
        rows.begin() + static_cast<std::ptrdiff_t>(p)) {
      throw make_error("low-rank term: row ", rows[p], " appears twice");
    }
  }
  for (size_t c = 0; c < target.size(); ++c) {
    if (!std::isfinite(target[c])) {
      throw make_error("low-rank term: target entry ", c, " is ", target[c]);
    }
  }
}

void LowRankUpdate::factorize(const SparseMatrix& a) {
  for (const Term& term : terms_) {
    for (const int row : term.rows) {
      if (row >= a.rows()) {
        throw make_error("low-rank update: a term has row ", row, ", the matrix ", a.rows(),
                         " rows");
      }
    }
  }
  matrix_ = a;
  refactor(/*fold_woodbury=*/settings_.method == LowRankMethod::kFactorUpdate);
}

// Factors A + sum of the folded terms: the folded terms that did not move since the previous
// solve and, when fold_woodbury, the Woodbury terms that did not move either. Every other term is
// a Woodbury term afterwards, its W column stale (the factored matrix changed).
void LowRankUpdate::refactor(bool fold_woodbury) {
  SparseMatrix folded = matrix_;
  std::vector<int> kept;
  for (size_t id = 0; id < terms_.size(); ++id) {
    Term& term = terms_[id];
    if (term.place == Place::kUnused) {
      continue;
    }
    const bool fold = settings_.method == LowRankMethod::kFactorUpdate ||
                      (!term.moved && (term.place == Place::kFolded || fold_woodbury));
    if (!fold) {
      term.place = Place::kWoodbury;
      kept.push_back(static_cast<int>(id));
      continue;
    }
    // k u u^T into the lower triangle (the only one SparseCholesky reads).
    for (size_t p = 0; p < term.rows.size(); ++p) {
      for (size_t q = 0; q < term.rows.size(); ++q) {
        if (term.rows[p] >= term.rows[q]) {
          folded.coeffRef(term.rows[p], term.rows[q]) +=
              term.stiffness * term.values[p] * term.values[q];
        }
      }
    }
    term.place = Place::kFolded;
    term.moved = false;
  }
  folded.makeCompressed();
  factored_ = false;
  woodbury_.clear();
  cholesky_.factorize(folded);
  ++factorizations_;
  factored_ = true;
  refactor_needed_ = false;
  for (const int id : kept) {
    add_woodbury(id);
  }
}

void LowRankUpdate::factor_update(const Term& term, bool downdate) {
  SparseMatrix c(size(), 1);
  c.reserve(Eigen::VectorXi::Constant(1, static_cast<int>(term.rows.size())));
  const double scale = std::sqrt(term.stiffness);
  for (size_t p = 0; p < term.rows.size(); ++p) {
    c.insert(term.rows[p], 0) = scale * term.values[p];
  }
  c.makeCompressed();
  cholesky_.rank_update(c, downdate);
}

void LowRankUpdate::add_woodbury(int term) {
  Term& t = terms_[static_cast<size_t>(term)];
  t.place = Place::kWoodbury;
  t.moved = true;
  woodbury_.push_back(term);
  const auto m = static_cast<Eigen::Index>(woodbury_.size());
  if (w_.cols() < m || w_.rows() != size()) {
    const Eigen::Index capacity = std::max<Eigen::Index>(4, 2 * m);
    Eigen::MatrixXd w(size(), capacity);
    Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(capacity, capacity);
    if (w_.rows() == size()) {
      w.leftCols(m - 1) = w_.leftCols(m - 1);
      gram.topLeftCorner(m - 1, m - 1) = gram_.topLeftCorner(m - 1, m - 1);
    }
    w_ = std::move(w);
    gram_ = std::move(gram);
  }
}

void LowRankUpdate::drop_woodbury(int term) {
  const auto found = std::find(woodbury_.begin(), woodbury_.end(), term);
  if (found == woodbury_.end()) {
    return;  // added before the first factorize: not placed yet
  }
  const auto j = static_cast<Eigen::Index>(found - woodbury_.begin());
  const auto last = static_cast<Eigen::Index>(woodbury_.size()) - 1;
  if (j != last) {  // the last column takes the dropped one's place
    w_.col(j) = w_.col(last);
    gram_.row(j).head(last + 1) = gram_.row(last).head(last + 1);
    gram_.col(j).head(last + 1) = gram_.col(last).head(last + 1);
    gram_(j, j) = gram_(last, last);
    woodbury_[static_cast<size_t>(j)] = woodbury_.back();
  }
  woodbury_.pop_back();
}

int LowRankUpdate::add_term(std::span<const int> rows, std::span<const double> values,
                            double stiffness, std::span<const double> target) {
  check_term(rows, values, stiffness, target);
  auto slot = std::find_if(terms_.begin(), terms_.end(),
                           [](const Term& t) { return t.place == Place::kUnused; });
  if (slot == terms_.end()) {
    terms_.emplace_back();
    slot = terms_.end() - 1;
  }
  const auto id = static_cast<int>(slot - terms_.begin());
  slot->rows.assign(rows.begin(), rows.end());
  slot->values.assign(values.begin(), values.end());
  slot->stiffness = stiffness;
  slot->target.assign(target.begin(), target.end());
  slot->moved = true;
  if (!factored_) {
    slot->place = Place::kWoodbury;  // placed by the coming factorize
  } else if (settings_.method == LowRankMethod::kFactorUpdate) {
    slot->place = Place::kFolded;
    factor_update(*slot, /*downdate=*/false);
    slot->moved = false;
  } else {
    add_woodbury(id);
  }
  return id;
}

void LowRankUpdate::move_term(int term, std::span<const int> rows, std::span<const double> values,
                              double stiffness, std::span<const double> target) {
  if (term < 0 || term >= static_cast<int>(terms_.size()) ||
      terms_[static_cast<size_t>(term)].place == Place::kUnused) {
    throw make_error("low-rank update: no term ", term);
  }
  check_term(rows, values, stiffness, target);
  Term& t = terms_[static_cast<size_t>(term)];
  if (factored_ && settings_.method == LowRankMethod::kFactorUpdate) {
    // Update with the new term before downdating the old one: the intermediate matrix
    // A + k_new u_new u_new^T + ... stays at least as positive definite as either end.
    const Term old = t;
    t.rows.assign(rows.begin(), rows.end());
    t.values.assign(values.begin(), values.end());
    t.stiffness = stiffness;
    factor_update(t, /*downdate=*/false);
    factor_update(old, /*downdate=*/true);
  } else {
    t.rows.assign(rows.begin(), rows.end());
    t.values.assign(values.begin(), values.end());
    t.stiffness = stiffness;
    if (factored_ && t.place == Place::kFolded) {
      refactor_needed_ = true;  // its old version is in the factor
    }
    t.moved = true;
  }
  t.target.assign(target.begin(), target.end());
}

void LowRankUpdate::remove_term(int term) {
  if (term < 0 || term >= static_cast<int>(terms_.size()) ||
      terms_[static_cast<size_t>(term)].place == Place::kUnused) {
    throw make_error("low-rank update: no term ", term);
  }
  Term& t = terms_[static_cast<size_t>(term)];
  if (factored_ && settings_.method == LowRankMethod::kFactorUpdate) {
    factor_update(t, /*downdate=*/true);
  } else if (t.place == Place::kWoodbury) {
    drop_woodbury(term);
  } else if (factored_) {
    refactor_needed_ = true;
  }
  t.place = Place::kUnused;
}

void LowRankUpdate::set_target(int term, std::span<const double> target) {
  if (term < 0 || term >= static_cast<int>(terms_.size()) ||
      terms_[static_cast<size_t>(term)].place == Place::kUnused) {
    throw make_error("low-rank update: no term ", term);
  }
  for (size_t c = 0; c < target.size(); ++c) {
    if (!std::isfinite(target[c])) {
      throw make_error("low-rank term ", term, ": target entry ", c, " is ", target[c]);
    }
  }
  terms_[static_cast<size_t>(term)].target.assign(target.begin(), target.end());
}

// B += sum over folded terms of k u t^T (their stiffness is in the factor, their pull is not).
void LowRankUpdate::add_folded_targets(Eigen::Ref<Eigen::MatrixXd> b) const {
  for (const Term& term : terms_) {
    if (term.place != Place::kFolded || term.target.empty()) {
      continue;
    }
    for (Eigen::Index c = 0; c < b.cols(); ++c) {
      const double pull = term.stiffness * term.target[static_cast<size_t>(c)];
      for (size_t p = 0; p < term.rows.size(); ++p) {
        b(term.rows[p], c) += pull * term.values[p];
      }
    }
  }
}

double LowRankUpdate::u_dot(const Term& term, const double* column) const {
  double sum = 0.0;
  for (size_t p = 0; p < term.rows.size(); ++p) {
    sum += term.values[p] * column[term.rows[p]];
  }
  return sum;
}

// A writable Eigen::Ref is a view: passed by value, as Eigen documents.
// NOLINTNEXTLINE(performance-unnecessary-value-param)
void LowRankUpdate::solve_in_place(Eigen::Ref<Eigen::MatrixXd> b) {
  if (!factored_) {
    throw make_error("low-rank update: solve before factorize");
  }
  for (const Term& term : terms_) {
    if (term.place != Place::kUnused && !term.target.empty() &&
        static_cast<Eigen::Index>(term.target.size()) != b.cols()) {
      throw make_error("low-rank update: a target has ", term.target.size(),
                       " entries, the right-hand side ", b.cols(), " columns");
    }
  }
  if (settings_.method == LowRankMethod::kWoodbury &&
      (refactor_needed_ || static_cast<int>(woodbury_.size()) > settings_.max_woodbury_terms)) {
    refactor(/*fold_woodbury=*/static_cast<int>(woodbury_.size()) > settings_.max_woodbury_terms);
  }
  if (woodbury_.empty()) {
    add_folded_targets(b);
    cholesky_.solve_in_place(b);
    return;
  }
  woodbury_solve(b);
}

// Sherman-Morrison-Woodbury with targets (Hager, Updating the inverse of a matrix, 1989): with
// Y = A_f^{-1} B, W = A_f^{-1} U, G = U^T W and C = K^{-1} + G, Woodbury's
//   (A_f + U K U^T)^{-1} = A_f^{-1} - W C^{-1} W^T
// applied to B + U K T gives Y + W K T - W C^{-1} (U^T Y + G K T); as G K T = C K T - T the
// W K T terms cancel exactly, leaving
//   X = Y + W C^{-1} (T - U^T Y),
// in which nothing scales with K, so stiff terms cost no digits. Y and the stale columns of W
// come from one multi-column solve.
void LowRankUpdate::woodbury_solve(Eigen::Ref<Eigen::MatrixXd> b) {
  const Eigen::Index n = b.rows();
  const Eigen::Index k = b.cols();
  for (int attempt = 0;; ++attempt) {
    stale_.clear();
    for (size_t j = 0; j < woodbury_.size(); ++j) {
      if (terms_[static_cast<size_t>(woodbury_[j])].moved) {
        stale_.push_back(static_cast<int>(j));
      }
    }
    const auto s = static_cast<Eigen::Index>(stale_.size());
    const auto needed = static_cast<size_t>(n * (k + s));
    if (workspace_.size() < needed) {
      workspace_.resize(needed);
    }
    Eigen::Map<Eigen::MatrixXd> rhs(workspace_.data(), n, k + s);
    rhs.leftCols(k) = b;
    add_folded_targets(rhs.leftCols(k));
    rhs.rightCols(s).setZero();
    for (Eigen::Index c = 0; c < s; ++c) {
      const Term& term = terms_[static_cast<size_t>(woodbury_[static_cast<size_t>(stale_[c])])];
      for (size_t p = 0; p < term.rows.size(); ++p) {
        rhs(term.rows[p], k + c) = term.values[p];
      }
    }
    cholesky_.solve_in_place(rhs);
    for (Eigen::Index c = 0; c < s; ++c) {
      w_.col(stale_[static_cast<size_t>(c)]) = rhs.col(k + c);
    }
    if (capacitance_is_ill_conditioned() && attempt == 0 &&
        std::any_of(woodbury_.begin(), woodbury_.end(),
                    [this](int id) { return !terms_[static_cast<size_t>(id)].moved; })) {
      refactor(/*fold_woodbury=*/true);  // fold the terms that did not move, then redo
      if (woodbury_.empty()) {
        add_folded_targets(b);
        cholesky_.solve_in_place(b);
        return;
      }
      continue;
    }
    if (capacitance_llt_.info() != Eigen::Success) {
      throw make_error("low-rank update: the ", woodbury_.size(), " by ", woodbury_.size(),
                       " capacitance matrix K^-1 + U^T A^-1 U is not "
                       "numerically positive definite");
    }
    // X = Y + W Z with C Z = T - U^T Y (m by k).
    const auto m = static_cast<Eigen::Index>(woodbury_.size());
    rhs_small_.resize(m, k);
    for (Eigen::Index j = 0; j < m; ++j) {
      const Term& term = terms_[static_cast<size_t>(woodbury_[static_cast<size_t>(j)])];
      for (Eigen::Index c = 0; c < k; ++c) {
        const double target = term.target.empty() ? 0.0 : term.target[static_cast<size_t>(c)];
        rhs_small_(j, c) = target - u_dot(term, rhs.col(c).data());
      }
    }
    capacitance_llt_.solveInPlace(rhs_small_);
    b = rhs.leftCols(k);
    for (Eigen::Index c = 0; c < k; ++c) {
      for (Eigen::Index j = 0; j < m; ++j) {
        b.col(c) += rhs_small_(j, c) * w_.col(j);
      }
    }
    for (const int id : woodbury_) {
      terms_[static_cast<size_t>(id)].moved = false;
    }
    return;
  }
}

// Refreshes the rows and columns of U^T W that belong to stale terms (symmetrized: the two
// computed halves differ by rounding), factors C = K^{-1} + U^T W and estimates its condition.
bool LowRankUpdate::capacitance_is_ill_conditioned() {
  const auto m = static_cast<Eigen::Index>(woodbury_.size());
  for (const int j : stale_) {
    const Term& term_j = terms_[static_cast<size_t>(woodbury_[static_cast<size_t>(j)])];
    for (Eigen::Index i = 0; i < m; ++i) {
      const Term& term_i = terms_[static_cast<size_t>(woodbury_[static_cast<size_t>(i)])];
      const double value =
          0.5 * (u_dot(term_i, w_.col(j).data()) + u_dot(term_j, w_.col(i).data()));
      gram_(i, j) = value;
      gram_(j, i) = value;
    }
  }
  capacitance_.resize(m, m);
  capacitance_ = gram_.topLeftCorner(m, m);
  for (Eigen::Index j = 0; j < m; ++j) {
    capacitance_(j, j) +=
        1.0 / terms_[static_cast<size_t>(woodbury_[static_cast<size_t>(j)])].stiffness;
  }
  capacitance_llt_.compute(capacitance_);
  capacitance_rcond_ = capacitance_llt_.info() == Eigen::Success ? capacitance_llt_.rcond() : 0.0;
  return capacitance_rcond_ < settings_.min_capacitance_rcond;
}

}  // namespace dnurbs
