// Swung surfaces: dnurbs.SwungSurface (nurbs/swung_surface.h) with its prototypes
// (nurbs/swung_shapes.h) and refinement (nurbs/swung_refinement.h), and the swung D-NURBS model
// dnurbs.DNurbsSwungSurface (dynamics/swung/dnurbs_swung_surface.h; Qin & Terzopoulos, Dynamic
// NURBS swung surfaces for physics-based shape design, CAD 27(2) 1995).

#include <pybind11/stl.h>

#include "dnurbs/dynamics/swung/dnurbs_swung_surface.h"
#include "dnurbs/nurbs/swung_refinement.h"
#include "dnurbs/nurbs/swung_shapes.h"
#include "python/src/bindings.h"
#include "python/src/model_arguments.h"
#include "python/src/rest_shape_binding.h"
#include "python/src/surface_arrays.h"

namespace dnurbs::python {

namespace {

void bind_swung_shape(py::module_& module) {
  py::class_<SwungSurface>(
      module, "SwungSurface",
      "A swung surface s(u, v) = (alpha p_x(u) t_x(v), alpha p_x(u) t_y(v), p_z(u)) of a profile "
      "curve p(u) in the xz plane and a trajectory t(v) in the xy plane (Qin & Terzopoulos, CAD "
      "27(2) 1995). A value.")
      .def(py::init<NurbsCurve, NurbsCurve, double>(), py::arg("profile"), py::arg("trajectory"),
           py::arg("alpha") = 1.0,
           "profile: NurbsCurve with every control point at y = 0; trajectory: NurbsCurve with "
           "every control point at z = 0; alpha != 0. Raises dnurbs.Error naming the point.")
      .def_property_readonly("profile", &SwungSurface::profile, "The profile curve p(u).")
      .def_property_readonly("trajectory", &SwungSurface::trajectory, "The trajectory curve t(v).")
      .def_property_readonly("alpha", &SwungSurface::alpha, "The scale of the swing.")
      .def_property_readonly(
          "domain",
          [](const SwungSurface& self) {
            return py::make_tuple(self.u_start(), self.u_end(), self.v_start(), self.v_end());
          },
          "(u_start, u_end, v_start, v_end).")
      .def(
          "__call__",
          [](const SwungSurface& self, const py::object& u, const py::object& v) {
            return vector_per_parameter(u, v, [&](double s, double t) { return self.point(s, t); });
          },
          py::arg("u"), py::arg("v"), "Points s(u, v): u, v broadcast to (...) -> (..., 3).")
      .def("derivatives", &surface_derivative_array<SwungSurface>, py::arg("u"), py::arg("v"),
           py::arg("order"),
           "d^(k+l) s / du^k dv^l: u, v (...) -> (..., order + 1, order + 1, 3), [..., k, l, :] "
           "for k + l <= order, zero beyond.")
      .def(
          "unit_normal",
          [](const SwungSurface& self, const py::object& u, const py::object& v) {
            return vector_per_parameter(u, v,
                                        [&](double s, double t) { return self.unit_normal(s, t); });
          },
          py::arg("u"), py::arg("v"),
          "Unit normals (S_u x S_v)/|S_u x S_v| (defined at poles as the limit): (...) -> (..., "
          "3).")
      .def("to_nurbs_surface", &SwungSurface::to_nurbs_surface,
           "The same surface as an exact tensor-product NurbsSurface.")
      .def("__copy__", [](const SwungSurface& self) { return SwungSurface(self); })
      .def(
          "__deepcopy__",
          [](const SwungSurface& self, const py::dict&) { return SwungSurface(self); },
          py::arg("memo"));
  module.def("unit_circle_trajectory", &unit_circle_trajectory,
             "The periodic rational quadratic unit circle in the xy plane (8 control points).");
  module.def("swung_sphere", &swung_sphere, py::arg("radius"),
             "The exact sphere: a half-circle profile (5 control points) swung around z.");
  module.def("swung_torus", &swung_torus, py::arg("major_radius"), py::arg("minor_radius"),
             "The exact torus, closed in u and v (8 x 8); 0 < minor_radius < major_radius.");
  module.def("swung_open_profile", &swung_open_profile, py::arg("x0"), py::arg("z0"), py::arg("x1"),
             py::arg("z1"), py::arg("profile_control_points") = 4,
             "The surface of the straight profile (x0, 0, z0) -> (x1, 0, z1) swung around z (a "
             "disk, annulus, cylinder or cone).");
  module.def("swung_cylinder", &swung_cylinder, py::arg("radius"), py::arg("height"),
             py::arg("profile_control_points") = 4,
             "The open cylinder x^2 + y^2 = r^2, 0 <= z <= height.");
  module.def("swung_cone", &swung_cone, py::arg("radius"), py::arg("height"),
             py::arg("profile_control_points") = 4,
             "The cone from the circle of radius r at z = 0 to the apex (0, 0, height).");
  module.def("swung_hat", &swung_hat, py::arg("brim_radius"), py::arg("crown_radius"),
             py::arg("height"), "An open hat (8 profile control points).");
  module.def("refine_swung_surface", &refine_swung_surface, py::arg("surface"),
             py::arg("profile_knots"), py::arg("trajectory_knots"),
             "The same surface with `profile_knots` (`trajectory_knots`) knots inserted "
             "uniformly in every non-empty span of the profile (trajectory).");
}

DNurbsSwungSurface make_swung_model(const SwungSurface& surface, double mass_density,
                                    double damping_density, double a10, double a01, double b20,
                                    double b11, double b02, bool free_weights,
                                    int quadrature_points, double minimum_weight, bool fix_gauge,
                                    bool geometric_stiffness, double weight_inertia,
                                    bool separable_assembly, bool initial_shape_at_rest) {
  DNurbsSwungSettings settings;
  settings.weight_mode = free_weights ? WeightMode::kFree : WeightMode::kFixed;
  settings.quadrature_points = quadrature_points;
  settings.minimum_weight = minimum_weight;
  settings.fix_gauge = fix_gauge;
  settings.geometric_stiffness = geometric_stiffness;
  settings.weight_inertia = weight_inertia;
  settings.separable_assembly = separable_assembly;
  settings.initial_shape_at_rest = initial_shape_at_rest;
  return DNurbsSwungSurface(surface, {mass_density, damping_density, a10, a01, b20, b11, b02},
                            settings);
}

void bind_swung_model(py::module_& module) {
  using S = DNurbsSwungSurface;
  py::class_<S, Model> model_class(
      module, "DNurbsSwungSurface",
      "A swung D-NURBS surface: q = [x_0, z_0, (w_0), ... | X_0, Y_0, (W_0), ...], the "
      "profile's control points then the trajectory's (Qin & Terzopoulos, CAD 27(2) 1995), with "
      "the D-NURBS energy of the tensor-product model.");
  model_class
      .def(py::init(&make_swung_model), py::arg("surface"), py::arg("mass_density") = 1.0,
           py::arg("damping_density") = 0.0, py::arg("a10") = 0.0, py::arg("a01") = 0.0,
           py::arg("b20") = 0.0, py::arg("b11") = 0.0, py::arg("b02") = 0.0,
           py::arg("free_weights") = false, py::arg("quadrature_points") = 0,
           py::arg("minimum_weight") = 1e-3, py::arg("fix_gauge") = true,
           py::arg("geometric_stiffness") = false, py::arg("weight_inertia") = 0.0,
           py::arg("separable_assembly") = true, py::arg("initial_shape_at_rest") = false,
           "surface: a SwungSurface; densities and stiffnesses as DNurbsSurface (>= 0); "
           "free_weights: weights are coordinates; quadrature_points per span (0: exact for "
           "polynomial curves); fix_gauge fixes the scaling gauge; geometric_stiffness: exact "
           "tangent stiffness instead of Gauss-Newton; separable_assembly: closed-form forms "
           "where possible; initial_shape_at_rest: the energy of the change from the surface as "
           "given (set_rest_shape).")
      .def_property_readonly(
          "free_weights", [](const S& self) { return self.weight_mode() == WeightMode::kFree; },
          "True if the weights are coordinates.")
      .def_property_readonly("minimum_weight", &S::minimum_weight, "The free weights' lower bound.")
      .def("profile_offset", &S::profile_offset, py::arg("i"),
           "Index in q of the x coordinate of profile control point i (z follows).")
      .def("trajectory_offset", &S::trajectory_offset, py::arg("j"),
           "Index in q of the x coordinate of trajectory control point j (y follows).")
      .def_property_readonly("gauge_coordinate", &S::gauge_coordinate,
                             "The coordinate fixed for the scaling gauge, or -1.")
      .def("fix_profile_point", &S::fix_profile_point, py::arg("i"),
           "Fixes the in-plane coordinates of profile control point i.")
      .def("fix_trajectory_point", &S::fix_trajectory_point, py::arg("j"),
           "Fixes the in-plane coordinates of trajectory control point j.")
      .def("fix_profile", &S::fix_profile, "Fixes every profile coordinate.")
      .def("fix_trajectory", &S::fix_trajectory, "Fixes every trajectory coordinate.")
      .def("fix_poles", &S::fix_poles,
           "Keeps the poles closed: fixes x of each end profile point on the z axis.")
      .def(
          "surface",
          [](const S& self, const py::object& q) { return self.surface(model_state(self, q)); },
          py::arg("q") = py::none(), "The SwungSurface at q (None: the initial one).")
      .def_property_readonly("initial_surface", &S::initial_surface,
                             "The SwungSurface the model was built from.")
      .def(
          "jacobian",
          [](const S& self, const py::object& q, const py::object& u, int order) {
            if (order < 0 || order > 2) {
              throw make_error("derivative order ", order, " is outside 0..2");
            }
            SwungJacobian jacobian;
            self.jacobian(model_state(self, q), material_parameter(u), order, jacobian);
            const int quantities = (order + 1) * (order + 2) / 2;
            py::array_t<double> result({quantities, 3, self.coordinate_count()});
            std::fill(result.mutable_data(), result.mutable_data() + result.size(), 0.0);
            auto out = result.mutable_unchecked<3>();
            for (int k = 0; k < quantities; ++k) {
              for (int c = 0; c < jacobian.column_count; ++c) {
                for (int row = 0; row < 3; ++row) {
                  out(k, row, jacobian.coordinate[static_cast<size_t>(c)]) =
                      jacobian.columns[static_cast<size_t>(k)](row, c);
                }
              }
            }
            return result;
          },
          py::arg("q"), py::arg("u"), py::arg("order") = 0,
          "The Jacobians dS^Q/dq of S, S_u, S_v, S_uu, S_uv, S_vv (those of total order <= "
          "`order`, 0..2) at the material point u (2,) and state q: (#quantities, 3, n), dense.")
      .def(
          "jacobian_rate",
          [](const S& self, const py::object& q, const py::object& qd, const py::object& u,
             int order) {
            if (order < 0 || order > 2) {
              throw make_error("derivative order ", order, " is outside 0..2");
            }
            std::array<Eigen::Vector3d, 6> rates;
            self.jacobian_rate(model_state(self, q), model_velocity(self, qd),
                               material_parameter(u), order, rates);
            const int quantities = (order + 1) * (order + 2) / 2;
            Eigen::MatrixXd table(quantities, 3);
            for (int k = 0; k < quantities; ++k) {
              table.row(k) = rates[static_cast<size_t>(k)].transpose();
            }
            return array_from_matrix(table);
          },
          py::arg("q"), py::arg("qd"), py::arg("u"), py::arg("order") = 0,
          "Jdot qd of S, S_u, ... (total order <= `order`) at u: the velocity-product part of "
          "d^2 S^Q/dt^2, (#quantities, 3).")
      .def_property_readonly("parametric_measure", &S::parametric_measure,
                             "Area of the parametric domain.")
      .def_property_readonly("uses_separable_assembly", &S::uses_separable_assembly,
                             "True if the closed-form separable path is used.");
  bind_rest_shape(model_class);
}

}  // namespace

void bind_swung(py::module_& module) {
  bind_swung_shape(module);
  bind_swung_model(module);
}

}  // namespace dnurbs::python
