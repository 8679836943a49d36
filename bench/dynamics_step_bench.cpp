// Step time of the dynamics layer: fixed-weight D-NURBS curves and surfaces from 1e2 to 1e5
// coordinates (Newmark, factor once), the ratio of a step to one back-substitution with the
// same factor, and free-weight against fixed-weight step time.
//
// Usage: dynamics_step_bench [output.csv]   (CSV also goes to stdout)

#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>

#include <Eigen/SparseCholesky>

#include "dynamics/dnurbs_curve.h"
#include "dynamics/dnurbs_surface.h"
#include "dynamics/forces.h"
#include "dynamics/integrator.h"
#include "nurbs/error.h"

namespace {

using namespace dnurbs;
using Clock = std::chrono::steady_clock;

// Seconds per call of `work`, repeated until 0.3 s have passed (at least 3 calls).
double time_per_call(const std::function<void()>& work) {
  work();  // warm up (first step factors)
  int calls = 0;
  const auto start = Clock::now();
  double elapsed = 0.0;
  while (calls < 3 || elapsed < 0.3) {
    work();
    ++calls;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  }
  return elapsed / calls;
}

Eigen::VectorXd greville(const KnotVector& knots) {
  const int p = knots.degree();
  Eigen::VectorXd result(knots.control_point_count());
  for (int i = 0; i < result.size(); ++i) {
    double sum = 0.0;
    for (int k = 1; k <= p; ++k) {
      sum += knots[i + k];
    }
    result[i] = sum / p;
  }
  return result;
}

DNurbsCurve make_curve(int control_points, WeightMode mode) {
  KnotVector knots = KnotVector::clamped_uniform(3, control_points);
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(control_points, 3);
  points.col(0) = greville(knots);
  DNurbsCurveMaterial material;
  material.tension = 1.0;
  material.rigidity = 1e-3;
  material.damping_density = 0.1;
  DNurbsSettings settings;
  settings.weight_mode = mode;
  DNurbsCurve model(NurbsCurve(knots, points), material, settings);
  model.fix_control_point(0);
  model.fix_control_point(control_points - 1);
  return model;
}

DNurbsSurface make_surface(int per_side, WeightMode mode) {
  KnotVector knots = KnotVector::clamped_uniform(3, per_side);
  const Eigen::VectorXd g = greville(knots);
  Eigen::MatrixX3d points(per_side * per_side, 3);
  for (int i = 0; i < per_side; ++i) {
    for (int j = 0; j < per_side; ++j) {
      points.row(i * per_side + j) << g[i], g[j], 0.0;
    }
  }
  DNurbsSurfaceMaterial material;
  material.a10 = 1.0;
  material.a01 = 1.0;
  material.b20 = 1e-3;
  material.b02 = 1e-3;
  material.damping_density = 0.1;
  DNurbsSettings settings;
  settings.weight_mode = mode;
  DNurbsSurface model(NurbsSurface(knots, knots, points), material, settings);
  model.fix_border();
  return model;
}

// One back-substitution with the factor of the fixed-weight Newmark matrix (scalar, free nodes,
// 3 right-hand sides), the operation a fixed-weight step cannot avoid.
double back_substitution_time(const System& system, double dt) {
  const ModelMatrices& scalar = *system.scalar_matrices();
  const SparseMatrix A =
      scalar.mass + 0.5 * dt * scalar.damping + 0.25 * dt * dt * scalar.stiffness;
  std::vector<int> free_nodes;
  std::vector<int> index(static_cast<size_t>(A.rows()), 0);
  for (const int fixed : system.fixed_coordinates()) {
    index[static_cast<size_t>(fixed / 3)] = -1;
  }
  for (int i = 0; i < A.rows(); ++i) {
    if (index[static_cast<size_t>(i)] == 0) {
      index[static_cast<size_t>(i)] = static_cast<int>(free_nodes.size());
      free_nodes.push_back(i);
    }
  }
  std::vector<Eigen::Triplet<double>> triplets;
  for (int j = 0; j < A.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      if (index[static_cast<size_t>(it.row())] >= 0 && index[static_cast<size_t>(j)] >= 0) {
        triplets.emplace_back(index[static_cast<size_t>(it.row())], index[static_cast<size_t>(j)],
                              it.value());
      }
    }
  }
  const auto n = static_cast<Eigen::Index>(free_nodes.size());
  SparseMatrix reduced(n, n);
  reduced.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<SparseMatrix> solver(reduced);
  const Eigen::MatrixXd rhs = Eigen::MatrixXd::Random(n, 3);
  Eigen::MatrixXd x(n, 3);
  return time_per_call([&] { x = solver.solve(rhs); });
}

// Seconds per step. A free-weight run whose light weight modes blow up (dnurbs::Error) restarts
// from the initial state; the restarts are counted and reported.
double step_time(const System& initial, double dt, int& restarts) {
  System system = initial;
  system.add_force(0, point_force(Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d(0.0, 0.0, 1e-3)));
  const System start = system;
  Integrator integrator;
  restarts = 0;
  return time_per_call([&] {
    try {
      integrator.step(system, dt);
    } catch (const Error&) {
      system = start;
      ++restarts;
    }
  });
}

double step_time(const System& initial, double dt) {
  int restarts = 0;
  return step_time(initial, dt, restarts);
}

}  // namespace

int main(int argc, char** argv) {
  std::ostringstream csv;
  // reference_seconds: one back-substitution (fixed weights) or the fixed-weight step of the
  // same shape (free weights); ratio = step_seconds / reference_seconds.
  csv << "shape,weights,coordinates,step_seconds,step_seconds_per_coordinate,"
         "reference_seconds,ratio\n";
  const double dt = 1e-3;
  auto report = [&](const std::string& shape, const std::string& weights, const System& system,
                    double step, double back) {
    csv << shape << ',' << weights << ',' << system.velocity_count() << ',' << step << ','
        << step / system.velocity_count() << ',';
    csv << back << ',' << step / back << '\n';
    std::cerr << shape << ' ' << weights << ' ' << system.velocity_count()
              << " coordinates: " << step * 1e6 << " us/step, ratio " << step / back << '\n';
  };

  // Fixed weights, 1e2 .. 1e5 coordinates.
  for (const int n : {34, 334, 3334, 33334}) {
    const System system(make_curve(n, WeightMode::kFixed));
    report("curve", "fixed", system, step_time(system, dt), back_substitution_time(system, dt));
  }
  for (const int m : {6, 18, 58, 183}) {
    const System system(make_surface(m, WeightMode::kFixed));
    report("surface", "fixed", system, step_time(system, dt), back_substitution_time(system, dt));
  }
  // Free weights (re-assembly and refactorization every step), 1e2 .. 1e4 coordinates, with
  // the same-size fixed-weight step for the ratio. The light weight modes need a small dt.
  const double dt_free = 1e-5;
  int restarts = 0;
  for (const int n : {25, 250, 2500}) {
    const System system(make_curve(n, WeightMode::kFree));
    const System fixed(make_curve(n, WeightMode::kFixed));
    const double step = step_time(system, dt_free, restarts);
    report("curve", "free", system, step, step_time(fixed, dt_free));
    std::cerr << "  (" << restarts << " restarts after a blown-up free-weight step)\n";
  }
  for (const int m : {5, 16, 50}) {
    const System system(make_surface(m, WeightMode::kFree));
    const System fixed(make_surface(m, WeightMode::kFixed));
    const double step = step_time(system, dt_free, restarts);
    report("surface", "free", system, step, step_time(fixed, dt_free));
    std::cerr << "  (" << restarts << " restarts after a blown-up free-weight step)\n";
  }

  std::cout << csv.str();
  if (argc > 1) {
    std::ofstream(argv[1]) << csv.str();
  }
  return 0;
}
