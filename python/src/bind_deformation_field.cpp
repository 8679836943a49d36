// dnurbs.DeformationFieldModel (dynamics/fields/deformation_field_model.h): a cascade of
// deformation fields (Goldenstein et al. 2005, eqs. 1-4) whose AddVector parameters are the
// generalized coordinates, from Python functions V(u, v) or from a face's geometry image.

#include <string>
#include <utility>

#include <pybind11/stl.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/fields/deformation_field_model.h"
#include "dnurbs/surface/deformable_face.h"
#include "python/src/bindings.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

namespace {

DeformationFieldSettings settings_from_python(const py::object& stiffness, double mass_density,
                                              double damping_density,
                                              const std::pair<int, int>& quadrature_cells,
                                              int quadrature_points, double max_error,
                                              long parameters) {
  DeformationFieldSettings settings;
  settings.mass_density = mass_density;
  settings.damping_density = damping_density;
  if (!stiffness.is_none()) {
    settings.stiffness = vector_from_array(stiffness, "stiffness", parameters);
  }
  settings.quadrature_cells_u = quadrature_cells.first;
  settings.quadrature_cells_v = quadrature_cells.second;
  settings.quadrature_points = quadrature_points;
  settings.tessellation_max_error = max_error;
  return settings;
}

// A Python function V(u, v) -> (3,) as a VectorField
VectorField python_field(const py::object& function, const std::string& name) {
  if (PyCallable_Check(function.ptr()) == 0) {
    throw make_error(name, " is not a function V(u, v)");
  }
  return [function, name](double u, double v) -> Eigen::Vector3d {
    return vector_from_array(function(u, v), name, 3);
  };
}

}  // namespace

void bind_deformation_field(py::module_& module) {
  py::class_<DeformationFieldModel, Model>(
      module, "DeformationFieldModel",
      "A cascade of deformation fields as a dynamic model (Goldenstein et al. 2005, eqs. 1-4; "
      "dynamics/fields/deformation_field_model.h): q = the AddVector parameters, x(u, v) = "
      "F_{u,v}(q), L = dF/dq constant, M = integral mu L^T L du dv, D = integral gamma L^T L "
      "du dv, K = diag(stiffness).")
      .def(py::init([](const py::list& stages, const py::object& initial,
                       const py::object& stiffness, const std::vector<double>& domain,
                       double mass_density, double damping_density,
                       const std::pair<int, int>& quadrature_cells, int quadrature_points,
                       double max_error) {
             DeformationField field;
             for (size_t s = 0; s < stages.size(); ++s) {
               const auto stage = stages[s].cast<py::tuple>();
               const std::string name = "stages[" + std::to_string(s) + "]";
               if (stage.size() == 1) {
                 field.constant(python_field(stage[0], name));
               } else if (stage.size() == 2) {
                 field.add_vector(python_field(stage[0], name), stage[1].cast<int>());
               } else {
                 throw make_error(name, " has ", stage.size(),
                                  " entries, not 1 (V,) or 2 (V, parameter)");
               }
             }
             if (domain.size() != 4) {
               throw make_error("domain has ", domain.size(),
                                " numbers, not 4 (u_min, u_max, v_min, v_max)");
             }
             ParameterDomain rectangle;
             rectangle.u_min = domain[0];
             rectangle.u_max = domain[1];
             rectangle.v_min = domain[2];
             rectangle.v_max = domain[3];
             const long parameters = field.parameter_count();
             return DeformationFieldModel(
                 field, std::nullopt, rectangle,
                 initial.is_none() ? Eigen::VectorXd::Zero(parameters)
                                   : vector_from_array(initial, "initial", parameters),
                 settings_from_python(stiffness, mass_density, damping_density, quadrature_cells,
                                      quadrature_points, max_error, parameters));
           }),
           py::arg("stages"), py::arg("initial") = py::none(), py::arg("stiffness") = py::none(),
           py::arg("domain") = std::vector<double>{0.0, 1.0, 0.0, 1.0},
           py::arg("mass_density") = 1.0, py::arg("damping_density") = 0.0,
           py::arg("quadrature_cells") = std::pair<int, int>(8, 8),
           py::arg("quadrature_points") = 3, py::arg("max_error") = 0.0,
           "stages: [(V,) for a constant stage p = V(u, v), (V, k) for p += q_k V(u, v)], V a "
           "function (u, v) -> (3,); initial, stiffness: (P,) or None (zeros). Raises "
           "dnurbs.Error as the C++ constructor.")
      .def_static(
          "face",
          [](const std::string& geometry_image, const py::object& initial,
             const py::object& stiffness, double mass_density, double damping_density,
             const std::pair<int, int>& quadrature_cells, int quadrature_points, double max_error) {
            const DeformableFace face = DeformableFace::read(geometry_image);
            const long parameters = face.parameter_count();
            return DeformationFieldModel(
                face.field(), std::nullopt, face.domain(),
                initial.is_none() ? Eigen::VectorXd::Zero(parameters)
                                  : vector_from_array(initial, "initial", parameters),
                settings_from_python(stiffness, mass_density, damping_density, quadrature_cells,
                                     quadrature_points, max_error, parameters));
          },
          py::arg("geometry_image"), py::arg("initial") = py::none(),
          py::arg("stiffness") = py::none(), py::arg("mass_density") = 1.0,
          py::arg("damping_density") = 0.0, py::arg("quadrature_cells") = std::pair<int, int>(8, 8),
          py::arg("quadrature_points") = 3, py::arg("max_error") = 0.0,
          "The deformable face of a geometry image file (surface/deformable_face.h): 7 "
          "parameters (frontalis, zygomatic and risorius left and right, jaw_open).")
      .def_property_readonly(
          "tessellation_max_error",
          [](const DeformationFieldModel& self) { return self.settings().tessellation_max_error; },
          "The max error of the model's own adaptive meshes (0: uniform).");
}

}  // namespace dnurbs::python
