#pragma once
// Work-precision section of dnurbs-bench: error against wall time per simulated second for each
// model family, over integrators, time steps, quadrature orders and resolutions.
//
// Writes work_precision.csv (family, case, integrator, dt, quadrature, resolution, error,
// error_kind, seconds_per_simulated_second) and richardson.csv (the observed order of the
// converged references), and checks the measured orders against the schemes' orders.

#include "bench_support.h"

namespace dnurbs::bench {

void run_work_precision(const BenchOptions& options, BoundChecks& checks);

}  // namespace dnurbs::bench
