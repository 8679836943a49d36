// bench/floor: the fixed-weight D-NURBS step against its floor, the solve (bench/floor/README.md).
//
//   step / solve:  the Newmark step of a clamped bicubic sheet (IntegratorSettings defaults:
//                  CHOLMOD supernodal from kDefaultSupernodalThreshold free nodes on) over one
//                  CHOLMOD three-column solve of the same scalar step matrix;
//   LDLT / step:   at the largest size, the same step with SimplicialLDLT over the default step;
//   run path:      the 100 x 100 control-point sheet scene (generated here, written with --scene)
//                  stepped through SceneSimulation and run_scene, the code path of `dnurbs run`.
//
// Medians of interleaved single calls (one of each kind in turn) in process CPU time, so that a
// slow phase of the shared machine hits all kinds alike; ratios are measured in one run.
//
// floor_bench [--quick] [--sides 12,58,100,183] [--run-side 100] [--out DIR] [--scene FILE]

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "dnurbs/core/fixed_coordinates.h"
#include "dnurbs/core/kronecker.h"
#include "dnurbs/core/sparse_cholesky.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_runner.h"
#include "dnurbs/io/scene_simulation.h"

namespace dnurbs::bench {
namespace {

struct Options {
  std::vector<int> sides{12, 58, 100, 183};
  int run_side = 100;
  int run_steps = 120;
  std::string out;
  std::string scene;
  bool quick = false;
};

constexpr double kDt = 0.01;

// CPU seconds of the process (all its threads; OpenBLAS and CHOLMOD are held to the calling
// thread): on the shared 2-core machine wall time measured 4-25 s for the same 1.5 s of CPU
// work of one run, so the ratios are taken in CPU time.
double cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Median seconds of each call, interleaved, at least `repeats` each and `budget` seconds in all.
std::vector<double> interleaved(const std::vector<std::function<void()>>& calls, int repeats,
                                double budget) {
  std::vector<std::vector<double>> samples(calls.size());
  const double start = cpu_seconds();
  for (int r = 0; r < repeats || (cpu_seconds() - start < budget && r < 2000); ++r) {
    for (size_t k = 0; k < calls.size(); ++k) {
      const double t = cpu_seconds();
      calls[k]();
      samples[k].push_back(cpu_seconds() - t);
    }
  }
  std::vector<double> result;
  for (const auto& s : samples) {
    result.push_back(median(s));
  }
  return result;
}

// A clamped flat bicubic sheet of side x side control points at the Greville abscissae of a
// clamped uniform knot vector on [0, 1] (x(u, v) = (u, v, 0)), the material of the hat demo and
// a point force; `sculpting` adds a spring whose target rises and a probe, the scene of a
// sculpting session.
std::string sheet_scene_json(int side, int steps, bool sculpting) {
  const int p = 3;
  std::vector<double> knots(static_cast<size_t>(side + p + 1), 0.0);
  for (int i = 0; i <= side + p; ++i) {
    const int inner = std::clamp(i - p, 0, side - p);
    knots[static_cast<size_t>(i)] = static_cast<double>(inner) / (side - p);
  }
  std::ostringstream json;
  json.precision(17);
  json << R"({"models": [{"name": "sheet", "type": "dnurbs_surface", "shape": {)"
       << R"("type": "nurbs_surface", "degree_u": 3, "degree_v": 3, "knots_u": [)";
  std::ostringstream knot_list;
  knot_list.precision(17);
  for (size_t i = 0; i < knots.size(); ++i) {
    knot_list << (i > 0 ? ", " : "") << knots[i];
  }
  json << knot_list.str() << R"(], "knots_v": [)" << knot_list.str() << R"(], "control_points": [)";
  const auto greville = [&](int i) {
    return (knots[static_cast<size_t>(i + 1)] + knots[static_cast<size_t>(i + 2)] +
            knots[static_cast<size_t>(i + 3)]) /
           3.0;
  };
  for (int i = 0; i < side; ++i) {
    json << (i > 0 ? ", [" : "[");
    for (int j = 0; j < side; ++j) {
      json << (j > 0 ? ", [" : "[") << greville(i) << ", " << greville(j) << ", 0]";
    }
    json << "]";
  }
  json << R"(]}, "material": {"mass_density": 1, "damping_density": 4, "a10": 1, "a01": 1, )"
       << R"("b20": 0.2, "b11": 0.2, "b02": 0.2}, "boundary": {"clamp_border": true}}], )"
       << R"("forces": [{"type": "point", "model": "sheet", "at": [0.3, 0.4], "force": [0, 0, 1]})";
  if (sculpting) {
    json << R"(, {"type": "spring", "model": "sheet", "at": [0.5, 0.5], "stiffness": 50, )"
         << R"("target": {"times": [0, 1], "values": [[0.5, 0.5, 0], [0.5, 0.5, 0.5]]}}], )"
         << R"("probes": [{"name": "centre", "model": "sheet", "at": [0.5, 0.5]}], )";
  } else {
    json << "], ";
  }
  json << R"("integrator": {"scheme": "newmark", "dt": )" << kDt << "}, "
       << R"("run": {"steps": )" << steps << "}, "
       << R"("output": {"name": "sheet"}})";
  return json.str();
}

// The step of one sheet (integrator defaults, and SimplicialLDLT when `ldlt` is set) and a
// CHOLMOD three-column solve of its scalar step matrix M + gamma dt D + beta dt^2 K on the
// free nodes.
void step_against_solve(int side, bool ldlt, const Options& options, std::ostream& csv) {
  const SceneSimulation simulation(
      parse_scene_json(sheet_scene_json(side, 1, false), "<floor bench>"));
  const Model& model = simulation.system().model(0);
  const ModelMatrices& scalar = *model.scalar_matrices();
  std::vector<int> fixed = model.fixed_coordinates();
  std::sort(fixed.begin(), fixed.end());
  const FreeCoordinates free(static_cast<int>(scalar.mass.rows()), *fixed_nodes(fixed, 3));
  const double beta = 0.25;
  const double gamma = 0.5;
  const SparseMatrix a =
      free.reduce(scalar.mass + gamma * kDt * scalar.damping + beta * kDt * kDt * scalar.stiffness);
  SparseCholeskySettings blas_settings{CholeskyBackend::kCholmodSupernodal};
  blas_settings.triangular_solve = TriangularSolve::kBlas;
  SparseCholesky cholmod(blas_settings);
  cholmod.factorize(a);
  SparseCholesky panels(SparseCholeskySettings{CholeskyBackend::kCholmodSupernodal});
  panels.factorize(a);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const Eigen::MatrixXd b = Eigen::MatrixXd::NullaryExpr(
      a.rows(), 3, [&](Eigen::Index, Eigen::Index) { return uniform(random); });
  Eigen::MatrixXd x = b;
  Eigen::MatrixXd y = b;

  System automatic = simulation.system();
  Integrator integrator;  // defaults: kAutomatic
  System simplicial = simulation.system();
  IntegratorSettings ldlt_settings;
  ldlt_settings.cholesky.backend = CholeskyBackend::kSimplicialLdlt;
  Integrator ldlt_integrator(ldlt_settings);
  integrator.step(automatic, kDt);  // factorizations outside the timing
  if (ldlt) {
    ldlt_integrator.step(simplicial, kDt);
  }
  std::vector<std::function<void()>> calls = {[&] { integrator.step(automatic, kDt); },
                                              [&] {
                                                x = b;
                                                cholmod.solve_in_place(x);
                                              },
                                              [&] {
                                                y = b;
                                                panels.solve_in_place(y);
                                              }};
  if (ldlt) {
    calls.emplace_back([&] { ldlt_integrator.step(simplicial, kDt); });
  }
  const std::vector<double> t =
      interleaved(calls, options.quick ? 3 : 7, options.quick ? 0.05 : 1.0);
  const double ldlt_step = ldlt ? t[3] : 0.0;
  std::printf(
      "side %4d: %6ld coordinates, %6ld free nodes: step %.3e s, CHOLMOD solve3 %.3e s, "
      "step / solve %.3f, panel solve3 %.3e s, step / panel solve %.3f",
      side, static_cast<long>(automatic.velocity_count()), static_cast<long>(a.rows()), t[0], t[1],
      t[0] / t[1], t[2], t[0] / t[2]);
  if (ldlt) {
    std::printf(", SimplicialLDLT step %.3e s, LDLT step / step %.2f", ldlt_step, ldlt_step / t[0]);
  }
  std::printf("\n");
  csv << side << ',' << automatic.velocity_count() << ',' << a.rows() << ',' << t[0] << ',' << t[1]
      << ',' << t[0] / t[1] << ',' << t[2] << ',' << t[0] / t[2] << ',' << ldlt_step << ','
      << (ldlt ? ldlt_step / t[0] : 0.0) << '\n';
}

// The sheet scene through run_scene (the `dnurbs run` path), timed between its progress
// callbacks: each interval holds one step and everything the runner does around it (energy
// check, log row, probes). The first interval (the first factorization) is left out.
void run_path(const Options& options, std::ostream& csv) {
  const int side = options.run_side;
  const int steps = options.run_steps;
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / ("dnurbs_floor_bench_" + std::to_string(side));
  SceneSimulation simulation(parse_scene_json(sheet_scene_json(side, steps, true), "<floor>"));
  SceneRunOptions run;
  run.output_directory = directory;
  std::vector<double> times;
  const double start = cpu_seconds();
  const SceneRunResult result =
      run_scene(simulation, run,
                [&](const SceneRunProgress& /*progress*/) { times.push_back(cpu_seconds()); });
  const double total = cpu_seconds() - start;
  std::filesystem::remove_all(directory);
  if (result.diverged || result.steps_done != steps || times.size() < 3) {
    throw Error("floor bench: the sheet run stopped after " + std::to_string(result.steps_done) +
                " steps: " + result.message);
  }
  std::vector<double> intervals;
  for (size_t k = 2; k < times.size(); ++k) {
    intervals.push_back(times[k] - times[k - 1]);
  }
  double sum = 0.0;
  for (const double t : intervals) {
    sum += t;
  }
  const double per_step = median(intervals);
  const double mean = sum / static_cast<double>(intervals.size());
  std::printf(
      "run path: %d x %d sheet, %d steps in %.3f s (with setup and files): median step "
      "%.3e s, mean %.3e s: %.1f steps per second\n",
      side, side, steps, total, per_step, mean, 1.0 / per_step);
  csv << side << ',' << steps << ',' << total << ',' << per_step << ',' << mean << ','
      << 1.0 / per_step << '\n';
}

std::vector<int> parse_list(const std::string& text) {
  std::vector<int> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    values.push_back(std::stoi(item));
  }
  return values;
}

int run(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    const bool has_value = i + 1 < argc;
    if (argument == "--quick") {
      options.quick = true;
      options.sides = {12, 24};
      options.run_side = 20;
      options.run_steps = 6;
    } else if (argument == "--sides" && has_value) {
      options.sides = parse_list(argv[++i]);
    } else if (argument == "--run-side" && has_value) {
      options.run_side = std::stoi(argv[++i]);
    } else if (argument == "--out" && has_value) {
      options.out = argv[++i];
    } else if (argument == "--scene" && has_value) {
      options.scene = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: floor_bench [--quick] [--sides 12,58,100,183] [--run-side 100] "
                   "[--out DIR] [--scene FILE]\n");
      return 2;
    }
  }
  if (!options.scene.empty()) {
    std::ofstream(options.scene) << sheet_scene_json(options.run_side, 600, true) << '\n';
    std::printf("wrote %s\n", options.scene.c_str());
    return 0;
  }
  std::ostringstream steps_csv;
  steps_csv << "side,coordinates,free_nodes,step_seconds,cholmod_solve3_seconds,step_to_solve,"
               "panel_solve3_seconds,step_to_panel_solve,ldlt_step_seconds,ldlt_step_to_step\n";
  for (size_t k = 0; k < options.sides.size(); ++k) {
    step_against_solve(options.sides[k], k + 1 == options.sides.size(), options, steps_csv);
  }
  std::ostringstream run_csv;
  run_csv << "side,steps,run_seconds,median_step_seconds,mean_step_seconds,steps_per_second\n";
  run_path(options, run_csv);
  if (!options.out.empty()) {
    std::filesystem::create_directories(options.out);
    std::ofstream(std::filesystem::path(options.out) / "floor.csv") << steps_csv.str();
    std::ofstream(std::filesystem::path(options.out) / "floor_run.csv") << run_csv.str();
  }
  return 0;
}

}  // namespace
}  // namespace dnurbs::bench

int main(int argc, char** argv) {
  try {
    return dnurbs::bench::run(argc, argv);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "floor_bench: %s\n", error.what());
    return 1;
  }
}
