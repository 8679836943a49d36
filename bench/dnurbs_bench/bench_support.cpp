#include "bench_support.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

#include <Eigen/SparseCholesky>

#include "dnurbs/core/error.h"

namespace dnurbs::bench {

double time_per_call(const std::function<void()>& work, double minimum_seconds) {
  work();
  std::vector<double> calls;
  const Stopwatch total;
  while (calls.size() < 3 || total.seconds() < minimum_seconds) {
    const Stopwatch call;
    work();
    calls.push_back(call.seconds());
  }
  // The median: robust against the load spikes of a shared machine.
  std::nth_element(calls.begin(), calls.begin() + static_cast<std::ptrdiff_t>(calls.size() / 2),
                   calls.end());
  return calls[calls.size() / 2];
}

void BoundChecks::expect(bool ok, const std::string& what) {
  if (!ok) {
    ++failures_;
    std::cerr << "BOUND EXCEEDED: " << what << '\n';
  }
}

CsvFile::CsvFile(const std::filesystem::path& path, const std::vector<std::string>& header)
    : stream_(path), columns_(header.size()) {
  if (!stream_) {
    throw Error("cannot write CSV file '" + path.string() + "'");
  }
  row(header);
}

void CsvFile::row(const std::vector<std::string>& fields) {
  if (fields.size() != columns_) {
    throw Error("CSV row of " + std::to_string(fields.size()) + " fields, header has " +
                std::to_string(columns_));
  }
  for (std::size_t i = 0; i < fields.size(); ++i) {
    stream_ << (i ? "," : "") << fields[i];
  }
  stream_ << '\n';
}

std::string number(double value) {
  std::ostringstream text;
  text.precision(6);
  text << value;
  return text.str();
}

double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size() || x.size() < 2) {
    throw Error("log_log_slope needs two or more (x, y) pairs, got " + std::to_string(x.size()));
  }
  double mean_x = 0.0;
  double mean_y = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0.0) || !(y[i] > 0.0)) {
      throw Error("log_log_slope needs positive values, got (" + number(x[i]) + ", " +
                  number(y[i]) + ")");
    }
    mean_x += std::log(x[i]) / static_cast<double>(x.size());
    mean_y += std::log(y[i]) / static_cast<double>(y.size());
  }
  double sxy = 0.0;
  double sxx = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (std::log(x[i]) - mean_x) * (std::log(y[i]) - mean_y);
    sxx += (std::log(x[i]) - mean_x) * (std::log(x[i]) - mean_x);
  }
  if (sxx == 0.0) {
    throw Error("log_log_slope needs two distinct x values");
  }
  return sxy / sxx;
}

namespace {

// Rows and columns of `matrix` kept where `keep` is true, renumbered in order.
SparseMatrix restrict_to(const SparseMatrix& matrix, const std::vector<bool>& keep) {
  std::vector<int> index(keep.size(), -1);
  int count = 0;
  for (std::size_t i = 0; i < keep.size(); ++i) {
    if (keep[i]) {
      index[i] = count++;
    }
  }
  std::vector<Eigen::Triplet<double>> triplets;
  for (int j = 0; j < matrix.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(matrix, j); it; ++it) {
      const int r = index[static_cast<std::size_t>(it.row())];
      const int c = index[static_cast<std::size_t>(j)];
      if (r >= 0 && c >= 0) {
        triplets.emplace_back(r, c, it.value());
      }
    }
  }
  SparseMatrix result(count, count);
  result.setFromTriplets(triplets.begin(), triplets.end());
  return result;
}

SparseMatrix newmark_matrix(const ModelMatrices& matrices, double dt) {
  SparseMatrix a = matrices.mass;
  if (matrices.damping.nonZeros() > 0) {
    a += 0.5 * dt * matrices.damping;
  }
  if (matrices.stiffness.nonZeros() > 0) {
    a += 0.25 * dt * dt * matrices.stiffness;
  }
  return a;
}

}  // namespace

double back_substitution_seconds(const System& system, double dt, double minimum_seconds) {
  const bool kronecker = system.kronecker_block_size() == 3;
  ModelMatrices assembled;
  const ModelMatrices* matrices = nullptr;
  if (kronecker) {
    matrices = system.scalar_matrices();
  } else if (system.matrices_are_constant()) {
    matrices = system.constant_matrices();
  } else {
    system.assemble_matrices(system.coordinates(), assembled);
    matrices = &assembled;
  }
  const int block = kronecker ? 3 : 1;
  std::vector<bool> keep(static_cast<std::size_t>(matrices->mass.rows()), true);
  for (const int fixed : system.fixed_coordinates()) {
    keep[static_cast<std::size_t>(fixed / block)] = false;
  }
  const SparseMatrix reduced = restrict_to(newmark_matrix(*matrices, dt), keep);
  const Eigen::SimplicialLDLT<SparseMatrix> solver(reduced);
  if (solver.info() != Eigen::Success) {
    throw Error("back_substitution_seconds: the Newmark matrix cannot be factored");
  }
  const Eigen::MatrixXd rhs = Eigen::MatrixXd::Random(reduced.rows(), block);
  Eigen::MatrixXd x(reduced.rows(), block);
  return time_per_call([&] { x = solver.solve(rhs); }, minimum_seconds);
}

}  // namespace dnurbs::bench
