#include "dnurbs/core/low_rank_update.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "dnurbs/core/error.h"
#include "tests/common/allocation_counter.h"
#include "tests/core/core_test_helpers.h"

namespace dnurbs {
namespace {

using testing::MatrixL;
using testing::random_block;
using testing::reference_solve;
using testing::relative_error;
using testing::sheet_matrix;
using testing::SparseMatrix;

constexpr int kSide = 15;  // 225 unknowns
constexpr int kColumns = 3;

// A spring on the sheet: the 16 bicubic basis functions N_a(s) N_b(t) of the uniform cubic
// B-spline at (s, t) in a node block (i0..i0+3, j0..j0+3), with a stiffness and a 3D target.
struct Spring {
  std::vector<int> rows;
  std::vector<double> values;
  double stiffness = 1.0;
  std::vector<double> target;
};

std::array<double, 4> cubic_basis(double t) {
  return {(1 - t) * (1 - t) * (1 - t) / 6, (3 * t * t * t - 6 * t * t + 4) / 6,
          (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, t * t * t / 6};
}

Spring make_spring(std::mt19937& engine, double stiffness) {
  std::uniform_int_distribution<int> block(0, kSide - 4);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int i0 = block(engine), j0 = block(engine);
  const std::array<double, 4> nu = cubic_basis(unit(engine)), nv = cubic_basis(unit(engine));
  Spring s;
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      s.rows.push_back((i0 + a) * kSide + (j0 + b));
      s.values.push_back(nu[static_cast<size_t>(a)] * nv[static_cast<size_t>(b)]);
    }
  }
  s.stiffness = stiffness;
  s.target = {2 * unit(engine) - 1, 2 * unit(engine) - 1, 2 * unit(engine) - 1};
  return s;
}

// The springs as U (n by m), their stiffnesses and targets T (m by 3), in long double.
struct Terms {
  MatrixL u, t;
  std::vector<long double> k;
};
Terms terms_of(const std::vector<const Spring*>& springs, Eigen::Index n) {
  Terms terms{MatrixL::Zero(n, static_cast<Eigen::Index>(springs.size())),
              MatrixL::Zero(static_cast<Eigen::Index>(springs.size()), kColumns),
              {}};
  for (size_t i = 0; i < springs.size(); ++i) {
    const auto column = static_cast<Eigen::Index>(i);
    for (size_t p = 0; p < springs[i]->rows.size(); ++p) {
      terms.u(springs[i]->rows[p], column) = springs[i]->values[p];
    }
    for (int c = 0; c < kColumns; ++c) {
      terms.t(column, c) = springs[i]->target[static_cast<size_t>(c)];
    }
    terms.k.push_back(springs[i]->stiffness);
  }
  return terms;
}

// Reference: (A + sum k u u^T) X = B + sum k u t^T by Woodbury in long double.
Eigen::MatrixXd reference(const SparseMatrix& a, const Eigen::MatrixXd& b,
                          const std::vector<const Spring*>& springs) {
  const Terms terms = terms_of(springs, a.rows());
  return testing::reference_with_terms(a, b.cast<long double>(), terms.u, terms.k, terms.t);
}

// The same by a dense long double solve of the summed matrix, with refinement.
Eigen::MatrixXd dense_reference(const SparseMatrix& a, const Eigen::MatrixXd& b,
                                const std::vector<const Spring*>& springs) {
  const Terms terms = terms_of(springs, a.rows());
  MatrixL k = MatrixL::Zero(terms.t.rows(), terms.t.rows());
  for (size_t i = 0; i < terms.k.size(); ++i) {
    k(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) = terms.k[i];
  }
  return reference_solve(a, MatrixL(b.cast<long double>() + terms.u * k * terms.t),
                         MatrixL(terms.u * k * terms.u.transpose()));
}

int add(LowRankUpdate& solver, const Spring& s) {
  return solver.add_term(s.rows, s.values, s.stiffness, s.target);
}
void move(LowRankUpdate& solver, int id, const Spring& s) {
  solver.move_term(id, s.rows, s.values, s.stiffness, s.target);
}

std::string method_name(const ::testing::TestParamInfo<LowRankMethod>& info) {
  return info.param == LowRankMethod::kWoodbury ? "Woodbury" : "FactorUpdate";
}

class LowRankMethods : public ::testing::TestWithParam<LowRankMethod> {};

TEST_P(LowRankMethods, AddMoveRemoveSequenceMatchesFromScratch) {
  // 100 random operations (mostly moves, some adds and removes), stiffness 1..1e3 times the
  // mean diagonal (~ 20), each followed by a solve compared with the reference.
  const SparseMatrix a = sheet_matrix(kSide);
  const Eigen::MatrixXd b = random_block(a.rows(), kColumns, 31);
  LowRankSettings settings;
  settings.method = GetParam();
  LowRankUpdate solver(settings);
  solver.factorize(a);
  std::mt19937 engine(32);
  std::uniform_real_distribution<double> log_k(0.0, 3.0);
  const double scale = a.diagonal().mean();
  std::vector<Spring> springs;
  std::vector<int> ids;
  for (int i = 0; i < 3; ++i) {
    springs.push_back(make_spring(engine, scale * std::pow(10.0, log_k(engine))));
    ids.push_back(add(solver, springs.back()));
  }
  double worst = 0.0;
  for (int step = 0; step < 100; ++step) {
    if (step % 10 == 5) {
      springs.push_back(make_spring(engine, scale * std::pow(10.0, log_k(engine))));
      ids.push_back(add(solver, springs.back()));
    } else if (step % 15 == 7 && springs.size() > 1) {
      solver.remove_term(ids.front());
      springs.erase(springs.begin());
      ids.erase(ids.begin());
    } else {
      const size_t which = static_cast<size_t>(step) % springs.size();
      springs[which] = make_spring(engine, scale * std::pow(10.0, log_k(engine)));
      move(solver, ids[which], springs[which]);
    }
    Eigen::MatrixXd x = b;
    solver.solve_in_place(x);
    std::vector<const Spring*> active;
    active.reserve(springs.size());
    for (const Spring& s : springs) {
      active.push_back(&s);
    }
    worst = std::max(worst, relative_error(x, reference(a, b, active)));
  }
  std::printf("largest relative error over 100 operations: %.2e\n", worst);
  // k up to 1e3 diag(A): measured 6.3e-15 (Woodbury, target form) and 1.6e-13 (factor update,
  // whose folded pull k u t^T in B costs ~1e-16 k / diag, see the stiffness sweep below).
  EXPECT_LT(worst, 1e-12);
  EXPECT_EQ(solver.term_count(), static_cast<int>(springs.size()));
}

// Relative errors of five ways to solve with two springs of stiffness k (relative to A's mean
// diagonal), against the long double reference.
struct StiffnessErrors {
  double woodbury_target = 0, woodbury_pull_in_b = 0, from_scratch = 0, factor_update = 0;
};

StiffnessErrors stiffness_errors(const SparseMatrix& a, const Eigen::MatrixXd& b,
                                 std::vector<Spring> springs, double k) {
  for (Spring& s : springs) {
    s.stiffness = k;
  }
  const Eigen::MatrixXd expected = reference(a, b, {&springs[0], &springs[1]});
  Eigen::MatrixXd pulled = b;  // B + sum k u t^T
  SparseMatrix stiffened = a;
  for (const Spring& s : springs) {
    for (size_t p = 0; p < s.rows.size(); ++p) {
      for (int c = 0; c < kColumns; ++c) {
        pulled(s.rows[p], c) += k * s.values[p] * s.target[static_cast<size_t>(c)];
      }
      for (size_t q = 0; q < s.rows.size(); ++q) {
        stiffened.coeffRef(s.rows[p], s.rows[q]) += k * s.values[p] * s.values[q];
      }
    }
  }
  StiffnessErrors errors;
  LowRankUpdate woodbury, woodbury_plain, update({LowRankMethod::kFactorUpdate, {}, 32, 1e-8});
  for (LowRankUpdate* solver : {&woodbury, &woodbury_plain, &update}) {
    solver->factorize(a);
  }
  for (const Spring& s : springs) {
    add(woodbury, s);
    add(update, s);
    woodbury_plain.add_term(s.rows, s.values, s.stiffness);
  }
  Eigen::MatrixXd x = b;
  woodbury.solve_in_place(x);
  errors.woodbury_target = relative_error(x, expected);
  x = pulled;
  woodbury_plain.solve_in_place(x);
  errors.woodbury_pull_in_b = relative_error(x, expected);
  x = b;
  update.solve_in_place(x);
  errors.factor_update = relative_error(x, expected);
  SparseCholesky scratch;
  scratch.factorize(stiffened);
  errors.from_scratch = relative_error(scratch.solve(pulled), expected);
  return errors;
}

TEST(LowRankUpdate, StiffSpringsStayAccurateInTargetForm) {
  const SparseMatrix a = sheet_matrix(kSide);
  const Eigen::MatrixXd b = random_block(a.rows(), kColumns, 41);
  std::mt19937 engine(42);
  const std::vector<Spring> springs = {make_spring(engine, 1.0), make_spring(engine, 1.0)};
  const double scale = a.diagonal().mean();
  std::printf("k/diag  woodbury(target)  woodbury(pull in B)  from scratch  factor update\n");
  for (int e = 0; e <= 8; ++e) {
    const StiffnessErrors errors = stiffness_errors(a, b, springs, scale * std::pow(10.0, e));
    std::printf("1e%d     %.1e           %.1e              %.1e       %.1e\n", e,
                errors.woodbury_target, errors.woodbury_pull_in_b, errors.from_scratch,
                errors.factor_update);
    // Target form: measured 3.3e-15 to 4.4e-15 for every k from 1 to 1e8 diag(A) (nothing in it
    // scales with k); 1e-13 leaves a margin of 20.
    EXPECT_LT(errors.woodbury_target, 1e-13) << "k = 1e" << e << " diag";
    // Every form with the pull k u t^T inside B (Woodbury on such a B, a factorization of the
    // summed matrix, the factor update) loses the rounding of that pull, ~1e-16 k / diag(A):
    // measured 1.3e-13 (from scratch) at 1e3, 1.2e-12 at 1e4, 1.1e-10 at 1e6, 1.1e-8 at 1e8.
    const double pull_bound = 1e-14 * std::max(1.0, std::pow(10.0, e));
    EXPECT_LT(errors.woodbury_pull_in_b, pull_bound) << "k = 1e" << e << " diag";
    EXPECT_LT(errors.from_scratch, pull_bound) << "k = 1e" << e << " diag";
    EXPECT_LT(errors.factor_update, pull_bound) << "k = 1e" << e << " diag";
    if (e <= 3) {
      EXPECT_LT(errors.from_scratch, 1e-12);
      EXPECT_LT(errors.factor_update, 1e-12);
    }
    // The two references agree while the dense one is accurate (1e-19 k cond(A)).
    const std::vector<Spring> stiff = [&] {
      std::vector<Spring> copy = springs;
      for (Spring& s : copy) {
        s.stiffness = scale * std::pow(10.0, e);
      }
      return copy;
    }();
    const double references = relative_error(dense_reference(a, b, {&stiff[0], &stiff[1]}),
                                             reference(a, b, {&stiff[0], &stiff[1]}));
    // Measured 1e-17 at k = 1 growing as 1e-19 k / diag(A) to 7e-12 at 1e8.
    EXPECT_LT(references, 1e-16 * std::max(1.0, std::pow(10.0, e - 2)));
    std::printf("        references differ by %.1e\n", references);
  }
}

TEST(LowRankUpdate, CoincidentStiffSpringsLoseDigitsWithTheCapacitance) {
  // Two springs at one parameter with different targets: U^T A^{-1} U is singular, so the
  // capacitance matrix has rcond ~ 1 / (k u^T A^{-1} u) and the Woodbury correction loses
  // log10(1 / rcond) digits. Folding them into the factor (min_capacitance_rcond) is no cure:
  // their pull then goes into B and loses log10(k / diag) digits, more.
  const SparseMatrix a = sheet_matrix(kSide);
  const Eigen::MatrixXd b = random_block(a.rows(), kColumns, 51);
  std::mt19937 engine(52);
  const double scale = a.diagonal().mean();
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  for (const double rcond_limit : {0.0, 1e-5}) {
    for (int e = 0; e <= 8; e += 2) {
      Spring first = make_spring(engine, scale * std::pow(10.0, e));
      Spring second = first;
      second.target = {0.5, -0.5, 0.25};
      LowRankSettings settings;
      settings.min_capacitance_rcond = rcond_limit;
      LowRankUpdate solver(settings);
      solver.factorize(a);
      add(solver, first);
      add(solver, second);
      Eigen::MatrixXd x = b;
      solver.solve_in_place(x);  // both new: nothing to fold yet
      const double rcond = solver.capacitance_rcond();
      const double woodbury = relative_error(x, reference(a, b, {&first, &second}));
      x = b;
      solver.solve_in_place(x);  // neither moved: folded if rcond < the limit
      const double second_solve = relative_error(x, reference(a, b, {&first, &second}));
      std::printf(
          "limit %g, k 1e%d diag: rcond(C) %.1e, Woodbury %.1e, second solve %.1e (%d "
          "Woodbury terms)\n",
          rcond_limit, e, rcond, woodbury, second_solve, solver.woodbury_term_count());
      // Measured: 6e-15 (k = 1), 7e-14 (1e4), 4e-12 (1e6, rcond 3e-6), 5e-10 (1e8, rcond 3e-8):
      // about 0.07 eps / rcond(C).
      EXPECT_LT(woodbury, std::max(1e-13, kEps / rcond)) << "k = 1e" << e;
      const bool folded = rcond < rcond_limit;
      EXPECT_EQ(solver.woodbury_term_count(), folded ? 0 : 2);
      // Folded: measured 6e-11 at 1e6 and 3e-8 at 1e8, the 1e-16 k / diag of the pull in B.
      EXPECT_LT(second_solve, folded ? 1e-15 * std::pow(10.0, e) : std::max(1e-13, kEps / rcond));
    }
  }
}

TEST(LowRankUpdate, FoldsOnlyWhatItMust) {
  const SparseMatrix a = sheet_matrix(kSide);
  const Eigen::MatrixXd b = random_block(a.rows(), kColumns, 61);
  std::mt19937 engine(62);
  const double scale = a.diagonal().mean();
  LowRankSettings settings;
  settings.max_woodbury_terms = 2;
  LowRankUpdate solver(settings);
  std::vector<Spring> springs;
  for (int i = 0; i < 3; ++i) {
    springs.push_back(make_spring(engine, 10.0 * scale));
    add(solver, springs.back());  // before the first factorize: placed by it
  }
  solver.factorize(a);
  EXPECT_EQ(solver.factorization_count(), 1);
  EXPECT_EQ(solver.woodbury_term_count(), 3);  // factorize keeps terms out of the factor
  const auto check = [&] {
    Eigen::MatrixXd x = b;
    solver.solve_in_place(x);
    // k = 10 diag: cond below 1e3; measured 4e-15.
    EXPECT_LT(relative_error(x, reference(a, b, {&springs[0], &springs[1], &springs[2]})), 1e-13);
  };
  check();  // 3 > 2 Woodbury terms, but all new (moved): none can be folded yet
  EXPECT_EQ(solver.factorization_count(), 2);
  EXPECT_EQ(solver.woodbury_term_count(), 3);
  check();  // unmoved now: all folded
  EXPECT_EQ(solver.factorization_count(), 3);
  EXPECT_EQ(solver.woodbury_term_count(), 0);
  springs[1] = make_spring(engine, 10.0 * scale);
  move(solver, 1, springs[1]);  // a folded term moves: one refactorization, then Woodbury
  check();
  EXPECT_EQ(solver.factorization_count(), 4);
  EXPECT_EQ(solver.woodbury_term_count(), 1);
  springs[1] = make_spring(engine, 10.0 * scale);
  move(solver, 1, springs[1]);  // dragged further: Woodbury only
  check();
  EXPECT_EQ(solver.factorization_count(), 4);
  EXPECT_EQ(solver.term_count(), 3);
}

TEST(LowRankUpdate, DragStepAllocatesNothing) {
  const SparseMatrix a = sheet_matrix(kSide);
  std::mt19937 engine(71);
  LowRankUpdate solver;
  solver.factorize(a);
  Spring spring = make_spring(engine, 100.0);
  const int id = add(solver, spring);
  add(solver, make_spring(engine, 50.0));
  Eigen::MatrixXd x = random_block(a.rows(), kColumns, 72);
  solver.solve_in_place(x);
  move(solver, id, make_spring(engine, 100.0));
  solver.solve_in_place(x);  // first drag step: workspace of width 3 + 1
  const Spring next = make_spring(engine, 100.0);
  testing::allocations = 0;
  testing::count_allocations = true;
  move(solver, id, next);
  solver.solve_in_place(x);
  testing::count_allocations = false;
  EXPECT_EQ(testing::allocations.load(), 0);
}

TEST(LowRankUpdate, BadTermsAreNamed) {
  LowRankUpdate solver;
  solver.factorize(sheet_matrix(4));
  const std::vector<int> rows = {1, 2};
  const std::vector<double> values = {0.5, 0.5};
  const auto message = [&](auto&& call) {
    try {
      call();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([&] { solver.add_term(rows, values, 0.0); }).find("stiffness is 0"),
            std::string::npos);
  EXPECT_NE(message([&] {
              solver.add_term(std::vector<int>{1, 16}, values, 1.0);
            }).find("row 16"),
            std::string::npos);
  EXPECT_NE(message([&] {
              solver.add_term(std::vector<int>{3, 3}, values, 1.0);
            }).find("row 3 appears twice"),
            std::string::npos);
  const std::vector<double> nan = {0.5, std::numeric_limits<double>::quiet_NaN()};
  EXPECT_NE(message([&] { solver.add_term(rows, nan, 1.0); }).find("is nan"), std::string::npos);
  EXPECT_NE(message([&] { solver.move_term(7, rows, values, 1.0); }).find("no term 7"),
            std::string::npos);
  const std::vector<double> target = {1.0, 2.0};
  solver.add_term(rows, values, 1.0, target);
  Eigen::MatrixXd b = Eigen::MatrixXd::Ones(16, 3);
  EXPECT_NE(message([&] { solver.solve_in_place(b); }).find("a target has 2 entries"),
            std::string::npos);
  EXPECT_THROW(LowRankUpdate({LowRankMethod::kWoodbury, {}, -1, 0.0}), Error);
  // Terms added, moved and removed before the first factorize are only recorded.
  for (const LowRankMethod method : {LowRankMethod::kWoodbury, LowRankMethod::kFactorUpdate}) {
    LowRankUpdate early({method, {}, 32, 0.0});
    const int first = early.add_term(rows, values, 1.0);
    early.add_term(std::vector<int>{5, 6}, values, 2.0);
    early.move_term(first, std::vector<int>{2, 3}, values, 3.0);
    early.remove_term(first);
    EXPECT_EQ(early.term_count(), 1);
    EXPECT_THROW(early.solve_in_place(b), Error);  // not factored yet
    EXPECT_THROW(early.add_term(std::vector<int>{-1}, std::vector<double>{1.0}, 1.0), Error);
    EXPECT_THROW(early.factorize(sheet_matrix(2)), Error);  // rows 5 and 6 of a 4 by 4 matrix
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, LowRankMethods,
                         ::testing::Values(LowRankMethod::kWoodbury, LowRankMethod::kFactorUpdate),
                         method_name);

}  // namespace
}  // namespace dnurbs
