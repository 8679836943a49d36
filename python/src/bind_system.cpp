// dnurbs.System (dynamics/core/system.h): models stepped together, their state as NumPy arrays,
// applied forces (dynamics/core/forces.h) and implicit springs (dynamics/core/spring.h) added,
// moved and removed between steps.

#include <limits>

#include <pybind11/stl.h>

#include "dnurbs/constraints/target_trajectory.h"
#include "dnurbs/dynamics/core/data_force.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/spring.h"
#include "dnurbs/dynamics/core/system.h"
#include "python/src/bindings.h"
#include "python/src/numpy_arrays.h"
#include "python/src/sparse_matrices.h"

namespace dnurbs::python {

namespace {

constexpr double kForever = std::numeric_limits<double>::infinity();

Eigen::Vector3d vector3(const py::object& value, const std::string& name) {
  return matrix_from_array(value, name, 1, 3, true).row(0).transpose();
}

// A 3-vector argument: constant ((3,)), a TargetTrajectory (evaluated in C++) or a Python
// function of time returning (3,).
VectorOfTime vector_of_time(const py::object& value, const std::string& name) {
  if (py::isinstance<TargetTrajectory>(value)) {
    return [target = value.cast<TargetTrajectory>()](double time) { return target.position(time); };
  }
  if (PyCallable_Check(value.ptr()) != 0) {
    return [function = py::reinterpret_borrow<py::function>(value), name](double time) {
      const py::gil_scoped_acquire gil;
      return vector3(function(time), name + "(t)");
    };
  }
  return [constant = vector3(value, name)](double) -> Eigen::Vector3d { return constant; };
}

// Data points (N, 3), constant or a Python function of time returning (N, 3).
PointsOfTime points_of_time(const py::object& value) {
  if (PyCallable_Check(value.ptr()) != 0) {
    return [function = py::reinterpret_borrow<py::function>(value)](double time) {
      const py::gil_scoped_acquire gil;
      return Eigen::MatrixX3d(matrix_from_array(function(time), "points(t)", -1, 3));
    };
  }
  return [constant = Eigen::MatrixX3d(matrix_from_array(value, "points", -1, 3))](double) {
    return constant;
  };
}

DataForceSettings data_force_settings(double stiffness, int search_segments, int refinement_steps) {
  DataForceSettings settings;
  settings.stiffness = stiffness;
  settings.search_segments = search_segments;
  settings.refinement_steps = refinement_steps;
  return settings;
}

Spring make_spring(const py::object& u, const py::object& target, double stiffness, double start,
                   double end) {
  return windowed_spring(
      mouse_spring(material_parameter(u), vector_of_time(target, "target"), stiffness), start, end);
}

py::dict spring_state_dict(const System& system, int id, const py::object& time) {
  const SpringState state =
      system.spring_state(id, time.is_none() ? system.time() : time.cast<double>());
  py::dict result;
  result["parameter"] = array_from_vector(state.parameter);
  result["target"] = array_from_vector(state.target);
  result["stiffness"] = state.stiffness;
  return result;
}

void bind_system_state(py::class_<System>& system) {
  system.def(py::init<>(), "An empty system; add models with add_model.")
      .def("__copy__", [](const System& self) { return System(self); })
      .def(
          "__deepcopy__", [](const System& self, const py::dict&) { return System(self); },
          py::arg("memo"))
      .def("add_model", &System::add_model, py::arg("model"),
           "Adds a copy of `model` with its initial coordinates and zero velocity; returns its "
           "index. Later changes to `model` do not reach the system: use fix_point and "
           "fix_border of the system.")
      .def("fix_point", &System::fix_point, py::arg("model"), py::arg("point"),
           "Fixes control point (or node) `point` of the system's model `model` where it is now "
           "(its velocity zero).")
      .def("fix_border", &System::fix_border, py::arg("model"),
           "Fixes every point on the border of the system's model `model`.")
      .def(
          "set_material_parameters",
          [](System& self, int model, const py::object& values) {
            return self.set_material_parameters(model, vector_from_array(values, "values", -1));
          },
          py::arg("model"), py::arg("values"),
          "Sets the material of the system's model `model` between steps (its "
          "material_parameters order): the state stays, integrators refactor. False, changing "
          "nothing, when the values are the current ones.")
      .def_property_readonly("model_count", &System::model_count, "Number of models.")
      .def(
          "model", [](const System& self, int i) { return self.model(i).clone(); }, py::arg("i"),
          "A copy of model i (fix points through the system's fix_point and fix_border).")
      .def("coordinate_offset", &System::coordinate_offset, py::arg("i"),
           "Offset of model i's coordinates in the stacked q.")
      .def("velocity_offset", &System::velocity_offset, py::arg("i"),
           "Offset of model i's velocities in the stacked velocities.")
      .def_property_readonly("time", &System::time, "The current time t.")
      .def("set_time", &System::set_time, py::arg("time"), "Sets the current time.")
      .def_property_readonly(
          "coordinates", [](const System& self) { return array_from_vector(self.coordinates()); },
          "The stacked coordinates q, (n,): a new array.")
      .def_property_readonly(
          "velocities", [](const System& self) { return array_from_vector(self.velocities()); },
          "The stacked velocities, (m,): a new array.")
      .def(
          "model_coordinates",
          [](const System& self, int i) { return array_from_vector(self.coordinates(i)); },
          py::arg("i"), "Model i's coordinates, (n_i,): a new array.")
      .def(
          "set_coordinates",
          [](System& self, int i, const py::object& q) {
            self.set_coordinates(i, vector_from_array(q, "q", self.model(i).coordinate_count()));
          },
          py::arg("i"), py::arg("q"), "Sets model i's coordinates (n_i,) (checked: finite).")
      .def(
          "set_velocities",
          [](System& self, int i, const py::object& qd) {
            self.set_velocities(i, vector_from_array(qd, "qd", self.model(i).velocity_count()));
          },
          py::arg("i"), py::arg("qd"), "Sets model i's velocities (m_i,).")
      .def(
          "position",
          [](const System& self, int i, const py::object& u) {
            return array_from_vector(self.position(i, material_parameter(u)));
          },
          py::arg("i"), py::arg("u"), "x(u) of model i at the current state, (3,).")
      .def_property_readonly("fixed_coordinates", &System::fixed_coordinates,
                             "Velocity-space indices held fixed (stacked, sorted).")
      .def("kinetic_energy", &System::kinetic_energy, "(1/2) qd^T M qd.")
      .def("potential_energy", &System::potential_energy, "The models' elastic energy.")
      .def(
          "spring_energy", [](const System& self) { return self.spring_energy(); },
          "Sum of (1/2) k |x(u) - target|^2 over the springs now.")
      .def(
          "matrices",
          [](const System& self, bool dense) {
            ModelMatrices matrices;
            self.assemble_matrices(self.coordinates(), matrices);
            py::dict result;
            result["mass"] = sparse_matrix_to_python(matrices.mass, dense);
            result["damping"] = sparse_matrix_to_python(matrices.damping, dense);
            result["stiffness"] = sparse_matrix_to_python(matrices.stiffness, dense);
            return result;
          },
          py::arg("dense") = false,
          "Block-diagonal M, D, K at the current state (m by m): a dict of "
          "scipy.sparse.csc_matrix (dense=True: arrays).")
      .def(
          "applied_forces",
          [](const System& self, bool include_springs) {
            Eigen::VectorXd force = Eigen::VectorXd::Zero(self.velocity_count());
            self.add_applied_forces(self.time(), self.coordinates(), self.velocities(), force,
                                    include_springs);
            return array_from_vector(force);
          },
          py::arg("include_springs") = true,
          "The generalized applied forces at the current time and state, (m,).");
}

void bind_system_forces(py::class_<System>& system) {
  system
      .def(
          "add_point_force",
          [](System& self, int i, const py::object& u, const py::object& force, double start,
             double end) {
            return self.add_force(
                i, windowed(point_force(material_parameter(u), vector_of_time(force, "force")),
                            start, end));
          },
          py::arg("i"), py::arg("u"), py::arg("force"), py::arg("start") = 0.0,
          py::arg("end") = kForever,
          "The force f (3,) or f(t) (a function of time returning (3,)) at material point u of "
          "model i while start <= t < end; returns the force's index.")
      .def(
          "add_gravity",
          [](System& self, int i, const py::object& acceleration, double start, double end) {
            return self.add_force(
                i, windowed(gravity(vector3(acceleration, "acceleration")), start, end));
          },
          py::arg("i"), py::arg("acceleration"), py::arg("start") = 0.0, py::arg("end") = kForever,
          "Gravity: the density mu g per unit parametric measure on model i.")
      .def(
          "add_pressure",
          [](System& self, int i, double value, double start, double end) {
            return self.add_force(i, windowed(pressure(value), start, end));
          },
          py::arg("i"), py::arg("pressure"), py::arg("start") = 0.0, py::arg("end") = kForever,
          "Pressure p along the normal of surface model i (inflation).")
      .def(
          "add_wind",
          [](System& self, int i, const py::object& velocity, double drag, double start,
             double end) {
            return self.add_force(
                i, windowed(wind(vector_of_time(velocity, "velocity"), drag), start, end));
          },
          py::arg("i"), py::arg("velocity"), py::arg("drag"), py::arg("start") = 0.0,
          py::arg("end") = kForever,
          "Wind on surface model i (Terzopoulos et al. 1987): per unit area drag (n . (v - "
          "xdot)) n, n the unit normal, xdot the surface velocity; velocity v (3,) or v(t) (a "
          "function of time returning (3,)), drag >= 0 (force per unit area per unit "
          "velocity). Explicit: its damping is not in the step matrix. Curves feel none. "
          "Returns the force's index.")
      .def(
          "add_data_force",
          [](System& self, int i, const py::object& points, double stiffness, int search_segments,
             int refinement_steps, double start, double end) {
            return self.add_force(
                i, windowed(moving_data_force(
                                points_of_time(points),
                                data_force_settings(stiffness, search_segments, refinement_steps)),
                            start, end));
          },
          py::arg("i"), py::arg("points"), py::arg("stiffness"), py::arg("search_segments") = 24,
          py::arg("refinement_steps") = 30, py::arg("start") = 0.0, py::arg("end") = kForever,
          "Data forces (Terzopoulos & Metaxas 1991): each of the points (N, 3), or points(t) (a "
          "function of time returning (N, 3): tracking), pulls the nearest material point of "
          "model i with a spring of this stiffness. Returns the force's index.")
      .def(
          "add_control_point_force",
          [](System& self, int i, std::vector<int> points, const py::object& force, double start,
             double end) {
            return self.add_force(
                i, windowed(control_point_force(std::move(points), vector_of_time(force, "force")),
                            start, end));
          },
          py::arg("i"), py::arg("control_points"), py::arg("force"), py::arg("start") = 0.0,
          py::arg("end") = kForever,
          "The force f (3,) or f(t) on the position of each listed control point of model i.")
      .def("clear_forces", &System::clear_forces, "Removes every applied force (not springs).")
      .def_property_readonly("force_count", &System::force_count,
                             "Number of applied forces (indices of the add_*force calls).")
      .def(
          "add_spring",
          [](System& self, int i, const py::object& u, const py::object& target, double stiffness,
             double start, double end) {
            return self.add_spring(i, make_spring(u, target, stiffness, start, end));
          },
          py::arg("i"), py::arg("u"), py::arg("target"), py::arg("stiffness"),
          py::arg("start") = 0.0, py::arg("end") = kForever,
          "An implicit spring of stiffness k pulling material point u of model i toward "
          "`target` ((3,) or a function of time returning (3,)) while start <= t < end; its k "
          "L^T L enters the step matrix. Returns the spring's id.")
      .def(
          "move_spring",
          [](System& self, int id, const py::object& u, const py::object& target,
             double stiffness) {
            self.set_spring(id, make_spring(u, target, stiffness, 0.0, kForever));
          },
          py::arg("id"), py::arg("u"), py::arg("target"), py::arg("stiffness"),
          "Replaces spring `id` (a new material point, target and stiffness); the integrator "
          "updates its factor instead of refactoring.")
      .def("remove_spring", &System::remove_spring, py::arg("id"), "Detaches spring `id`.")
      .def("has_spring", &System::has_spring, py::arg("id"),
           "True if spring `id` was added and not removed.")
      .def("spring_model", &System::spring_model, py::arg("id"), "The model of spring `id`.")
      .def("spring_state", &spring_state_dict, py::arg("id"), py::arg("time") = py::none(),
           "Spring `id` at `time` (None: now): a dict parameter (2,), target (3,), stiffness.");
}

}  // namespace

void bind_system(py::module_& module) {
  py::class_<System> system(
      module, "System",
      "Several models stepped together (dynamics/core/system.h): coordinates stacked (model 0 "
      "first), matrices block diagonal, applied forces and implicit springs. A value: copying "
      "it clones its models.");
  bind_system_state(system);
  bind_system_forces(system);
  module.def(
      "nearest_material_points",
      [](const Model& model, const py::object& q, const py::object& points, int search_segments,
         int refinement_steps) {
        const Eigen::VectorXd coordinates = vector_from_array(q, "q", model.coordinate_count());
        const auto nearest =
            nearest_material_points(model, coordinates, matrix_from_array(points, "points", -1, 3),
                                    data_force_settings(1.0, search_segments, refinement_steps));
        Eigen::MatrixXd parameters(static_cast<Eigen::Index>(nearest.size()), 2);
        Eigen::MatrixXd positions(static_cast<Eigen::Index>(nearest.size()), 3);
        for (size_t k = 0; k < nearest.size(); ++k) {
          parameters.row(static_cast<Eigen::Index>(k)) = nearest[k].parameter.transpose();
          positions.row(static_cast<Eigen::Index>(k)) = nearest[k].position.transpose();
        }
        return py::make_tuple(array_from_matrix(parameters), array_from_matrix(positions));
      },
      py::arg("model"), py::arg("q"), py::arg("points"), py::arg("search_segments") = 24,
      py::arg("refinement_steps") = 30,
      "The material points of `model` at q nearest to points (N, 3): (parameters (N, 2), "
      "positions (N, 3)), the search of System.add_data_force.");
}

}  // namespace dnurbs::python
