#pragma once
// Needs section of dnurbs-bench: each automatic choice that models only what a scene needs,
// timed against the naive path it replaces:
//   - D-NURBS weights stay fixed unless freed (3 coordinates per control point and constant,
//     once-factored matrices, against free weights: 4 per point, re-assembly every step);
//   - a rigid superquadric steps as a 6-coordinate body (against the same body with its global
//     and local deformations as coordinates);
//   - PDE-surface nodes outside every deformation region are not simulated (against the
//     whole grid);
//   - a surface of revolution sculpted as a swung surface, 2 (m + n) coordinates (against the
//     tensor-product surface of the same shape, 3 m n).
// Writes needs.csv (model, active and total coordinates, constant matrices, naive and chosen
// seconds per step, saving ratio).

#include "bench_support.h"

namespace dnurbs::bench {

void run_needs(const BenchOptions& options, BoundChecks& checks);

}  // namespace dnurbs::bench
