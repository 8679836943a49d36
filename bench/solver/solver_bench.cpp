// bench/solver: SimplicialLDLT against CHOLMOD supernodal on the step matrices of clamped bicubic
// sheets (factor and three-column solve), and the cost of implicit springs: Woodbury on the solve
// against CHOLMOD's factor update/downdate. Prints tables; README.md beside this file holds the
// measured numbers and the choice of kDefaultSupernodalThreshold.
//
// solver_bench [--quick] [--sides 10,32,100] [--budget SECONDS]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bench/common/bench_arguments.h"
#include "bench/solver/sheet_matrix.h"
#include "dnurbs/core/cholmod_factor.h"
#include "dnurbs/core/low_rank_update.h"
#include "dnurbs/core/sparse_cholesky.h"

namespace dnurbs::bench {
namespace {

struct Options {
  std::vector<int> sides{10, 15, 21, 32, 45, 64, 100, 141, 200, 316};
  std::vector<int> spring_sides{32, 100, 200, 316};
  double budget = 0.5;  // seconds per measured operation (at least kMinRepeats calls)
  bool quick = false;
};

constexpr int kMinRepeats = 5;
constexpr int kMaxRepeats = 400;

struct Operation {
  std::function<void()> prepare;  // untimed (copies of right-hand sides)
  std::function<void()> work;     // timed
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

// Median seconds of each operation, measured interleaved (op 0, op 1, ..., op 0, ...) so that a
// slow phase of the shared machine hits every operation alike; one untimed warm-up round.
std::vector<double> time_interleaved(const std::vector<Operation>& operations, double budget) {
  std::vector<std::vector<double>> samples(operations.size());
  for (const Operation& op : operations) {
    op.prepare();
    op.work();
  }
  double total = 0.0;
  for (int repeat = 0; repeat < kMaxRepeats; ++repeat) {
    if (repeat >= kMinRepeats && total > budget * static_cast<double>(operations.size())) {
      break;
    }
    for (size_t i = 0; i < operations.size(); ++i) {
      operations[i].prepare();
      const auto start = std::chrono::steady_clock::now();
      operations[i].work();
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      samples[i].push_back(seconds);
      total += seconds;
    }
  }
  std::vector<double> medians;
  medians.reserve(samples.size());
  for (const std::vector<double>& s : samples) {
    medians.push_back(median(s));
  }
  return medians;
}

double seconds_of(const std::function<void()>& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Eigen::MatrixXd random_block(Eigen::Index rows, Eigen::Index cols, unsigned seed) {
  std::mt19937 engine(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::MatrixXd block(rows, cols);
  for (Eigen::Index i = 0; i < block.size(); ++i) {
    block.data()[i] = uniform(engine);
  }
  return block;
}

// Factor and solve times of both backends on one sheet.
void backend_row(int side, double budget) {
  const SheetMatrix sheet = make_sheet_matrix(side);
  const Eigen::SparseMatrix<double>& a = sheet.step_matrix;
  const Eigen::Index n = a.rows();
  SparseCholesky simplicial({CholeskyBackend::kSimplicialLdlt, 0});
  SparseCholesky supernodal({CholeskyBackend::kCholmodSupernodal, 0});
  const double analyze_s = seconds_of([&] { simplicial.analyze(a); });
  const double analyze_c = seconds_of([&] { supernodal.analyze(a); });
  const Eigen::MatrixXd rhs = random_block(n, 4, 1);
  Eigen::MatrixXd b3(n, 3), b4(n, 4);
  const auto copy3 = [&] { b3 = rhs.leftCols(3); };
  const auto copy4 = [&] { b4 = rhs; };
  const auto none = [] {};
  const std::vector<double> t = time_interleaved({{none, [&] { simplicial.factorize(a); }},
                                                  {none, [&] { supernodal.factorize(a); }},
                                                  {copy3, [&] { simplicial.solve_in_place(b3); }},
                                                  {copy3, [&] { supernodal.solve_in_place(b3); }},
                                                  {copy4, [&] { simplicial.solve_in_place(b4); }},
                                                  {copy4, [&] { supernodal.solve_in_place(b4); }}},
                                                 budget);
  std::printf(
      "%7ld %9ld %9.0f %9.0f | %7.2f %7.2f | %9.3f %9.3f %5.2f | %8.3f %8.3f %5.2f | %8.3f "
      "%8.3f %5.2f\n",
      static_cast<long>(n), static_cast<long>(a.nonZeros()), simplicial.factor_nonzeros(),
      supernodal.factor_nonzeros(), 1e3 * analyze_s, 1e3 * analyze_c, 1e3 * t[0], 1e3 * t[1],
      t[0] / t[1], 1e3 * t[2], 1e3 * t[3], t[2] / t[3], 1e3 * t[4], 1e3 * t[5], t[4] / t[5]);
  std::fflush(stdout);
}

// Four springs on one sheet, spring 0 dragged along a small random walk.
struct Springs {
  const SheetMatrix& sheet;
  std::vector<Eigen::Vector2d> parameters;
  std::vector<Eigen::Vector3d> targets;
  double stiffness = 0.0;
  std::mt19937 engine{7};

  void add_to(LowRankUpdate& solver) const {
    for (size_t i = 0; i < parameters.size(); ++i) {
      const SpringBasis basis = spring_basis(sheet, parameters[i].x(), parameters[i].y());
      solver.add_term(basis.rows, basis.values, stiffness, {targets[i].data(), 3});
    }
  }
  void step() {
    std::uniform_real_distribution<double> walk(-2e-3, 2e-3);
    for (int d = 0; d < 2; ++d) {
      parameters[0][d] = std::clamp(parameters[0][d] + walk(engine), 0.05, 0.95);
    }
    targets[0] += Eigen::Vector3d(walk(engine), walk(engine), walk(engine));
  }
  void move_in(LowRankUpdate& solver) const {
    const SpringBasis basis = spring_basis(sheet, parameters[0].x(), parameters[0].y());
    solver.move_term(0, basis.rows, basis.values, stiffness, {targets[0].data(), 3});
  }
};

// Returns the largest relative difference between the Woodbury and factor-update solutions of
// the last drag step (both solve the same system).
double spring_row(int side, double budget) {
  const SheetMatrix sheet = make_sheet_matrix(side);
  const Eigen::SparseMatrix<double>& a = sheet.step_matrix;
  const Eigen::Index n = a.rows();
  Springs springs{sheet, {}, {}, 100.0 * a.diagonal().mean()};
  std::mt19937 engine(3);
  std::uniform_real_distribution<double> uniform(0.1, 0.9);
  for (int i = 0; i < 4; ++i) {
    springs.parameters.emplace_back(uniform(engine), uniform(engine));
    springs.targets.emplace_back(uniform(engine), uniform(engine), uniform(engine));
  }
  SparseCholesky plain;
  double refactor_seconds = seconds_of([&] { plain.factorize(a); });
  LowRankSettings woodbury_settings;
  LowRankSettings update_settings;
  update_settings.method = LowRankMethod::kFactorUpdate;
  LowRankUpdate woodbury_fixed(woodbury_settings), woodbury_drag(woodbury_settings);
  LowRankUpdate update_fixed(update_settings), update_drag(update_settings);
  for (LowRankUpdate* solver : {&woodbury_fixed, &woodbury_drag, &update_fixed, &update_drag}) {
    solver->factorize(a);
    springs.add_to(*solver);
  }
  const Eigen::MatrixXd rhs = random_block(n, 3, 2);
  Eigen::MatrixXd b(n, 3), b_woodbury(n, 3), b_update(n, 3);
  const auto copy = [&] { b = rhs; };
  const auto none = [] {};
  const std::vector<double> t = time_interleaved({{copy, [&] { plain.solve_in_place(b); }},
                                                  {copy, [&] { woodbury_fixed.solve_in_place(b); }},
                                                  {[&] {
                                                     springs.step();
                                                     b = rhs;
                                                   },
                                                   [&] {
                                                     springs.move_in(woodbury_drag);
                                                     woodbury_drag.solve_in_place(b);
                                                   }},
                                                  {copy, [&] { update_fixed.solve_in_place(b); }},
                                                  {[&] { b = rhs; },
                                                   [&] {
                                                     springs.move_in(update_drag);
                                                     update_drag.solve_in_place(b);
                                                   }},
                                                  {none, [&] { plain.factorize(a); }}},
                                                 budget);
  refactor_seconds = t[5];
  b_woodbury = rhs;
  woodbury_drag.solve_in_place(b_woodbury);
  b_update = rhs;
  update_drag.solve_in_place(b_update);
  const double difference = (b_woodbury - b_update).norm() / b_update.norm();
  std::printf(
      "%7ld %-9s | %8.3f %8.3f %8.3f %8.3f %8.3f | %5.2f %5.2f %5.2f | %5.2f %5.2f %5.2f | "
      "%6.1f | %.1e\n",
      static_cast<long>(n),
      plain.backend() == CholeskyBackend::kCholmodSupernodal ? "cholmod" : "simplicial", 1e3 * t[0],
      1e3 * t[1], 1e3 * t[2], 1e3 * t[3], 1e3 * t[4], t[1] / t[0], t[2] / t[1], t[2] / t[0],
      t[3] / t[0], t[4] / t[0], t[4] / t[2], refactor_seconds / t[0], difference);
  std::fflush(stdout);
  return difference;
}

int thread_count() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("Threads:", 0) == 0) {
      return std::stoi(line.substr(8));
    }
  }
  return -1;
}

std::vector<int> parse_sides(const std::string& text) {
  std::vector<int> sides;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    sides.push_back(std::stoi(item));
  }
  return sides;
}

int run(const Options& options) {
  const bool openblas = limit_blas_to_one_thread();
  std::printf("BLAS: %s\n", openblas ? "OpenBLAS, limited to one thread"
                                     : "no OpenBLAS thread setting found (reference BLAS?)");
  std::printf(
      "\nFactor and solve, step matrix of a side x side clamped bicubic sheet "
      "(ms, medians; s = SimplicialLDLT, c = CHOLMOD supernodal; ratio s/c)\n");
  std::printf("%7s %9s %9s %9s | %7s %7s | %9s %9s %5s | %8s %8s %5s | %8s %8s %5s\n", "n",
              "nnz(A)", "nnz(L)s", "nnz(L)c", "anal.s", "anal.c", "factor s", "factor c", "ratio",
              "solve3 s", "solve3 c", "ratio", "solve4 s", "solve4 c", "ratio");
  for (const int side : options.sides) {
    backend_row(side, options.budget);
  }
  std::printf(
      "\nImplicit springs (4 springs, k = 100 mean(diag A); drag: spring 0's parameter and "
      "target move every step), 3 columns, ms (medians)\n");
  std::printf("%7s %-9s | %8s %8s %8s %8s %8s | %5s %5s %5s | %5s %5s %5s | %6s | %s\n", "n",
              "backend", "plain", "W fixed", "W drag", "U fixed", "U drag", "Wf/p", "Wd/Wf", "Wd/p",
              "Uf/p", "Ud/p", "Ud/Wd", "fact/p", "|xW-xU|/|x|");
  double worst = 0.0;
  for (const int side : options.spring_sides) {
    worst = std::max(worst, spring_row(side, options.budget));
  }
  std::printf("\nthreads in this process at the end: %d\n", thread_count());
  // Both spring methods solve one system: they must agree to rounding (conditioning of the
  // step matrix plus springs is below 1e6 here, so 1e-9 leaves a wide margin).
  if (!(worst < 1e-9)) {
    std::fprintf(stderr, "BOUND EXCEEDED: Woodbury and factor update differ by %.3e\n", worst);
    return 1;
  }
  return 0;
}

}  // namespace
}  // namespace dnurbs::bench

int main(int argc, char** argv) {
  dnurbs::bench::Options options;
  const auto unknown = dnurbs::bench::read_bench_arguments(
      argc, argv,
      [&] {
        options.quick = true;
        options.sides = {10, 32};
        options.spring_sides = {10, 32};
        options.budget = 0.02;
      },
      {{"--sides", [&](const char* value) { options.sides = dnurbs::bench::parse_sides(value); }},
       {"--spring-sides",
        [&](const char* value) { options.spring_sides = dnurbs::bench::parse_sides(value); }},
       {"--budget", [&](const char* value) { options.budget = std::stod(value); }}});
  if (unknown) {
    std::fprintf(stderr,
                 "usage: solver_bench [--quick] [--sides a,b,..] [--spring-sides a,b,..] "
                 "[--budget seconds]\n");
    return 2;
  }
  return dnurbs::bench::run(options);
}
