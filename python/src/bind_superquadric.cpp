// dnurbs.DeformableSuperquadricModel (dynamics/superquadric/deformable_superquadric_model.h): the
// dynamic deformable superquadric of Terzopoulos, Deformable Models: Classic, Topology-Adaptive
// and Generalized Formulations, eqs. 1.28-1.38, with its settings, state decoding and mass
// properties.

#include <pybind11/stl.h>

#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"
#include "python/src/bindings.h"
#include "python/src/model_arguments.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

namespace {

SuperquadricShapeParameters shape_vector(const py::object& value, const std::string& name) {
  return vector_from_array(value, name, kSuperquadricShapeParameterCount);
}

DeformableSuperquadricParts parts_from(const std::string& parts,
                                       const std::vector<int>& free_shape) {
  DeformableSuperquadricParts result;
  if (parts == "rigid") {
    result = DeformableSuperquadricParts::rigid();
  } else if (parts == "global") {
    result = DeformableSuperquadricParts::global();
  } else if (parts == "full") {
    result = DeformableSuperquadricParts::full();
  } else {
    throw make_error("parts is \"", parts, "\", must be rigid, global or full");
  }
  for (const int k : free_shape) {
    if (k < 0 || k >= kSuperquadricShapeParameterCount) {
      throw make_error("free shape parameter ", k, " is outside 0..",
                       kSuperquadricShapeParameterCount - 1);
    }
    result.shape[static_cast<size_t>(k)] = true;
  }
  return result;
}

DeformableSuperquadricModel make_superquadric(
    const py::object& shape, const py::object& centre, const py::object& orientation,
    const std::string& parts, const std::vector<int>& free_shape, double mass_density,
    double damping_alpha, double damping_beta, const py::object& shape_stiffness,
    const py::object& rest_shape, const py::object& local_stiffness,
    const std::pair<int, int>& mesh_cells, int quadrature_points, bool graded_quadrature,
    double regularization) {
  DeformableSuperquadricSettings settings;
  settings.parts = parts_from(parts, free_shape);
  settings.mass_density = mass_density;
  settings.damping_alpha = damping_alpha;
  settings.damping_beta = damping_beta;
  if (py::isinstance<py::float_>(shape_stiffness) || py::isinstance<py::int_>(shape_stiffness)) {
    settings.shape_stiffness.setConstant(shape_stiffness.cast<double>());
  } else {
    settings.shape_stiffness = shape_vector(shape_stiffness, "shape_stiffness");
  }
  if (!rest_shape.is_none()) {
    settings.rest_shape = shape_vector(rest_shape, "rest_shape");
  }
  const Eigen::Vector3d local = vector3_argument(local_stiffness, "local_stiffness");
  settings.local_stiffness = {local.x(), local.y(), local.z()};
  settings.mesh_cells_u = mesh_cells.first;
  settings.mesh_cells_v = mesh_cells.second;
  settings.quadrature_points = quadrature_points;
  settings.graded_quadrature = graded_quadrature;
  settings.regularization = regularization;
  const Eigen::Vector4d wxyz = vector_from_array(orientation, "orientation", 4);
  return DeformableSuperquadricModel(
      shape_vector(shape, "shape"), vector3_argument(centre, "centre"),
      Eigen::Quaterniond(wxyz(0), wxyz(1), wxyz(2), wxyz(3)), settings);
}

py::dict mass_properties_dict(const RigidMassProperties& properties) {
  return py::dict(
      py::arg("mass") = properties.mass,
      py::arg("centre_of_mass") = array_from_vector(properties.centre_of_mass),
      py::arg("inertia_about_origin") = array_from_matrix(properties.inertia_about_origin),
      py::arg("inertia_about_centre") = array_from_matrix(properties.inertia_about_centre));
}

py::dict layout_dict(const DeformableSuperquadricModel& model) {
  return py::dict(py::arg("translation_coordinate") = model.translation_coordinate_offset(),
                  py::arg("quaternion_coordinate") = model.quaternion_coordinate_offset(),
                  py::arg("shape_coordinate") = model.shape_coordinate_offset(),
                  py::arg("local_coordinate") = model.local_coordinate_offset(),
                  py::arg("translation_velocity") = model.translation_velocity_offset(),
                  py::arg("rotation_velocity") = model.rotation_velocity_offset(),
                  py::arg("shape_velocity") = model.shape_velocity_offset(),
                  py::arg("local_velocity") = model.local_velocity_offset());
}

// A function of (q) returning a 3-vector, bound with q = None for the initial state.
template <typename Function>
auto vector_of_state(Function function) {
  return [function](const DeformableSuperquadricModel& self, const py::object& q) {
    return array_from_vector((self.*function)(model_state(self, q)));
  };
}

// A function of (q, qd) returning a 3-vector.
template <typename Function>
auto vector_of_motion(Function function) {
  return [function](const DeformableSuperquadricModel& self, const py::object& q,
                    const py::object& qd) {
    return array_from_vector((self.*function)(model_state(self, q), model_velocity(self, qd)));
  };
}

void bind_superquadric_state(py::class_<DeformableSuperquadricModel, Model>& model) {
  using M = DeformableSuperquadricModel;
  model
      .def("centre", vector_of_state(&M::centre), py::arg("q") = py::none(),
           "The centre c at q (None: initial), (3,).")
      .def(
          "orientation",
          [](const M& self, const py::object& q) {
            const Eigen::Quaterniond r = self.orientation(model_state(self, q));
            return array_from_vector(Eigen::Vector4d(r.w(), r.x(), r.y(), r.z()));
          },
          py::arg("q") = py::none(), "The normalized orientation quaternion (w, x, y, z), (4,).")
      .def(
          "shape_parameters",
          [](const M& self, const py::object& q) {
            return array_from_vector(self.shape_parameters(model_state(self, q)));
          },
          py::arg("q") = py::none(),
          "All 14 q_s entries at q (a, a1, a2, a3, e1, e2, t1, t2, b1, b2, b3, tau, sx, sy; fixed "
          "ones at their construction values), (14,).")
      .def_property_readonly(
          "rest_shape", [](const M& self) { return array_from_vector(self.rest_shape()); },
          "The rest values of q_s, (14,).")
      .def(
          "mass_properties",
          [](const M& self, const py::object& q) {
            return mass_properties_dict(self.mass_properties(model_state(self, q)));
          },
          py::arg("q") = py::none(),
          "Mass properties of the body-frame shape p = s + d at q by quadrature: a dict mass, "
          "centre_of_mass (3,), inertia_about_origin (3, 3), inertia_about_centre (3, 3).")
      .def("linear_momentum", vector_of_motion(&M::linear_momentum), py::arg("q") = py::none(),
           py::arg("qd") = py::none(),
           "integral mu xdot dA (world frame) at (q, qd) (None: initial q, zero qd), (3,).")
      .def("angular_momentum", vector_of_motion(&M::angular_momentum), py::arg("q") = py::none(),
           py::arg("qd") = py::none(), "integral mu x cross xdot dA about the origin, (3,).")
      .def("centre_of_mass", vector_of_state(&M::centre_of_mass), py::arg("q") = py::none(),
           "World centre of mass (1/m) integral mu x dA at q, (3,).");
}

}  // namespace

void bind_superquadric(py::module_& module) {
  using M = DeformableSuperquadricModel;
  py::class_<M, Model> model(
      module, "DeformableSuperquadricModel",
      "The dynamic deformable superquadric x = c + R (s + d) (Terzopoulos, Deformable Models, "
      "eqs. 1.28-1.38): q = [c (3) | quaternion w, x, y, z (4) | free q_s | q_d (3 #nodes)], "
      "velocities [cdot (3) | body angular velocity (3) | q_s rates | q_d rates], each block "
      "present only if its part is free. Material points are (latitude u, longitude v).");
  model.def(
      py::init(&make_superquadric), py::arg("shape"), py::arg("centre") = py::make_tuple(0, 0, 0),
      py::arg("orientation") = py::make_tuple(1, 0, 0, 0), py::arg("parts") = "rigid",
      py::arg("free_shape") = std::vector<int>{}, py::arg("mass_density") = 1.0,
      py::arg("damping_alpha") = 0.0, py::arg("damping_beta") = 0.0,
      py::arg("shape_stiffness") = 1.0, py::arg("rest_shape") = py::none(),
      py::arg("local_stiffness") = py::make_tuple(1.0, 1.0, 1.0),
      py::arg("mesh_cells") = std::pair<int, int>(8, 16), py::arg("quadrature_points") = 3,
      py::arg("graded_quadrature") = true, py::arg("regularization") = 1e-3,
      "shape: q_s (14,) (a, a1, a2, a3 > 0; e1, e2 squareness; tapering t1, t2; bending b1, "
      "b2, b3; twist tau; shear sx, sy); centre (3,); orientation: a unit quaternion (w, x, y, "
      "z); parts: 'rigid' (c and rotation), 'global' (plus a1..a3, e1, e2, t1, t2, b1, tau, sx, "
      "sy) or 'full' (plus local displacements); free_shape: further q_s indices to free; "
      "Rayleigh damping D = damping_alpha M + damping_beta K; shape_stiffness: a number or "
      "(14,) stiffness of q_s toward rest_shape ((14,), None: the construction shape); "
      "local_stiffness (membrane_u, membrane_v, spring); mesh_cells (u, v) of the local "
      "displacements and quadrature; quadrature_points per cell and direction.");
  model.def_property_readonly("is_rigid", &M::is_rigid, "True for translation and rotation only.")
      .def_property_readonly("layout", &layout_dict,
                             "Offsets of the blocks in q and qdot (-1 for a switched-off part): "
                             "a dict translation_coordinate, quaternion_coordinate, "
                             "shape_coordinate, local_coordinate, translation_velocity, "
                             "rotation_velocity, shape_velocity, local_velocity.")
      .def_property_readonly("free_shape_parameters", &M::free_shape_parameters,
                             "The free q_s indices, in coordinate order (a list).")
      .def_property_readonly(
          "quadrature_points",
          [](const M& self) {
            const auto& points = self.quadrature_points();
            Eigen::MatrixXd table(static_cast<Eigen::Index>(points.size()), 3);
            for (std::size_t i = 0; i < points.size(); ++i) {
              const auto row = static_cast<Eigen::Index>(i);
              table.row(row) << points[i].u, points[i].v, points[i].weight;
            }
            return array_from_matrix(table);
          },
          "The quadrature points (u, v, weight du dv), (#points, 3).")
      .def_property_readonly(
          "quadrature_masses",
          [](const M& self) {
            const auto& masses = self.quadrature_masses();
            return array_from_vector(Eigen::Map<const Eigen::VectorXd>(
                masses.data(), static_cast<Eigen::Index>(masses.size())));
          },
          "The mass of each quadrature point, (#points,).")
      .def_property_readonly(
          "reference_mass_properties",
          [](const M& self) { return mass_properties_dict(self.reference_mass_properties()); },
          "Mass properties of the reference shape (d = 0), as mass_properties.");
  bind_superquadric_state(model);
  module.def(
      "superquadric_parameter_names",
      [] {
        std::vector<std::string> names;
        names.reserve(kSuperquadricShapeParameterCount);
        for (int k = 0; k < kSuperquadricShapeParameterCount; ++k) {
          names.emplace_back(superquadric_parameter_name(k));
        }
        return names;
      },
      "The names of the 14 q_s entries, in order (for messages and plots).");
}

}  // namespace dnurbs::python
