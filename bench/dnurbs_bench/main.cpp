// dnurbs-bench: speed against error for every model family (bench/README.md).
//
// Usage: dnurbs-bench [--out DIR] [--quick]
//   --out DIR  directory of the CSV files (created if missing; default ".")
//   --quick    smallest sizes and fewest steps: a smoke test of seconds
// Exit status 1 if a measured error leaves its physical bound (the bound checks of each
// section, printed on stderr), 2 for a usage error.

#include <filesystem>
#include <iostream>
#include <string>

#include "bench_support.h"
#include "dnurbs/core/error.h"
#include "machine.h"
#include "needs.h"
#include "scaling.h"
#include "work_precision.h"

int main(int argc, char** argv) {
  using namespace dnurbs::bench;
  BenchOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--quick") {
      options.quick = true;
    } else if (argument == "--out" && i + 1 < argc) {
      options.out_dir = argv[++i];
    } else {
      std::cerr << "dnurbs-bench: unknown argument '" << argument
                << "'\nusage: dnurbs-bench [--out DIR] [--quick]\n";
      return 2;
    }
  }
  try {
    std::filesystem::create_directories(options.out_dir);
    BoundChecks checks;
    const Stopwatch watch;
    run_machine(options);
    run_work_precision(options, checks);
    run_scaling(options);
    run_needs(options, checks);
    std::cerr << "dnurbs-bench: " << watch.seconds() << " s, " << checks.failures()
              << " bound(s) exceeded; CSV files in " << options.out_dir.string() << '\n';
    return checks.failures() == 0 ? 0 : 1;
  } catch (const std::exception& error) {
    std::cerr << "dnurbs-bench: " << error.what() << '\n';
    return 1;
  }
}
