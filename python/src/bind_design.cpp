// Design and fitting from Python: D-NURBS fits to point clouds (design/dnurbs_fitting.h) from a
// principal-plane or principal-axis start (io/scene_fit.h), superquadric fits with global and
// local deformations (design/superquadric_fitting.h), and energy-minimizing design of a System
// under constraints (design/energy_minimization.h).

#include <pybind11/stl.h>

#include "dnurbs/design/dnurbs_fitting.h"
#include "dnurbs/design/energy_minimization.h"
#include "dnurbs/design/superquadric_fitting.h"
#include "dnurbs/io/scene_fit.h"
#include "python/src/bindings.h"
#include "python/src/model_arguments.h"
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

py::dict superquadric_fit(const py::object& points, bool twist, bool shear, bool bend_shape,
                          bool local, const std::pair<int, int>& local_cells,
                          double local_smoothness, const py::object& local_stiffness,
                          int max_evaluations) {
  SuperquadricFitSettings settings;
  settings.fit_twist = twist;
  settings.fit_shear = shear;
  settings.fit_bend_shape = bend_shape;
  settings.max_evaluations = max_evaluations;
  if (local) {
    SuperquadricLocalFitSettings local_settings;
    local_settings.mesh_cells_u = local_cells.first;
    local_settings.mesh_cells_v = local_cells.second;
    local_settings.smoothness = local_smoothness;
    const Eigen::Vector3d k = vector3_argument(local_stiffness, "local_stiffness");
    local_settings.stiffness = {k.x(), k.y(), k.z()};
    settings.local = local_settings;
  }
  const SuperquadricFitResult fit =
      fit_superquadric(matrix_from_array(points, "points", -1, 3), settings);
  py::dict result;
  result["shape"] = array_from_vector(fit.shape);
  result["centre"] = array_from_vector(fit.centre);
  result["rotation"] = array_from_matrix(fit.rotation);
  result["rms_error"] = fit.rms_error;
  result["max_error"] = fit.max_error;
  result["evaluations"] = fit.evaluations;
  if (fit.local) {
    py::dict displacements;
    displacements["mesh_cells"] = py::make_tuple(fit.local->mesh_cells_u, fit.local->mesh_cells_v);
    displacements["q_d"] = array_from_vector(fit.local->displacements);
    displacements["parameters"] = array_from_matrix(fit.local->parameters);
    displacements["rms_error"] = fit.local->rms_error;
    displacements["max_error"] = fit.local->max_error;
    displacements["global_rms_error"] = fit.local->global_rms_error;
    displacements["global_max_error"] = fit.local->global_max_error;
    result["local"] = displacements;
  } else {
    result["local"] = py::none();
  }
  return result;
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
  module.def(
      "fit_superquadric", &superquadric_fit, py::arg("points"), py::arg("twist") = true,
      py::arg("shear") = true, py::arg("bend_shape") = false, py::arg("local") = false,
      py::arg("local_cells") = std::pair<int, int>(8, 16), py::arg("local_smoothness") = 1e-4,
      py::arg("local_stiffness") = py::make_tuple(1.0, 1.0, 0.0),
      py::arg("max_evaluations") = 20000,
      "Fits a deformable superquadric (Terzopoulos, Deformable Models, eqs. 1.28-1.33) to "
      "`points` (k, 3) by radial distance: pose, sizes, squareness, taper, bend amplitude and, "
      "unless switched off, twist and shear (bend_shape: the bend's offset b2 and frequency b3 "
      "too). With local=True the displacements d = S q_d on a local_cells (nu, nv) mesh follow: "
      "the static equilibrium of the local_stiffness (membrane_u, membrane_v, spring) energy, "
      "weighted by local_smoothness, against springs to the points. Returns a dict shape: q_s "
      "(14,) with a = 1, centre (3,), rotation (3, 3) body to world, rms_error, max_error "
      "(radial distances), evaluations, and local: None or a dict mesh_cells, q_d (3 #nodes,), "
      "parameters (k, 2), rms_error, max_error, global_rms_error, global_max_error.");
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
