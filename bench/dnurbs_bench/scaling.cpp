#include "scaling.h"

#include <iostream>
#include <vector>

#include "bench_scenes.h"
#include "dnurbs/dynamics/core/forces.h"
#include "step_timing.h"

namespace dnurbs::bench {

void run_scaling(const BenchOptions& options) {
  const double dt = 1e-3;
  const double minimum_seconds = options.quick ? 0.02 : 0.3;
  const std::vector<int> sides =
      options.quick ? std::vector<int>{6, 12, 24} : std::vector<int>{6, 12, 24, 48, 96, 183};
  CsvFile csv(options.out_dir / "scaling.csv",
              {"coordinates", "seconds_per_step", "ratio_to_backsubstitution"});
  std::vector<double> coordinates;
  std::vector<double> steps;
  std::vector<double> solves;
  for (const int side : sides) {
    System system(clamped_membrane(side, WeightMode::kFixed, 0.1));
    system.add_force(0, point_force(Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d(0, 0, 1e-3)));
    const double step = seconds_per_step(system, IntegratorSettings{}, dt, minimum_seconds);
    const double solve = back_substitution_seconds(system, dt, minimum_seconds);
    csv.row({std::to_string(system.velocity_count()), number(step), number(step / solve)});
    std::cerr << "scaling: " << system.velocity_count() << " coordinates, " << step
              << " s/step, ratio " << step / solve << '\n';
    coordinates.push_back(system.velocity_count());
    steps.push_back(step);
    solves.push_back(solve);
  }
  CsvFile fit(options.out_dir / "scaling_fit.csv", {"quantity", "exponent"});
  fit.row({"seconds_per_step", number(log_log_slope(coordinates, steps))});
  fit.row({"back_substitution", number(log_log_slope(coordinates, solves))});
  std::cerr << "scaling: fitted exponent " << log_log_slope(coordinates, steps) << '\n';
}

}  // namespace dnurbs::bench
