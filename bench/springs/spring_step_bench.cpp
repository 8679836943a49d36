// bench/springs: the cost of implicit springs in the integrator's step (dynamics/integrators/
// implicit_springs.h). A clamped bicubic D-NURBS sheet with four springs, stepped by implicit
// Euler: a step with the springs held (parameters and targets fixed), a drag step (spring 0's
// parameter and target move every step: one Woodbury column recomputed), the same drag with the
// springs summed into the step matrix and refactored every step (SpringTreatment::kRefactor), and
// a step without springs. Medians of interleaved single steps; ratios are what matter (measured
// in one run on a shared machine).
//
// spring_step_bench [--quick] [--sides 10,32,100] [--out DIR] [--budget SECONDS]

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bench/common/bench_arguments.h"
#include "bench/common/interleaved_medians.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/nurbs/knot_vector.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs::bench {
namespace {

struct Options {
  std::vector<int> sides{10, 32, 100};
  double budget = 0.4;  // seconds per measured step kind (at least kMinRepeats steps)
  std::string out;
  bool quick = false;
};

constexpr int kMinRepeats = 7;
constexpr int kMaxRepeats = 2000;
constexpr double kDt = 1.0 / 60.0;
constexpr double kStiffness = 1e3;

// A flat clamped bicubic sheet on [0, 1]^2 with side x side control points at the Greville
// abscissae (x(u, v) = (u, v, 0)), mass 1, damping 1, tension 1, border fixed.
DNurbsSurface sheet(int side) {
  const KnotVector knots = KnotVector::clamped_uniform(3, side);
  Eigen::MatrixX3d points(side * side, 3);
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      double gu = 0.0;
      double gv = 0.0;
      for (int k = 1; k <= 3; ++k) {
        gu += knots[i + k] / 3.0;
        gv += knots[j + k] / 3.0;
      }
      points.row(i * side + j) << gu, gv, 0.0;
    }
  }
  DNurbsSurfaceMaterial material;
  material.damping_density = 1.0;
  material.a10 = material.a01 = 1.0;
  DNurbsSurface model(NurbsSurface(knots, knots, points), material);
  model.fix_border();
  return model;
}

enum class Kind { kNone, kHeld, kDrag, kRefactor };

// One stepping setup: its own System and Integrator, stepped forward one dt per call.
struct Stepper {
  System system;
  Integrator integrator;
  Stepper(const DNurbsSurface& model, Kind kind, CholeskyBackend backend)
      : system(model), integrator(settings(kind, backend)) {
    if (kind == Kind::kNone) {
      return;
    }
    const std::array<Eigen::Vector2d, 4> at{
        Eigen::Vector2d(0.31, 0.42), Eigen::Vector2d(0.63, 0.27), Eigen::Vector2d(0.55, 0.71),
        Eigen::Vector2d(0.22, 0.8)};
    for (int s = 0; s < 4; ++s) {
      const Eigen::Vector2d& u = at[static_cast<size_t>(s)];
      const Eigen::Vector3d target(u.x(), u.y(), 0.1 * (s + 1));
      if (s == 0 && kind != Kind::kHeld) {
        // The drag: parameter and target move every step
        system.add_spring(0, dragged_spring(
                                 [u](double t) {
                                   return Eigen::Vector2d(u.x() + 0.1 * std::sin(t),
                                                          u.y() + 0.1 * std::sin(0.7 * t));
                                 },
                                 [target](double t) {
                                   return Eigen::Vector3d(target.x(), target.y(),
                                                          target.z() * std::cos(t));
                                 },
                                 kStiffness));
      } else {
        system.add_spring(0,
                          mouse_spring(
                              u, [target](double) { return Eigen::Vector3d(target); }, kStiffness));
      }
    }
  }
  static IntegratorSettings settings(Kind kind, CholeskyBackend backend) {
    IntegratorSettings s;
    s.scheme = IntegratorScheme::kImplicitEuler;  // stable for sliding parameters
    s.springs = kind == Kind::kRefactor ? SpringTreatment::kRefactor : SpringTreatment::kLowRank;
    s.cholesky.backend = backend;
    return s;
  }
  void step() { integrator.step(system, kDt); }
};

// Median seconds of one step of each stepper, interleaved (one step of each in turn) so that a
// slow phase of the shared machine hits them alike; two untimed warm-up steps each.
std::vector<double> time_steps(std::vector<std::unique_ptr<Stepper>>& steppers, double budget) {
  for (auto& stepper : steppers) {
    stepper->step();
    stepper->step();
  }
  return interleaved_medians(steppers, budget, kMinRepeats, kMaxRepeats);
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

int run(const Options& options) {
  std::ostringstream csv;
  csv << "side,coordinates,free_nodes,backend,none_s,held_s,drag_s,refactor_s,held_over_none,"
         "drag_over_held,refactor_over_drag\n";
  std::printf("%5s %12s %10s %11s %11s %11s %11s %11s %11s %12s\n", "side", "coordinates",
              "backend", "none ms", "held ms", "drag ms", "refactor ms", "held/none", "drag/held",
              "refactor/drag");
  for (const int side : options.sides) {
    const DNurbsSurface model = sheet(side);
    for (const CholeskyBackend backend :
         {CholeskyBackend::kSimplicialLdlt, CholeskyBackend::kAutomatic}) {
      std::vector<std::unique_ptr<Stepper>> steppers;
      for (const Kind kind : {Kind::kNone, Kind::kHeld, Kind::kDrag, Kind::kRefactor}) {
        steppers.push_back(std::make_unique<Stepper>(model, kind, backend));
      }
      const std::vector<double> t = time_steps(steppers, options.budget);
      const char* name = backend == CholeskyBackend::kSimplicialLdlt ? "simplicial" : "automatic";
      std::printf("%5d %12d %10s %11.4g %11.4g %11.4g %11.4g %11.3g %11.3g %12.3g\n", side,
                  3 * side * side, name, 1e3 * t[0], 1e3 * t[1], 1e3 * t[2], 1e3 * t[3],
                  t[1] / t[0], t[2] / t[1], t[3] / t[2]);
      csv << side << ',' << 3 * side * side << ',' << (side - 2) * (side - 2) << ',' << name << ','
          << t[0] << ',' << t[1] << ',' << t[2] << ',' << t[3] << ',' << t[1] / t[0] << ','
          << t[2] / t[1] << ',' << t[3] / t[2] << '\n';
      std::fflush(stdout);
    }
  }
  if (!options.out.empty()) {
    std::ofstream(options.out + "/springs.csv") << csv.str();
  }
  return 0;
}

}  // namespace
}  // namespace dnurbs::bench

int main(int argc, char** argv) {
  dnurbs::bench::Options options;
  const auto unknown = dnurbs::bench::read_bench_arguments(
      argc, argv,
      [&] {
        options.quick = true;
        options.sides = {8, 16};
        options.budget = 0.02;
      },
      {{"--sides", [&](const char* value) { options.sides = dnurbs::bench::parse_list(value); }},
       {"--out", [&](const char* value) { options.out = value; }},
       {"--budget", [&](const char* value) { options.budget = std::stod(value); }}});
  if (unknown) {
    std::fprintf(stderr,
                 "usage: spring_step_bench [--quick] [--sides 10,32,100] [--out DIR] "
                 "[--budget SECONDS]\n");
    return 2;
  }
  return dnurbs::bench::run(options);
}
