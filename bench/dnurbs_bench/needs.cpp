#include "needs.h"

#include <iostream>
#include <string>

#include "bench_scenes.h"
#include "dynamics/forces.h"
#include "step_timing.h"

namespace dnurbs::bench {

namespace {

std::string constant_matrices(const System& system) {
  return system.matrices_are_constant() ? "M D K" : "none";
}

int active_coordinates(const System& system) {
  return system.velocity_count() - static_cast<int>(system.fixed_coordinates().size());
}

}  // namespace

void run_needs(const BenchOptions& options, BoundChecks& checks) {
  const double minimum_seconds = options.quick ? 0.02 : 0.3;
  CsvFile csv(options.out_dir / "needs.csv",
              {"model", "active_coordinates", "total_coordinates", "constant_matrices",
               "naive_seconds_per_step", "chosen_seconds_per_step", "saving_ratio"});
  auto report = [&](const std::string& name, const System& chosen, const System& naive,
                    double naive_step, double chosen_step) {
    csv.row({name, std::to_string(active_coordinates(chosen)),
             std::to_string(active_coordinates(naive)), constant_matrices(chosen),
             number(naive_step), number(chosen_step), number(naive_step / chosen_step)});
    std::cerr << "needs: " << name << ' ' << active_coordinates(chosen) << " of "
              << active_coordinates(naive) << " coordinates, saving " << naive_step / chosen_step
              << '\n';
    // The chosen path solves a subset of the naive path's coordinates with the same scheme.
    checks.expect(active_coordinates(chosen) <= active_coordinates(naive),
                  name + ": chosen path has more active coordinates than the naive one");
  };

  // Fixed against free weights, same membrane. Free weights are light coordinates: dt = 1e-5
  // (dynamics_step_bench), a blown-up step restarts (counted).
  {
    const int side = options.quick ? 6 : 12;
    System fixed(clamped_membrane(side, WeightMode::kFixed, 0.1));
    System free(clamped_membrane(side, WeightMode::kFree, 0.1));
    for (System* system : {&fixed, &free}) {
      system->add_force(0, point_force(Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d(0, 0, 1e-3)));
    }
    int restarts = 0;
    const double naive =
        seconds_per_step(free, IntegratorSettings{}, 1e-5, minimum_seconds, &restarts);
    const double chosen = seconds_per_step(fixed, IntegratorSettings{}, 1e-5, minimum_seconds);
    if (restarts > 0) {
      std::cerr << "needs: free-weight membrane restarted " << restarts << " times\n";
    }
    report("dnurbs_surface_fixed_weights", fixed, free, naive, chosen);
  }
  // Rigid superquadric as a 6-coordinate body against the full deformable model.
  {
    const System rigid = spinning_superquadric(DeformableSuperquadricParts::rigid());
    const System full = spinning_superquadric(DeformableSuperquadricParts::full());
    const double naive = seconds_per_step(full, IntegratorSettings{}, 1e-2, minimum_seconds);
    const double chosen = seconds_per_step(rigid, IntegratorSettings{}, 1e-2, minimum_seconds);
    report("superquadric_rigid_parts", rigid, full, naive, chosen);
  }
  // PDE surface: deformation region against the whole grid.
  {
    const int nodes = options.quick ? 33 : 65;
    const System region = pushed_pde_surface(nodes, true);
    const System whole = pushed_pde_surface(nodes, false);
    const IntegratorSettings settings{IntegratorScheme::kImplicitEuler};
    const double naive = seconds_per_step(whole, settings, 1.0 / 240.0, minimum_seconds);
    const double chosen = seconds_per_step(region, settings, 1.0 / 240.0, minimum_seconds);
    report("pde_surface_deformation_region", region, whole, naive, chosen);
  }
}

}  // namespace dnurbs::bench
