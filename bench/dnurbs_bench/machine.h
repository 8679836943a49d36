#pragma once
// Machine section of dnurbs-bench: the memory bandwidth of a streaming triad a = b + s c, and for
// each model family the time of one back-substitution with the factor its step uses and of one
// vector pass at that bandwidth, with the model's step as a ratio to both floors. Writes
// machine.csv.

#include "bench_support.h"

namespace dnurbs::bench {

void run_machine(const BenchOptions& options);

}  // namespace dnurbs::bench
