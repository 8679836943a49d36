#pragma once
// Shared pieces of dnurbs-bench: options, wall-clock timing, the bound checks that make the
// program fail when a measured error leaves its physical bound, CSV output, the fitted slope of
// a log-log line, and the back-substitution floor of a System.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "dnurbs/dynamics/core/system.h"

namespace dnurbs::bench {

/// Command-line options of dnurbs-bench.
struct BenchOptions {
  std::filesystem::path out_dir = ".";
  bool quick = false;  ///< smallest sizes and fewest time steps (a smoke test of seconds)
};

/// Wall-clock seconds since construction.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

/// Median seconds per call of `work` after one warm-up call, repeated until `minimum_seconds`
/// have passed (at least 3 calls).
double time_per_call(const std::function<void()>& work, double minimum_seconds);

/// Collects the bound checks: each failed check is printed on stderr and makes main return 1.
class BoundChecks {
 public:
  /// Records `what` (a sentence with the measured value and its bound) as failed unless `ok`.
  void expect(bool ok, const std::string& what);
  int failures() const { return failures_; }

 private:
  int failures_ = 0;
};

/// A CSV file with a fixed header; every row must have as many fields.
class CsvFile {
 public:
  CsvFile(const std::filesystem::path& path, const std::vector<std::string>& header);
  void row(const std::vector<std::string>& fields);

 private:
  std::ofstream stream_;
  std::size_t columns_ = 0;
};

/// Shortest round-trip text of a number ("inf", "nan" spelled out).
std::string number(double value);

/// Least-squares slope of log(y) against log(x) (the exponent of y ~ x^slope); needs two
/// distinct x > 0 and y > 0 (throws Error otherwise).
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y);

/// Seconds of one back-substitution with the factor of the Newmark matrix
/// A = M + dt/2 D + dt^2/4 K at the system's current state, on its free coordinates: the
/// scalar matrix with 3 right-hand sides when every model has the S (x) I_3 layout (the
/// integrators' Kronecker path), else the full matrix with one right-hand side. This is the
/// floor of any implicit step that factors once.
double back_substitution_seconds(const System& system, double dt, double minimum_seconds);

}  // namespace dnurbs::bench
