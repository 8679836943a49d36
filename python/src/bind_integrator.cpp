// dnurbs.Integrator (dynamics/integrators/integrator.h), solve_static_equilibrium
// (dynamics/integrators/static_equilibrium.h) and dnurbs.TargetTrajectory
// (constraints/target_trajectory.h); bind_constraints.cpp binds the ConstraintSolver.

#include <pybind11/stl.h>

#include "dnurbs/constraints/target_trajectory.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/integrators/static_equilibrium.h"
#include "dnurbs/io/schedule.h"
#include "python/src/bindings.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

namespace {

Integrator make_integrator(const std::string& scheme, int newton_iterations,
                           double newton_tolerance, double newmark_beta, double newmark_gamma,
                           bool automatic_newton, bool keep_factor_across_steps) {
  IntegratorSettings settings;
  settings.automatic_newton = automatic_newton;
  settings.keep_factor_across_steps = keep_factor_across_steps;
  settings.scheme = parse_integrator_scheme(scheme);
  settings.newton_iterations = newton_iterations;
  settings.newton_tolerance = newton_tolerance;
  settings.newmark_beta = newmark_beta;
  settings.newmark_gamma = newmark_gamma;
  return Integrator(settings);
}

Interpolation interpolation_of(const std::string& name) {
  for (const Interpolation kind :
       {Interpolation::kCubic, Interpolation::kMonotone, Interpolation::kLinear}) {
    if (name == interpolation_name(kind)) {
      return kind;
    }
  }
  throw make_error("interpolation: expected \"cubic\", \"monotone\" or \"linear\", got \"", name,
                   "\"");
}

TargetTrajectory keyframes(const py::object& times, const py::object& points,
                           const std::string& interpolation) {
  const std::vector<double> keys = list_from_array(times, "times");
  const Eigen::MatrixXd values =
      matrix_from_array(points, "points", static_cast<long>(keys.size()), 3);
  std::vector<Eigen::Vector3d> positions;
  for (Eigen::Index i = 0; i < values.rows(); ++i) {
    positions.emplace_back(values.row(i).transpose());
  }
  return TargetTrajectory::keyframes(keys, positions, interpolation_of(interpolation));
}

}  // namespace

void bind_integrator(py::module_& module) {
  py::class_<Integrator>(
      module, "Integrator",
      "Time integration of M qdd + D qd + K q = f + g (central: Terzopoulos, Deformable Models, "
      "eq. 1.13; implicit-euler; newmark: average acceleration). Constant blocks are factored "
      "once; springs are implicit.")
      .def(py::init(&make_integrator), py::arg("scheme") = "newmark",
           py::arg("newton_iterations") = 0, py::arg("newton_tolerance") = 1e-12,
           py::arg("newmark_beta") = 0.25, py::arg("newmark_gamma") = 0.5,
           py::arg("automatic_newton") = true, py::arg("keep_factor_across_steps") = true,
           "scheme: 'central', 'implicit-euler' or 'newmark'. automatic_newton: with "
           "newton_iterations = 0, free-weight D-NURBS models still iterate Newton (up to 10 "
           "times, to 1e-8 of |a|); False makes the step linearly implicit for every model. "
           "keep_factor_across_steps: that Newton starts each step from the factor the last "
           "step ended with and refactors where a correction stalls; False factors at every "
           "step's predictor (the same steps within the tolerance, more factorizations).")
      .def(
          "step",
          [](Integrator& self, System& system, double dt, int count) {
            for (int i = 0; i < count; ++i) {
              self.step(system, dt);
            }
          },
          py::arg("system"), py::arg("dt"), py::arg("count") = 1,
          "Advances `system` `count` steps of dt (the loop runs in C++). Raises dnurbs.Error "
          "(state untouched) for dt <= 0 or a non-finite state.")
      .def_property_readonly(
          "scheme",
          [](const Integrator& self) { return std::string(to_string(self.settings().scheme)); },
          "The scheme: central, implicit-euler or newmark.")
      .def_property_readonly("last_newton_iterations", &Integrator::last_newton_iterations,
                             "Newton iterations of the last step (0: linearly implicit).")
      .def_property_readonly("factorization_count", &Integrator::factorization_count,
                             "Block factorizations of the step matrix so far.");
  module.def("solve_static_equilibrium", &solve_static_equilibrium, py::arg("system"),
             "Solves K q = f on the free coordinates (springs exact), sets q with zero "
             "velocity. Constant-matrix systems only; raises dnurbs.Error if K_ff is singular.");
  py::class_<TargetTrajectory>(module, "TargetTrajectory",
                               "A moving target point x(t) with velocity and acceleration.")
      .def_static(
          "fixed",
          [](const py::object& point) {
            return TargetTrajectory::fixed(matrix_from_array(point, "point", 1, 3, true).row(0));
          },
          py::arg("point"), "A target at rest at `point` (3,).")
      .def_static("keyframes", &keyframes, py::arg("times"), py::arg("points"),
                  py::arg("interpolation") = "monotone",
                  "Keyframes: times (k,) strictly increasing, points (k, 3), interpolated per "
                  "coordinate by \"monotone\" piecewise cubics (Fritsch & Carlson 1980: never "
                  "beyond the two keyframes around, C1), a \"cubic\" natural spline (C2, may "
                  "overshoot) or \"linear\" segments; before the first and after the last the "
                  "target rests.")
      .def(
          "__call__",
          [](const TargetTrajectory& self, double time) {
            return array_from_vector(self.position(time));
          },
          py::arg("t"), "x(t), (3,).")
      .def(
          "velocity",
          [](const TargetTrajectory& self, double time) {
            return array_from_vector(self.velocity(time));
          },
          py::arg("t"), "xdot(t), (3,).");
}

}  // namespace dnurbs::python
