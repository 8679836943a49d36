// bench/free_weights: the cost of a free-weight D-NURBS step against the fixed-weight step of the
// same shape (issue 16, part 4): clamped curved bicubic sheets (10 x 10, 20 x 20 control points,
// border fixed, dt = 0.01) and a curved cubic rod of 50 control points (ends fixed, dt = 0.002),
// stepped by newmark from their initial shape (tension and bending pull them flat: everything
// moves). Setups, interleaved one step each in turn (medians of single steps, ratios from one run):
//   fixed      fixed weights (the constant, Kronecker-factored step);
//   reference  free weights, IntegratorSettings::lean_step = false: separate assembly of M, D,
//              K, f_int and g, sparse sums, reduction, SparseCholesky at every iterate (the path
//              before the lean step);
//   lean       free weights, the lean step (one pass per iterate, the factorization into a
//              pattern analyzed once);
//   reference_newton, lean_newton: the same with up to 4 Newton iterations (tolerance 1e-10);
//   default    free weights, IntegratorSettings{}: the lean step with the automatic Newton
//              iterations of free weights (up to 10, to 1e-8 of |a|).
// reference and lean (0 Newton iterations) switch automatic_newton off: linearly implicit.
// Heap allocations per step (malloc, calloc and realloc, counted by the interposed functions
// below over steady-state steps) for every setup. Times are means of the interleaved single
// steps: the default step keeps a factor across steps and replaces it now and then, a cost the
// median would hide (its median is printed beside, default_median_over_fixed).
//
// free_step_bench [--quick] [--out DIR] [--budget SECONDS] [--only SHAPE]

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bench/common/bench_arguments.h"
#include "bench/common/interleaved_medians.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/nurbs/knot_vector.h"
#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

// Allocation counting: this executable's malloc, calloc and realloc take precedence over the C
// library's for every library it loads (ELF symbol interposition) and forward to glibc's own.
namespace {
std::atomic<long> allocation_count{0};
}  // namespace

extern "C" {
// NOLINTBEGIN(bugprone-reserved-identifier,readability-identifier-naming,cert-dcl51-cpp)
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void* malloc(std::size_t size) noexcept {
  allocation_count.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) noexcept {
  allocation_count.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) noexcept {
  allocation_count.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(pointer, size);
}
// NOLINTEND(bugprone-reserved-identifier,readability-identifier-naming,cert-dcl51-cpp)
}

namespace dnurbs::bench {
namespace {

struct Options {
  double budget = 0.5;  // seconds per setup (at least kMinRepeats steps)
  std::string out;
  std::string only;  // one shape by name ("rod 50"), or all
  bool quick = false;
};

constexpr int kMinRepeats = 7;
constexpr int kMaxRepeats = 5000;
constexpr int kCountedSteps = 20;

Eigen::VectorXd greville(const KnotVector& knots) {
  Eigen::VectorXd result(knots.control_point_count());
  for (Eigen::Index i = 0; i < result.size(); ++i) {
    double sum = 0.0;
    for (int k = 1; k <= knots.degree(); ++k) {
      sum += knots[static_cast<int>(i) + k];
    }
    result[i] = sum / knots.degree();
  }
  return result;
}

DNurbsSettings weights(WeightMode mode) {
  DNurbsSettings settings;
  settings.weight_mode = mode;
  return settings;
}

// The bicubic sheet (u, v, 0.2 sin(pi u) sin(pi v)) at the Greville abscissae, border fixed.
System sheet(int side, WeightMode mode) {
  const KnotVector knots = KnotVector::clamped_uniform(3, side);
  const Eigen::VectorXd g = greville(knots);
  Eigen::MatrixX3d points(side * side, 3);
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      points.row(i * side + j) << g[i], g[j], 0.2 * std::sin(M_PI * g[i]) * std::sin(M_PI * g[j]);
    }
  }
  DNurbsSurfaceMaterial material;
  material.damping_density = 0.5;
  material.a10 = material.a01 = 1.0;
  material.b20 = material.b02 = 0.01;
  DNurbsSurface model(NurbsSurface(knots, knots, points), material, weights(mode));
  model.fix_border();
  return System(model);
}

// The cubic rod (u, 0, 0.3 sin(pi u)) at the Greville abscissae, ends fixed.
System rod(int count, WeightMode mode) {
  const KnotVector knots = KnotVector::clamped_uniform(3, count);
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(count, 3);
  points.col(0) = greville(knots);
  for (int i = 0; i < count; ++i) {
    points(i, 2) = 0.3 * std::sin(M_PI * points(i, 0));
  }
  DNurbsCurveMaterial material;
  material.damping_density = 0.5;
  material.tension = 1.0;
  material.rigidity = 0.01;
  DNurbsCurve model(NurbsCurve(knots, points), material, weights(mode));
  model.fix_control_point(0);
  model.fix_control_point(count - 1);
  return System(model);
}

struct Stepper {
  System system;
  Integrator integrator;
  double dt;
  double allocations_per_step = 0.0;
  Stepper(System s, IntegratorSettings settings, double step)
      : system(std::move(s)), integrator(settings), dt(step) {}
  // newton = 0: the linearly implicit step (automatic Newton off)
  static IntegratorSettings settings(bool lean, int newton) {
    IntegratorSettings s;
    s.lean_step = lean;
    s.newton_iterations = newton;
    s.newton_tolerance = 1e-10;
    s.automatic_newton = false;
    return s;
  }
  void step() { integrator.step(system, dt); }
};

// Warm-up, the allocation count over kCountedSteps steady-state steps, then interleaved timing.
StepTimes time_steps(std::vector<std::unique_ptr<Stepper>>& steppers, double budget) {
  for (auto& stepper : steppers) {
    stepper->step();
    stepper->step();
    const long before = allocation_count.load();
    for (int i = 0; i < kCountedSteps; ++i) {
      stepper->step();
    }
    stepper->allocations_per_step =
        static_cast<double>(allocation_count.load() - before) / kCountedSteps;
  }
  return interleaved_times(steppers, budget, kMinRepeats, kMaxRepeats);
}

struct Shape {
  std::string name;
  System (*make)(int, WeightMode);
  int size;
  double dt;
};

int run(const Options& options) {
  std::ostringstream csv;
  csv << "shape,free_coordinates,fixed_s,reference_s,lean_s,reference_newton_s,lean_newton_s,"
         "reference_over_fixed,lean_over_fixed,lean_newton_over_fixed,reference_over_lean,"
         "allocations_fixed,allocations_reference,allocations_lean,allocations_lean_newton,"
         "default_s,default_over_fixed,allocations_default,default_median_over_fixed\n";
  std::printf("%-12s %7s %10s %10s %10s %10s %10s %10s %9s %9s %9s %9s %9s %7s %7s %7s\n", "shape",
              "coords", "fixed ms", "ref ms", "lean ms", "ref+N ms", "lean+N ms", "default ms",
              "ref/fix", "lean/fix", "leanN/fix", "deflt/fix", "median d/f", "alloc_r", "alloc_l",
              "alloc_lN");
  // dt 0.01 for the sheets; the 50-point rod's free weights need dt 0.002 (at 0.01 its
  // linearly implicit newmark run leaves the positive definite states)
  std::vector<Shape> shapes{{"sheet 10x10", sheet, 10, 0.01},
                            {"sheet 20x20", sheet, 20, 0.01},
                            {"rod 50", rod, 50, 0.002}};
  if (options.quick) {
    shapes = {{"sheet 6x6", sheet, 6, 0.01}, {"rod 12", rod, 12, 0.002}};
  }
  if (!options.only.empty()) {
    std::erase_if(shapes, [&](const Shape& shape) { return shape.name != options.only; });
  }
  for (const Shape& shape : shapes) {
    std::vector<std::unique_ptr<Stepper>> steppers;
    steppers.push_back(std::make_unique<Stepper>(shape.make(shape.size, WeightMode::kFixed),
                                                 IntegratorSettings{}, shape.dt));
    for (const int newton : {0, 4}) {
      for (const bool lean : {false, true}) {
        steppers.push_back(std::make_unique<Stepper>(shape.make(shape.size, WeightMode::kFree),
                                                     Stepper::settings(lean, newton), shape.dt));
      }
    }
    steppers.push_back(std::make_unique<Stepper>(shape.make(shape.size, WeightMode::kFree),
                                                 IntegratorSettings{}, shape.dt));
    const StepTimes times = time_steps(steppers, options.budget);
    const std::vector<double>& t = times.mean;
    const double default_median_ratio = times.median[5] / times.median[0];
    const int coordinates = steppers[1]->system.velocity_count() -
                            static_cast<int>(steppers[1]->system.fixed_coordinates().size());
    // t: fixed, reference, lean, reference_newton, lean_newton, default
    std::printf(
        "%-12s %7d %10.4g %10.4g %10.4g %10.4g %10.4g %10.4g %9.3g %9.3g %9.3g %9.3g %9.3g %7.1f "
        "%7.1f %7.1f\n",
        shape.name.c_str(), coordinates, 1e3 * t[0], 1e3 * t[1], 1e3 * t[2], 1e3 * t[3], 1e3 * t[4],
        1e3 * t[5], t[1] / t[0], t[2] / t[0], t[4] / t[0], t[5] / t[0], default_median_ratio,
        steppers[1]->allocations_per_step, steppers[2]->allocations_per_step,
        steppers[4]->allocations_per_step);
    csv << shape.name << ',' << coordinates << ',' << t[0] << ',' << t[1] << ',' << t[2] << ','
        << t[3] << ',' << t[4] << ',' << t[1] / t[0] << ',' << t[2] / t[0] << ',' << t[4] / t[0]
        << ',' << t[1] / t[2] << ',' << steppers[0]->allocations_per_step << ','
        << steppers[1]->allocations_per_step << ',' << steppers[2]->allocations_per_step << ','
        << steppers[4]->allocations_per_step << ',' << t[5] << ',' << t[5] / t[0] << ','
        << steppers[5]->allocations_per_step << ',' << default_median_ratio << '\n';
    std::fflush(stdout);
  }
  if (!options.out.empty()) {
    std::ofstream(options.out + "/free_weights.csv") << csv.str();
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
        options.budget = 0.02;
      },
      {{"--out", [&](const char* value) { options.out = value; }},
       {"--only", [&](const char* value) { options.only = value; }},
       {"--budget", [&](const char* value) { options.budget = std::stod(value); }}});
  if (unknown) {
    std::fprintf(
        stderr, "usage: free_step_bench [--quick] [--out DIR] [--budget SECONDS] [--only SHAPE]\n");
    return 2;
  }
  return dnurbs::bench::run(options);
}
