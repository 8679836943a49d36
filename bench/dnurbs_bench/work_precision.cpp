#include "work_precision.h"

#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "bench_scenes.h"
#include "dnurbs/constraints/constraint_solver.h"
#include "dnurbs/constraints/point_constraints.h"
#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/integrators/rigid_body_integrator.h"

namespace dnurbs::bench {

namespace {

struct Row {
  std::string family;
  std::string case_name;
  std::string integrator;
  double dt = 0.0;
  int quadrature = 0;
  int resolution = 0;
  double error = 0.0;
  std::string error_kind;
  double seconds_per_simulated_second = 0.0;
};

class WorkPrecisionCsv {
 public:
  explicit WorkPrecisionCsv(const BenchOptions& options)
      : csv_(options.out_dir / "work_precision.csv",
             {"family", "case", "integrator", "dt", "quadrature", "resolution", "error",
              "error_kind", "seconds_per_simulated_second"}) {}
  void add(const Row& r) {
    csv_.row({r.family, r.case_name, r.integrator, number(r.dt), std::to_string(r.quadrature),
              std::to_string(r.resolution), number(r.error), r.error_kind,
              number(r.seconds_per_simulated_second)});
    std::cerr << r.family << ' ' << r.case_name << ' ' << r.integrator << " dt " << r.dt << " q "
              << r.quadrature << " n " << r.resolution << ": " << r.error_kind << ' ' << r.error
              << ", " << r.seconds_per_simulated_second << " s/s\n";
  }

 private:
  CsvFile csv_;
};

// Observed order log2(e_coarse / e_fine) of consecutive halvings of dt.
double observed_order(double coarse, double fine) {
  return std::log2(coarse / fine);
}

// Checks the order of every consecutive dt pair whose finer error is above `floor` (round-off
// and Newton tolerances below it) against `minimum_order`.
void check_orders(const std::vector<double>& errors, double minimum_order, double floor,
                  const std::string& what, BoundChecks& checks) {
  for (std::size_t i = 1; i < errors.size(); ++i) {
    if (errors[i] > floor) {
      const double order = observed_order(errors[i - 1], errors[i]);
      checks.expect(order >= minimum_order, what + ": observed order " + number(order) +
                                                " between dt pair " + std::to_string(i) +
                                                " below " + number(minimum_order));
    }
  }
}

// --- Modal solutions of linear D-NURBS models ------------------------------------------------
//
// A fixed-weight D-NURBS model is linear with constant M = S_M (x) I_3 and K = S_K (x) I_3.
// Released from rest at q0 + A phi (z components of the free nodes), phi the lowest generalized
// eigenvector of (S_K, S_M) on the free nodes (S_K phi = omega^2 S_M phi), the discrete system
// moves exactly as q0 + A phi cos(omega t): any deviation is the integrator's error.
struct Mode {
  std::vector<int> free_nodes;
  Eigen::VectorXd shape;  // phi, max |phi| = 1
  double omega = 0.0;
};

Mode lowest_mode(const System& system) {
  const ModelMatrices& scalar = *system.scalar_matrices();
  std::vector<bool> fixed(static_cast<std::size_t>(scalar.mass.rows()), false);
  for (const int c : system.fixed_coordinates()) {
    fixed[static_cast<std::size_t>(c / 3)] = true;
  }
  Mode mode;
  for (int i = 0; i < scalar.mass.rows(); ++i) {
    if (!fixed[static_cast<std::size_t>(i)]) {
      mode.free_nodes.push_back(i);
    }
  }
  const Eigen::MatrixXd mass_full(scalar.mass);
  const Eigen::MatrixXd stiffness_full(scalar.stiffness);
  const auto n = static_cast<Eigen::Index>(mode.free_nodes.size());
  Eigen::MatrixXd mass(n, n);
  Eigen::MatrixXd stiffness(n, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    for (Eigen::Index b = 0; b < n; ++b) {
      mass(a, b) = mass_full(mode.free_nodes[static_cast<std::size_t>(a)],
                             mode.free_nodes[static_cast<std::size_t>(b)]);
      stiffness(a, b) = stiffness_full(mode.free_nodes[static_cast<std::size_t>(a)],
                                       mode.free_nodes[static_cast<std::size_t>(b)]);
    }
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(stiffness, mass);
  if (solver.info() != Eigen::Success) {
    throw Error("lowest_mode: the generalized eigenproblem (K, M) did not converge");
  }
  mode.omega = std::sqrt(solver.eigenvalues()[0]);
  mode.shape = solver.eigenvectors().col(0);
  mode.shape /= mode.shape.cwiseAbs().maxCoeff();
  return mode;
}

struct RunResult {
  double error = 0.0;
  double seconds_per_simulated_second = 0.0;
};

// Largest |q_z - exact| / A over every step of [0, duration].
RunResult modal_run(System system, const Mode& mode, IntegratorScheme scheme, double dt,
                    double duration) {
  const double amplitude = 1e-2;
  const Eigen::VectorXd q0 = system.coordinates();
  Eigen::VectorXd q = q0;
  for (std::size_t a = 0; a < mode.free_nodes.size(); ++a) {
    q[3 * mode.free_nodes[a] + 2] += amplitude * mode.shape[static_cast<Eigen::Index>(a)];
  }
  system.set_coordinates(0, q);
  Integrator integrator(IntegratorSettings{scheme});
  const int steps = static_cast<int>(std::lround(duration / dt));
  RunResult result;
  double stepping = 0.0;
  for (int k = 0; k < steps; ++k) {
    const Stopwatch watch;
    integrator.step(system, dt);
    stepping += watch.seconds();
    const double c = std::cos(mode.omega * system.time());
    const Eigen::VectorXd& now = system.coordinates();
    for (std::size_t a = 0; a < mode.free_nodes.size(); ++a) {
      const int z = 3 * mode.free_nodes[a] + 2;
      const double exact = q0[z] + amplitude * mode.shape[static_cast<Eigen::Index>(a)] * c;
      result.error = std::max(result.error, std::abs(now[z] - exact) / amplitude);
    }
  }
  result.seconds_per_simulated_second = stepping / duration;
  return result;
}

constexpr IntegratorScheme kSchemes[] = {
    IntegratorScheme::kNewmark, IntegratorScheme::kImplicitEuler, IntegratorScheme::kCentral};

template <typename MakeModel>
void modal_family(const std::string& family, const std::string& case_name,
                  const std::vector<int>& resolutions, const std::vector<double>& steps,
                  MakeModel&& make_model, WorkPrecisionCsv& csv, BoundChecks& checks) {
  const double duration = 2.0;
  for (const int resolution : resolutions) {
    for (const int quadrature : {2, 4}) {
      const System system(make_model(resolution, quadrature));
      const Mode mode = lowest_mode(system);
      for (const IntegratorScheme scheme : kSchemes) {
        std::vector<double> errors;
        for (const double dt : steps) {
          const RunResult run = modal_run(system, mode, scheme, dt, duration);
          csv.add({family, case_name, std::string(to_string(scheme)), dt, quadrature, resolution,
                   run.error, "modal_exact", run.seconds_per_simulated_second});
          errors.push_back(run.error);
        }
        const std::string what = family + " " + std::string(to_string(scheme)) + " n " +
                                 std::to_string(resolution) + " quadrature " +
                                 std::to_string(quadrature);
        // Newmark (average acceleration) is second order: phase error omega^3 dt^2 t / 12.
        // Implicit Euler is first order (amplitude decay ~ omega^2 dt t / 2); its coarse steps
        // are outside the asymptotic range, so only the finest pair is checked.
        if (scheme == IntegratorScheme::kNewmark) {
          check_orders(errors, 1.8, 1e-9, what, checks);
        } else if (scheme == IntegratorScheme::kImplicitEuler && errors.size() >= 2) {
          check_orders({errors[errors.size() - 2], errors.back()}, 0.8, 1e-9, what, checks);
        }
      }
    }
  }
}

// --- Rigid superquadric free spin --------------------------------------------------------------

Eigen::Vector3d rigid_angular_momentum(const System& system) {
  const auto& model = dynamic_cast<const DeformableSuperquadricModel&>(system.model(0));
  const Eigen::VectorXd& q = system.coordinates();
  const Eigen::VectorXd& qd = system.velocities();
  const RigidMassProperties& props = model.reference_mass_properties();
  const Eigen::Matrix3d rotation = model.orientation(q).toRotationMatrix();
  const Eigen::Vector3d omega = qd.segment<3>(3);
  const Eigen::Vector3d x = q.head<3>() + rotation * props.centre_of_mass;
  const Eigen::Vector3d v = qd.head<3>() + rotation * omega.cross(props.centre_of_mass);
  return props.mass * x.cross(v) + rotation * (props.inertia_about_centre * omega);
}

void spin_family(const BenchOptions& options, WorkPrecisionCsv& csv, BoundChecks& checks) {
  const double duration = options.quick ? 2.0 : 10.0;
  const std::vector<double> steps = options.quick ? std::vector<double>{0.02, 0.01}
                                                  : std::vector<double>{0.04, 0.02, 0.01, 0.005};
  for (const std::string integrator_name : {"lie-midpoint", "newmark"}) {
    std::vector<double> energy_errors;
    for (const double dt : steps) {
      System system = spinning_superquadric(DeformableSuperquadricParts::rigid());
      const double energy0 = system.kinetic_energy();
      const Eigen::Vector3d momentum0 = rigid_angular_momentum(system);
      RigidBodyIntegrator lie;
      IntegratorSettings settings;
      settings.newton_iterations = 20;
      settings.newton_tolerance = 1e-13;
      Integrator newmark(settings);
      double energy_drift = 0.0;
      double momentum_drift = 0.0;
      double stepping = 0.0;
      const int count = static_cast<int>(std::lround(duration / dt));
      for (int k = 0; k < count; ++k) {
        const Stopwatch watch;
        if (integrator_name == "lie-midpoint") {
          lie.step(system, dt);
        } else {
          newmark.step(system, dt);
        }
        stepping += watch.seconds();
        energy_drift =
            std::max(energy_drift, std::abs(system.kinetic_energy() - energy0) / energy0);
        momentum_drift = std::max(
            momentum_drift, (rigid_angular_momentum(system) - momentum0).norm() / momentum0.norm());
      }
      const auto& model = dynamic_cast<const DeformableSuperquadricModel&>(system.model(0));
      const int quadrature = model.settings().quadrature_points;
      csv.add({"superquadric", "rigid_free_spin", integrator_name, dt, quadrature,
               system.velocity_count(), energy_drift, "energy_drift", stepping / duration});
      csv.add({"superquadric", "rigid_free_spin", integrator_name, dt, quadrature,
               system.velocity_count(), momentum_drift, "angular_momentum_drift",
               stepping / duration});
      energy_errors.push_back(energy_drift);
      if (integrator_name == "lie-midpoint") {
        // Exact invariants of the Lie midpoint rule: only the Newton tolerance (1e-15) and
        // round-off accumulated over at most 2000 steps remain.
        checks.expect(energy_drift < 1e-8 && momentum_drift < 1e-8,
                      "lie-midpoint free spin drift " + number(energy_drift) + " / " +
                          number(momentum_drift) + " above 1e-8 at dt " + number(dt));
      }
    }
    if (integrator_name == "newmark") {
      // The trapezoidal rule's energy drift is O((|w| dt)^2): second order (1.5 allows the
      // coarsest pair to sit slightly outside the asymptotic range).
      check_orders(energy_errors, 1.5, 1e-12, "newmark free-spin energy drift", checks);
    }
  }
}

// --- Baumgarte violation against its closed form ------------------------------------------------
//
// A free D-NURBS curve whose point at u = 0.5 is held at a target `offset` away: the violation
// obeys Cddot + 2 alpha Cdot + alpha^2 C = 0 (Terzopoulos 2003, eq. 1.40 with beta = alpha), so
// C(t) = C0 (1 + alpha t) exp(-alpha t); the error is the largest |C - closed form| / C0 over
// every step of [0, 0.4].
void baumgarte_family(const BenchOptions& options, WorkPrecisionCsv& csv, BoundChecks& checks) {
  const double alpha = 20.0;
  const double duration = 0.4;
  const std::vector<double> steps =
      options.quick ? std::vector<double>{2e-3, 1e-3} : std::vector<double>{4e-3, 2e-3, 1e-3, 5e-4};
  for (const IntegratorScheme scheme :
       {IntegratorScheme::kNewmark, IntegratorScheme::kImplicitEuler}) {
    std::vector<double> errors;
    for (const double dt : steps) {
      const int control_points = 7;
      DNurbsCurveMaterial material;
      material.tension = 1.0;
      const KnotVector knots = KnotVector::clamped_uniform(3, control_points);
      Eigen::MatrixX3d points(control_points, 3);
      for (int i = 0; i < control_points; ++i) {
        const double t = i / 6.0;
        points.row(i) << 0.1 + 0.8 * t, 0.2 + 0.5 * t * t, 0.05 + 0.02 * std::sin(5.0 * t);
      }
      System system(DNurbsCurve(NurbsCurve(knots, points), material));
      const Eigen::Vector2d u(0.5, 0.0);
      const Eigen::Vector3d offset(0.03, -0.02, 0.04);
      ConstraintSolver solver;
      BaumgarteParameters parameters;
      parameters.alpha = alpha;
      solver.add(
          system,
          PointTargetConstraint(0, u, TargetTrajectory::fixed(system.position(0, u) + offset)),
          parameters);
      Integrator integrator(IntegratorSettings{scheme});
      const double initial = offset.norm();
      double error = 0.0;
      double stepping = 0.0;
      const int count = static_cast<int>(std::lround(duration / dt));
      for (int k = 0; k < count; ++k) {
        const Stopwatch watch;
        solver.step(integrator, system, dt);
        stepping += watch.seconds();
        const double t = system.time();
        const double expected = initial * (1.0 + alpha * t) * std::exp(-alpha * t);
        error = std::max(error, std::abs(solver.max_violation(system) - expected) / initial);
      }
      csv.add({"constraints", "baumgarte_point_target", std::string(to_string(scheme)), dt, 4,
               system.velocity_count(), error, "baumgarte_closed_form", stepping / duration});
      errors.push_back(error);
    }
    // The discrete violation follows the closed form up to O(alpha dt) (both schemes are
    // consistent); the test suite's bound: halving dt at least divides the error by 1/0.6.
    check_orders(errors, std::log2(1.0 / 0.6), 0.0, "baumgarte " + std::string(to_string(scheme)),
                 checks);
  }
}

// --- Converged references (Richardson) for non-linear and region models -------------------------
//
// Runs at dt, dt/2, dt/4, ... to the same end time. From the three finest, the observed order
// p = log2(|q_4 - q_2| / |q_2 - q_1|) (q_k at dt_finest * k) and the Richardson reference
// q_ref = q_1 + (q_1 - q_2) / (2^p - 1); every run's error is |q - q_ref|_inf / |q_ref - q0|_inf.
struct ReferenceFamily {
  std::string family;
  std::string case_name;
  std::function<System()> make;
  int quadrature = 0;
  double duration = 1.0;
  int newton_iterations = 0;
  /// Check implicit Euler's order too. Off for stiff grids, where implicit Euler's error in the
  /// stiff modes (damped by 1 / (1 + (omega dt)^2) per step) is pre-asymptotic at every
  /// affordable dt: its observed order is reported, not checked.
  bool check_implicit_euler = true;
};

void richardson_family(const ReferenceFamily& setup, const std::vector<double>& steps,
                       WorkPrecisionCsv& csv, CsvFile& orders, BoundChecks& checks) {
  for (const IntegratorScheme scheme :
       {IntegratorScheme::kNewmark, IntegratorScheme::kImplicitEuler}) {
    std::vector<Eigen::VectorXd> finals;
    std::vector<double> costs;
    Eigen::VectorXd q0;
    int resolution = 0;
    for (const double dt : steps) {
      System system = setup.make();
      q0 = system.coordinates();
      resolution = system.velocity_count();
      IntegratorSettings settings{scheme};
      settings.newton_iterations = setup.newton_iterations;
      Integrator integrator(settings);
      const int count = static_cast<int>(std::lround(setup.duration / dt));
      const Stopwatch watch;
      for (int k = 0; k < count; ++k) {
        integrator.step(system, dt);
      }
      costs.push_back(watch.seconds() / setup.duration);
      finals.push_back(system.coordinates());
    }
    const std::size_t n = finals.size();
    const double coarse_difference = (finals[n - 3] - finals[n - 2]).cwiseAbs().maxCoeff();
    const double fine_difference = (finals[n - 2] - finals[n - 1]).cwiseAbs().maxCoeff();
    const double order = observed_order(coarse_difference, fine_difference);
    const Eigen::VectorXd reference =
        finals[n - 1] + (finals[n - 1] - finals[n - 2]) / (std::pow(2.0, order) - 1.0);
    const double scale = (reference - q0).cwiseAbs().maxCoeff();
    for (std::size_t i = 0; i < n; ++i) {
      csv.add({setup.family, setup.case_name, std::string(to_string(scheme)), steps[i],
               setup.quadrature, resolution, (finals[i] - reference).cwiseAbs().maxCoeff() / scale,
               "richardson_reference", costs[i]});
    }
    orders.row({setup.family, setup.case_name, std::string(to_string(scheme)), number(steps[n - 3]),
                number(steps[n - 2]), number(steps[n - 1]), number(order)});
    std::cerr << setup.family << ' ' << to_string(scheme) << ": observed order " << order << '\n';
    const double expected = scheme == IntegratorScheme::kNewmark ? 2.0 : 1.0;
    if (scheme == IntegratorScheme::kImplicitEuler && !setup.check_implicit_euler) {
      continue;
    }
    checks.expect(std::abs(order - expected) < 0.5,
                  setup.family + " " + std::string(to_string(scheme)) + ": observed order " +
                      number(order) + " not within 0.5 of " + number(expected));
  }
}

}  // namespace

void run_work_precision(const BenchOptions& options, BoundChecks& checks) {
  WorkPrecisionCsv csv(options);
  const std::vector<double> modal_steps =
      options.quick ? std::vector<double>{0.05, 0.025, 0.0125}
                    : std::vector<double>{0.1, 0.05, 0.025, 0.0125, 0.00625};
  modal_family(
      "dnurbs_curve", "clamped_string_mode",
      options.quick ? std::vector<int>{8} : std::vector<int>{8, 16, 32}, modal_steps,
      [](int n, int quadrature) { return clamped_string(n, WeightMode::kFixed, 1e-3, quadrature); },
      csv, checks);
  modal_family(
      "dnurbs_surface", "clamped_membrane_mode",
      options.quick ? std::vector<int>{6} : std::vector<int>{6, 9, 12}, modal_steps,
      [](int n, int quadrature) {
        return clamped_membrane(n, WeightMode::kFixed, 0.0, quadrature);
      },
      csv, checks);
  spin_family(options, csv, checks);
  baumgarte_family(options, csv, checks);

  CsvFile orders(options.out_dir / "richardson.csv", {"family", "case", "integrator", "dt_coarse",
                                                      "dt_medium", "dt_fine", "observed_order"});
  // Loads ramped smoothly (smooth_ramp) so that the runs are in the asymptotic range; the
  // coarsest steps of the full run show where it starts.
  const std::vector<double> sheet_steps =
      options.quick ? std::vector<double>{0.005, 0.0025, 0.00125}
                    : std::vector<double>{0.02, 0.01, 0.005, 0.0025, 0.00125, 0.000625};
  richardson_family(
      {"terzopoulos", "pushed_sheet_9x9", [] { return pushed_terzopoulos_sheet(0.2); }, 0, 0.25, 5},
      sheet_steps, csv, orders, checks);
  // The biharmonic grid's stiffest mode has omega_max ~ 8 / h^2 ~ 2e3 (h = 1/16), which the
  // steps must resolve (omega_max dt <= 0.4) for Newmark's error to fall at its order.
  const std::vector<double> pde_steps =
      options.quick ? std::vector<double>{4e-4, 2e-4, 1e-4}
                    : std::vector<double>{3.2e-3, 1.6e-3, 8e-4, 4e-4, 2e-4, 1e-4};
  richardson_family({"pde_surface", "pushed_region_17x17",
                     [] { return pushed_pde_surface(17, true, 0.1); }, 0, 0.1, 0, false},
                    pde_steps, csv, orders, checks);
}

}  // namespace dnurbs::bench
