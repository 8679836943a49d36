#include "machine.h"

#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "bench_scenes.h"
#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "step_timing.h"

namespace dnurbs::bench {

namespace {

// Best-of-repetitions bandwidth of a = b + s c over arrays far larger than the caches, counting
// the three streams (24 bytes per entry; write-allocate traffic is not counted).
double triad_bandwidth_gb_per_s(Eigen::Index length, int repetitions) {
  Eigen::VectorXd a = Eigen::VectorXd::Zero(length);
  const Eigen::VectorXd b = Eigen::VectorXd::Constant(length, 1.0);
  const Eigen::VectorXd c = Eigen::VectorXd::Constant(length, 2.0);
  double best = 1e300;
  for (int r = 0; r < repetitions; ++r) {
    const Stopwatch watch;
    a.noalias() = b + 0.5 * c;
    best = std::min(best, watch.seconds());
  }
  if (a[length / 2] != 2.0) {  // keeps the kernel observable (b + 0.5 c = 2 exactly)
    throw Error("triad kernel produced " + number(a[length / 2]) + ", expected 2");
  }
  return 24.0 * static_cast<double>(length) / best / 1e9;
}

struct MachineModel {
  std::string name;
  System system;
  IntegratorSettings settings;
  double dt = 1e-3;
};

}  // namespace

void run_machine(const BenchOptions& options) {
  const double minimum_seconds = options.quick ? 0.02 : 0.3;
  const double bandwidth =
      triad_bandwidth_gb_per_s(options.quick ? (1 << 20) : (1 << 23), options.quick ? 3 : 10);
  std::cerr << "machine: triad bandwidth " << bandwidth << " GB/s\n";

  std::vector<MachineModel> models;
  {
    System curve(clamped_string(options.quick ? 334 : 3334, WeightMode::kFixed));
    curve.add_force(0, point_force(Eigen::Vector2d(0.5, 0.0), Eigen::Vector3d(0, 0, 1e-3)));
    models.push_back({"dnurbs_curve_fixed_weights", curve, {}, 1e-3});
    System surface(clamped_membrane(options.quick ? 18 : 58, WeightMode::kFixed, 0.1));
    surface.add_force(0, point_force(Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d(0, 0, 1e-3)));
    models.push_back({"dnurbs_surface_fixed_weights", surface, {}, 1e-3});
  }
  models.push_back({"pde_surface_region", pushed_pde_surface(options.quick ? 33 : 65, true),
                    IntegratorSettings{IntegratorScheme::kImplicitEuler}, 1.0 / 240.0});
  models.push_back({"terzopoulos_sheet", pushed_terzopoulos_sheet(), {}, 5e-3});
  models.push_back({"superquadric_rigid",
                    spinning_superquadric(DeformableSuperquadricParts::rigid()),
                    {},
                    1e-2});

  CsvFile csv(
      options.out_dir / "machine.csv",
      {"model", "coordinates", "bandwidth_gb_per_s", "back_substitution_seconds",
       "vector_pass_seconds", "step_seconds", "step_to_back_substitution", "step_to_vector_pass"});
  for (const MachineModel& model : models) {
    const double solve = back_substitution_seconds(model.system, model.dt, minimum_seconds);
    const double step = seconds_per_step(model.system, model.settings, model.dt, minimum_seconds);
    // One pass over three vectors of the model's size (read two, write one) at the triad rate.
    const double pass = 24.0 * model.system.velocity_count() / (bandwidth * 1e9);
    csv.row({model.name, std::to_string(model.system.velocity_count()), number(bandwidth),
             number(solve), number(pass), number(step), number(step / solve), number(step / pass)});
    std::cerr << "machine: " << model.name << " step " << step << " s, " << step / solve
              << " back-substitutions\n";
  }
}

}  // namespace dnurbs::bench
