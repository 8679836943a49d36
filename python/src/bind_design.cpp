// Design and fitting from Python: D-NURBS fits to point clouds (design/dnurbs_fitting.h) from a
// principal-plane or principal-axis start (io/scene_fit.h), and energy-minimizing design of a
// System under constraints (design/energy_minimization.h).

#include <pybind11/stl.h>

#include "dnurbs/design/dnurbs_fitting.h"
#include "dnurbs/design/energy_minimization.h"
#include "dnurbs/io/scene_fit.h"
#include "python/src/bindings.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

namespace {

py::dict fit_result_dict(const DNurbsFitResult& fit) {
  py::dict result;
  result["coordinates"] = array_from_vector(fit.coordinates);
  result["parameters"] = array_from_matrix(fit.parameters);
  result["iterations"] = fit.iterations;
  result["rms_error"] = fit.rms_error;
  result["max_error"] = fit.max_error;
  return result;
}

DNurbsFitSettings fit_settings(double smoothness, int max_iterations, double parameter_tolerance) {
  DNurbsFitSettings settings;
  settings.smoothness = smoothness;
  settings.max_iterations = max_iterations;
  settings.parameter_tolerance = parameter_tolerance;
  return settings;
}

py::dict design(const System& system, const ConstraintSolver* constraints,
                const std::string& algorithm, double variable_tolerance,
                double constraint_tolerance, int max_evaluations) {
  DesignSettings settings;
  if (algorithm == "slsqp") {
    settings.algorithm = DesignAlgorithm::kSlsqp;
  } else if (algorithm == "auglag_lbfgs") {
    settings.algorithm = DesignAlgorithm::kAugmentedLagrangianLbfgs;
  } else {
    throw make_error("design algorithm \"", algorithm, "\" is not slsqp or auglag_lbfgs");
  }
  settings.variable_tolerance = variable_tolerance;
  settings.constraint_tolerance = constraint_tolerance;
  settings.max_evaluations = max_evaluations;
  const DesignResult optimum = minimize_energy(system, constraints, settings);
  py::dict result;
  result["coordinates"] = array_from_vector(optimum.coordinates);
  result["iterations"] = optimum.iterations;
  result["energy"] = optimum.energy;
  result["constraint_violation"] = optimum.constraint_violation;
  result["status"] = optimum.status;
  result["status_name"] = optimum.status_name;
  result["converged"] = optimum.converged();
  return result;
}

}  // namespace

void bind_design(py::module_& module) {
  const char* fit_doc =
      "Fits the model to `points` (k, 3) from its initial shape: least squares plus "
      "smoothness / 2 q^T K q (K the model's stiffness), parameters re-projected between "
      "iterations. Returns a dict coordinates (n,), parameters (k, 2), iterations, rms_error, "
      "max_error.";
  module.def(
      "fit_dnurbs_surface",
      [](const DNurbsSurface& model, const py::object& points, double smoothness,
         int max_iterations, double parameter_tolerance) {
        return fit_result_dict(
            fit_dnurbs_surface(model, matrix_from_array(points, "points", -1, 3),
                               fit_settings(smoothness, max_iterations, parameter_tolerance)));
      },
      py::arg("model"), py::arg("points"), py::arg("smoothness") = 0.0,
      py::arg("max_iterations") = 30, py::arg("parameter_tolerance") = 1e-12, fit_doc);
  module.def(
      "fit_dnurbs_curve",
      [](const DNurbsCurve& model, const py::object& points, double smoothness, int max_iterations,
         double parameter_tolerance) {
        return fit_result_dict(
            fit_dnurbs_curve(model, matrix_from_array(points, "points", -1, 3),
                             fit_settings(smoothness, max_iterations, parameter_tolerance)));
      },
      py::arg("model"), py::arg("points"), py::arg("smoothness") = 0.0,
      py::arg("max_iterations") = 30, py::arg("parameter_tolerance") = 1e-12, fit_doc);
  module.def(
      "principal_plane_surface",
      [](const py::object& points, int degree, int spans) {
        return principal_plane_surface(matrix_from_array(points, "points", -1, 3), degree, spans);
      },
      py::arg("points"), py::arg("degree") = 3, py::arg("spans") = 4,
      "A flat clamped uniform NurbsSurface over the principal plane of `points` (k, 3): a "
      "fitting start.");
  module.def(
      "principal_axis_curve",
      [](const py::object& points, int degree, int spans) {
        return principal_axis_curve(matrix_from_array(points, "points", -1, 3), degree, spans);
      },
      py::arg("points"), py::arg("degree") = 3, py::arg("spans") = 4,
      "A straight clamped uniform NurbsCurve along the principal axis of `points` (k, 3).");
  module.def("minimize_energy", &design, py::arg("system"), py::arg("constraints") = nullptr,
             py::arg("algorithm") = "slsqp", py::arg("variable_tolerance") = 1e-14,
             py::arg("constraint_tolerance") = 1e-12, py::arg("max_evaluations") = 5000,
             "Energy-minimizing design: minimizes the models' elastic energy minus the work of "
             "the applied forces over the free coordinates of `system`, the rows of the "
             "ConstraintSolver `constraints` (or None) as equalities (NLopt). Does not change "
             "the system. Returns a dict coordinates (n,), iterations, energy, "
             "constraint_violation, status, status_name, converged.");
}

}  // namespace dnurbs::python
