// dnurbs.Model (dynamics/core/model.h): the contract every dynamic model answers, bound once for
// every model type; dnurbs.DNurbsCurve and dnurbs.DNurbsSurface built from NURBS shapes
// (dynamics/dnurbs/); dnurbs.model_from_json for every model type of scene files.

#include <limits>
#include <string>

#include <pybind11/stl.h>

#include "dnurbs/dynamics/core/model_tessellation.h"
#include "dnurbs/dynamics/core/sculpted_region.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"
#include "python/src/bindings.h"
#include "python/src/model_arguments.h"
#include "python/src/numpy_arrays.h"
#include "python/src/rest_shape_binding.h"
#include "python/src/sparse_matrices.h"

namespace dnurbs::python {

namespace {

// Material points: u of shape (...) for curves, (..., 2) for surfaces.
ItemArray material_points(const Model& model, const py::object& u) {
  return item_array(u, "u", model.parametric_dimension() == 1 ? 0 : 2);
}

Eigen::Vector2d material_point(const Model& model, const ItemArray& points, py::ssize_t i) {
  const double* u = points.item(i);
  return model.parametric_dimension() == 1 ? Eigen::Vector2d(u[0], 0.0)
                                           : Eigen::Vector2d(u[0], u[1]);
}

py::array_t<double> model_positions(const Model& model, const py::object& q, const py::object& u) {
  const Eigen::VectorXd state = model_state(model, q);
  const ItemArray points = material_points(model, u);
  py::array_t<double> result = new_result(points, {3});
  for (py::ssize_t i = 0; i < points.count; ++i) {
    Eigen::Map<Eigen::Vector3d>(result.mutable_data() + 3 * i) =
        model.position(state, material_point(model, points, i));
  }
  return result;
}

py::object model_jacobian(const Model& model, const py::object& q, const py::object& u,
                          bool dense) {
  const ItemArray points = material_points(model, u);
  if (points.count != 1) {
    throw make_error("position_jacobian takes one material point, got ", points.count);
  }
  return sparse_matrix_to_python(
      model.position_jacobian(model_state(model, q), material_point(model, points, 0)), dense);
}

py::dict model_matrices(const Model& model, const py::object& q, bool dense) {
  ModelMatrices matrices;
  model.assemble_matrices(model_state(model, q), matrices);
  py::dict result;
  result["mass"] = sparse_matrix_to_python(matrices.mass, dense);
  result["damping"] = sparse_matrix_to_python(matrices.damping, dense);
  result["stiffness"] = sparse_matrix_to_python(matrices.stiffness, dense);
  return result;
}

py::array_t<double> model_point_force(const Model& model, const py::object& q, const py::object& u,
                                      const py::object& force) {
  const Eigen::VectorXd state = model_state(model, q);
  const ItemArray points = material_points(model, u);
  const ItemArray forces = item_array(force, "force", 3);
  if (forces.count != points.count) {
    throw make_error("force has ", forces.count, " vectors for ", points.count, " material points");
  }
  Eigen::VectorXd generalized = Eigen::VectorXd::Zero(model.velocity_count());
  for (py::ssize_t i = 0; i < points.count; ++i) {
    model.add_point_force(state, material_point(model, points, i),
                          Eigen::Map<const Eigen::Vector3d>(forces.item(i)), generalized);
  }
  return array_from_vector(generalized);
}

py::object model_exact_shape(const Model& model, const py::object& q) {
  const std::optional<Shape> shape = model.exact_shape(model_state(model, q));
  if (!shape) {
    return py::none();
  }
  return std::visit([](const auto& value) { return py::cast(value); }, *shape);
}

TriangleMesh model_tessellation(const Model& model, const py::object& q, int segments_u,
                                int segments_v, double max_error, const std::string& name) {
  ModelTessellationSettings settings;
  settings.segments_u = segments_u;
  settings.segments_v = segments_v;
  settings.max_error = max_error;
  return tessellate_model(model, model_state(model, q), settings, name);
}

void bind_model_contract(py::class_<Model>& model) {
  model.def_property_readonly("coordinate_count", &Model::coordinate_count, "n, the size of q.")
      .def_property_readonly("velocity_count", &Model::velocity_count,
                             "m, the size of velocities, forces and matrices.")
      .def_property_readonly("parametric_dimension", &Model::parametric_dimension,
                             "1 for curves, 2 for surfaces.")
      .def_property_readonly("matrices_are_constant", &Model::matrices_are_constant,
                             "True if M, D, K do not depend on q.")
      .def_property_readonly(
          "material_parameters",
          [](const Model& self) { return array_from_vector(self.material_parameters()); },
          "The material a run may change (System.set_material_parameters), in the model's "
          "order (PdeSurface: b, c, d, density, damping, su0, su1, sv0, sv1); empty when fixed.")
      .def(
          "initial_coordinates",
          [](const Model& self) { return array_from_vector(self.initial_coordinates()); },
          "The coordinates the model was built with, (n,).")
      .def("position", &model_positions, py::arg("q") = py::none(), py::arg("u") = 0.5,
           "x(u) at q (None: the initial coordinates): u (...) for curves, (..., 2) for "
           "surfaces -> (..., 3).")
      .def("position_jacobian", &model_jacobian, py::arg("q"), py::arg("u"),
           py::arg("dense") = false,
           "L(u) = dx/dq at one material point u: 3 by m, scipy.sparse.csc_matrix (dense=True: "
           "an array).")
      .def("matrices", &model_matrices, py::arg("q") = py::none(), py::arg("dense") = false,
           "M, D, K at q (m by m, symmetric): a dict mass, damping, stiffness of "
           "scipy.sparse.csc_matrix (dense=True: arrays).")
      .def(
          "potential_energy",
          [](const Model& self, const py::object& q) {
            return self.potential_energy(model_state(self, q));
          },
          py::arg("q") = py::none(), "The elastic energy E(q).")
      .def(
          "kinetic_energy",
          [](const Model& self, const py::object& q, const py::object& qd) {
            return self.kinetic_energy(model_state(self, q), model_velocity(self, qd));
          },
          py::arg("q") = py::none(), py::arg("qd") = py::none(),
          "The kinetic energy (1/2) qd^T M(q) qd.")
      .def(
          "internal_force",
          [](const Model& self, const py::object& q) {
            Eigen::VectorXd force = Eigen::VectorXd::Zero(self.velocity_count());
            self.add_internal_force(model_state(self, q), force);
            return array_from_vector(force);
          },
          py::arg("q") = py::none(), "f_int(q) = -dE/dq, (m,).")
      .def("point_force", &model_point_force, py::arg("q"), py::arg("u"), py::arg("force"),
           "The generalized force sum_i L(u_i)^T f_i of point forces `force` (..., 3) at "
           "material points u: (m,).")
      .def_property_readonly("fixed_coordinates", &Model::fixed_coordinates,
                             "Velocity-space indices held fixed (a sorted list).")
      .def("fix_coordinate", &Model::fix_coordinate, py::arg("index"),
           "Fixes one velocity-space coordinate.")
      .def("fix_point", &Model::fix_point, py::arg("i"), "Fixes control point (or node) i.")
      .def("fix_border", &Model::fix_border, "Fixes every point on the border of an open surface.")
      .def(
          "freeze_outside",
          [](Model& self, const py::object& parameters, std::vector<int> control_points,
             int margin) {
            SculptedRegion region;
            if (!parameters.is_none()) {
              const Eigen::MatrixXd uv = matrix_from_array(parameters, "parameters", -1, 2, true);
              for (Eigen::Index i = 0; i < uv.rows(); ++i) {
                region.parameters.emplace_back(uv.row(i).transpose());
              }
            }
            region.control_points = std::move(control_points);
            return self.freeze_outside(region, margin);
          },
          py::arg("parameters") = py::none(), py::arg("control_points") = std::vector<int>{},
          py::arg("margin") = 1,
          "Local sculpting: fixes every control point that cannot move the material points "
          "`parameters` (k, 2) (or (2,)) and the listed control points, grown by `margin` "
          "rings; returns how many were frozen. Raises dnurbs.Error for models without it.")
      .def(
          "advance_coordinates",
          [](const Model& self, const py::object& q, const py::object& dv) {
            const Eigen::VectorXd state = model_state(self, q);
            Eigen::VectorXd result(state.size());
            self.advance_coordinates(state, vector_from_array(dv, "dv", self.velocity_count()),
                                     result);
            return array_from_vector(result);
          },
          py::arg("q"), py::arg("dv"),
          "q advanced by the velocity-space increment dv (m,): q + dv for most models, the "
          "exponential map for rotations (superquadrics). Returns (n,).")
      .def("control_point_offset", &Model::control_point_offset, py::arg("i"),
           "The index in q of control point (or node) i's x coordinate; raises dnurbs.Error "
           "for models without 3-D control points among their coordinates.")
      .def("exact_shape", &model_exact_shape, py::arg("q") = py::none(),
           "The NurbsCurve or NurbsSurface at q, or None for models without one.")
      .def("tessellate", &model_tessellation, py::arg("q") = py::none(), py::arg("segments_u") = 32,
           py::arg("segments_v") = 32, py::arg("max_error") = 0.0, py::arg("name") = "model",
           "A TriangleMesh of the shape at q (curves: a tube); max_error > 0 refines a surface "
           "mesh adaptively.")
      .def("__copy__", [](const Model& self) { return self.clone(); })
      .def(
          "__deepcopy__", [](const Model& self, const py::dict&) { return self.clone(); },
          py::arg("memo"));
}

std::unique_ptr<Model> model_from_json(const std::string& text) {
  // The model through the scene reader and the simulation's own build (boundary conditions
  // included), so that every model type and key of scene files is available.
  Scene scene =
      parse_scene_json(R"({"models": [)" + text + R"(], "run": {"steps": 1}})", "model_from_json");
  const SceneSimulation simulation(std::move(scene));
  return simulation.system().model(0).clone();
}

}  // namespace

void bind_model(py::module_& module) {
  py::class_<Model> model(
      module, "Model",
      "A dynamic model (the contract of dynamics/core/model.h): generalized coordinates q "
      "(n,), velocities (m,), positions x(u) and their Jacobians L(u), the mass, damping and "
      "stiffness matrices, forces, boundary conditions and tessellation. Models are values: "
      "System.add_model copies one.");
  bind_model_contract(model);
  py::class_<DNurbsCurve, Model> curve_class(
      module, "DNurbsCurve",
      "A D-NURBS curve (Terzopoulos, Deformable Models, eq. 1.21-1.26): "
      "q = [P_0, P_1, ...] (3 n), or [P_0, w_0, ...] (4 n) with free "
      "weights.");
  curve_class
      .def(
          py::init([](const NurbsCurve& curve, double mass_density, double damping_density,
                      double tension, double rigidity, bool free_weights,
                      bool initial_shape_at_rest) {
            DNurbsSettings settings;
            settings.weight_mode = free_weights ? WeightMode::kFree : WeightMode::kFixed;
            settings.initial_shape_at_rest = initial_shape_at_rest;
            return DNurbsCurve(curve, {mass_density, damping_density, tension, rigidity}, settings);
          }),
          py::arg("curve"), py::arg("mass_density") = 1.0, py::arg("damping_density") = 0.0,
          py::arg("tension") = 0.0, py::arg("rigidity") = 0.0, py::arg("free_weights") = false,
          py::arg("initial_shape_at_rest") = false,
          "A D-NURBS curve from a NurbsCurve with constant material: mass and damping "
          "densities mu, gamma and the snake energy's tension w1 and rigidity w2 (all >= 0); "
          "with initial_shape_at_rest the energy is measured from the curve as given.")
      .def(
          "curve",
          [](const DNurbsCurve& self, const py::object& q) {
            return self.curve(model_state(self, q));
          },
          py::arg("q") = py::none(), "The NurbsCurve at q.");
  bind_rest_shape(curve_class);
  py::class_<DNurbsSurface, Model> surface_class(
      module, "DNurbsSurface",
      "A tensor-product D-NURBS surface (Terzopoulos, Deformable Models, eq. 1.27) with the "
      "thin-plate-under-tension energy (eq. 1.20): q = [P_0, P_1, ...], control point (i, j) "
      "is node i (n + 1) + j.");
  surface_class
      .def(py::init([](const NurbsSurface& surface, double mass_density, double damping_density,
                       double a10, double a01, double b20, double b11, double b02,
                       bool free_weights, bool initial_shape_at_rest) {
             DNurbsSettings settings;
             settings.weight_mode = free_weights ? WeightMode::kFree : WeightMode::kFixed;
             settings.initial_shape_at_rest = initial_shape_at_rest;
             return DNurbsSurface(surface, {mass_density, damping_density, a10, a01, b20, b11, b02},
                                  settings);
           }),
           py::arg("surface"), py::arg("mass_density") = 1.0, py::arg("damping_density") = 0.0,
           py::arg("a10") = 0.0, py::arg("a01") = 0.0, py::arg("b20") = 0.0, py::arg("b11") = 0.0,
           py::arg("b02") = 0.0, py::arg("free_weights") = false,
           py::arg("initial_shape_at_rest") = false,
           "A D-NURBS surface from a NurbsSurface with constant material: densities mu, gamma, "
           "tensions a10, a01 and rigidities b20, b11, b02 (all >= 0); with "
           "initial_shape_at_rest the energy is measured from the surface as given.")
      .def(
          "surface",
          [](const DNurbsSurface& self, const py::object& q) {
            return self.surface(model_state(self, q));
          },
          py::arg("q") = py::none(), "The NurbsSurface at q.");
  bind_rest_shape(surface_class);
  module.def("model_from_json", &model_from_json, py::arg("text"),
             "A model of any type from the JSON text of one entry of a scene's \"models\" "
             "(docs/scene-format.md: dnurbs_curve, dnurbs_surface, superquadric, "
             "terzopoulos_surface, pde_surface, snake, swung_surface, "
             "triangular_dnurbs_surface), its boundary conditions applied.");
}

}  // namespace dnurbs::python
