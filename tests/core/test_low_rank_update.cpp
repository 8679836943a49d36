#include "core/low_rank_update.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "tests/core/allocation_counter.h"
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
    for (const Spring& s : springs) {
      active.push_back(&s);
    }
    worst = std::max(worst, relative_error(x, reference(a, b, active)));
  }
  std::printf("largest relative error over 100 operations: %.2e\n", worst);
  // cond(A + sum k u u^T) <= 1e4 here; Woodbury and the update/downdate are backward stable at
  // these stiffnesses: the measured worst errors are at 1e-15.
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
    // MEASURED_SWEEP
    EXPECT_LT(errors.woodbury_target, 1e-12) << "k = 1e" << e << " diag";
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
    std::printf("        references differ by %.1e\n", references);
  }
}

TEST(LowRankUpdate, CoincidentStiffSprings) {
  // Two springs at one parameter with different targets: U^T A^{-1} U is singular, so the
  // capacitance matrix has rcond ~ 1 / (k u^T A^{-1} u).
  const SparseMatrix a = sheet_matrix(kSide);
  const Eigen::MatrixXd b = random_block(a.rows(), kColumns, 51);
  std::mt19937 engine(52);
  const double scale = a.diagonal().mean();
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
      solver.solve_in_place(x);
      const double error1 = relative_error(x, reference(a, b, {&first, &second}));
      x = b;
      solver.solve_in_place(x);
      const double error2 = relative_error(x, reference(a, b, {&first, &second}));
      std::printf("limit %g k 1e%d: rcond %.1e, first %.1e, second %.1e, woodbury terms %d\n",
                  rcond_limit, e, solver.capacitance_rcond(), error1, error2,
                  solver.woodbury_term_count());
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, LowRankMethods,
                         ::testing::Values(LowRankMethod::kWoodbury, LowRankMethod::kFactorUpdate),
                         method_name);

}  // namespace
}  // namespace dnurbs
