#pragma once
// Scaling section of dnurbs-bench: Newmark step time of fixed-weight bicubic D-NURBS surfaces
// from about 1e2 to 1e5 coordinates, its ratio to one back-substitution with the same factor,
// and the fitted exponents (step ~ coordinates^exponent). Writes scaling.csv and
// scaling_fit.csv.

#include "bench_support.h"

namespace dnurbs::bench {

void run_scaling(const BenchOptions& options);

}  // namespace dnurbs::bench
