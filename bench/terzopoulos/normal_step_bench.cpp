// bench/terzopoulos: the cost of the Christoffel normal against the classic one (Wu & de Melo,
// section 6: "much more intuitive results ... with small increment in the computational
// complexity"), bench/terzopoulos/README.md.
//
// The same scene with each normal approximation: the paper sheet of figures 5 and 7 (a clamped
// unit square of side x side nodes, eta_ii = 0.1, xi = 7e-7 (figure 5's largest, at which the
// classic normal does not yet fold), gamma = 0.5, a normal force of 0.01 on the middle nodes),
// stepped by the seed's semi-implicit step (dt = 0.005, the matrix from the current tensors). Every
// setup is first stepped 50 times into the pressed state, then timed with interleaved single steps
// (bench/common/interleaved_medians.h); ratios to the classic step are measured in one run.
//
// normal_step_bench [--quick] [--out DIR] [--budget SECONDS]

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "bench/common/bench_arguments.h"
#include "bench/common/interleaved_medians.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/dynamics/integrators/semi_implicit_step.h"
#include "dnurbs/surface/grid.h"

namespace dnurbs::bench {
namespace {

constexpr double kDt = 0.005;

struct Options {
  std::vector<int> sides{17, 33, 65};
  double budget = 1.0;
  std::string out;
};

// One sheet with one normal approximation and its stepper.
class SheetSetup {
 public:
  SheetSetup(int side, NormalApproximation normal) {
    const Grid grid(side, side, 1.0 / (side - 1));
    TerzopoulosMaterial paper;
    paper.damping_density = 0.5;
    paper.eta << 0.1, 0.0, 0.0, 0.1;
    paper.xi << 7e-7, 7e-7, 7e-7, 7e-7;
    TerzopoulosSettings settings;
    settings.normal = normal;
    TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()), paper,
                             settings);
    sheet.fix_border();
    system_.add_model(sheet);
    // The middle 3 x 3 nodes of a side of 17 (the paper scene) and their share of the sheet on
    // finer grids: a load over the square [7/16, 9/16]^2.
    const int first = (side - 1) * 7 / 16;
    const int last = (side - 1) * 9 / 16;
    const int count = (last - first + 1) * (last - first + 1);
    for (int j = first; j <= last; ++j) {
      for (int i = first; i <= last; ++i) {
        system_.add_force(0,
                          point_force(grid.parameter(i, j), Eigen::Vector3d(0, 0, -0.01 / count)));
      }
    }
    for (int s = 0; s < 50; ++s) {
      step();
    }
  }
  void step() { stepper_.step(system_, kDt); }

 private:
  System system_;
  SemiImplicitStepper stepper_;
};

int run(const Options& options) {
  const std::vector<NormalApproximation> normals{NormalApproximation::kClassic,
                                                 NormalApproximation::kChristoffel,
                                                 NormalApproximation::kChristoffelUnnormalized};
  std::ofstream csv;
  if (!options.out.empty()) {
    std::filesystem::create_directories(options.out);
    csv.open(std::filesystem::path(options.out) / "terzopoulos_normals.csv");
    csv << "side,nodes,classic_s,christoffel_s,unnormalized_s,christoffel_over_classic,"
           "unnormalized_over_classic\n";
  }
  std::printf("%6s %6s %12s %12s %12s %10s %10s\n", "side", "nodes", "classic [s]", "christoffel",
              "unnormalized", "chr/cls", "unn/cls");
  for (const int side : options.sides) {
    std::vector<std::unique_ptr<SheetSetup>> setups;
    setups.reserve(normals.size());
    for (const NormalApproximation normal : normals) {
      setups.push_back(std::make_unique<SheetSetup>(side, normal));
    }
    const std::vector<double> seconds = interleaved_medians(setups, options.budget, 7, 5000);
    std::printf("%6d %6d %12.4e %12.4e %12.4e %10.3f %10.3f\n", side, side * side, seconds[0],
                seconds[1], seconds[2], seconds[1] / seconds[0], seconds[2] / seconds[0]);
    if (csv.is_open()) {
      csv << side << "," << side * side << "," << seconds[0] << "," << seconds[1] << ","
          << seconds[2] << "," << seconds[1] / seconds[0] << "," << seconds[2] / seconds[0] << "\n";
    }
  }
  std::printf("normals timed: %s, %s, %s\n", to_string(normals[0]), to_string(normals[1]),
              to_string(normals[2]));
  return 0;
}

}  // namespace
}  // namespace dnurbs::bench

int main(int argc, char** argv) {
  dnurbs::bench::Options options;
  const auto unknown = dnurbs::bench::read_bench_arguments(
      argc, argv,
      [&] {
        options.sides = {17};
        options.budget = 0.05;
      },
      {{"--out", [&](const char* value) { options.out = value; }},
       {"--budget", [&](const char* value) { options.budget = std::stod(value); }}});
  if (unknown) {
    std::cerr << "normal_step_bench: unknown argument '" << *unknown
              << "' (usage: normal_step_bench [--quick] [--out DIR] [--budget SECONDS])\n";
    return 2;
  }
  return dnurbs::bench::run(options);
}
