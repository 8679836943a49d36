// dnurbs.ConstraintSolver (constraints/constraint_solver.h) with the point, ball-joint, hinge and
// control point constraints (constraints/point_constraints.h), the surface normal constraint and
// the curve-on-surface joints (constraints/surface_constraints.h) or following samples
// (constraints/curve_on_surface_constraint.h, with curve_to_surface_distances): holonomic
// constraints stabilized with Baumgarte's method (Terzopoulos, Deformable Models, eqs. 1.39-1.40).

#include <pybind11/stl.h>

#include "dnurbs/constraints/constraint_solver.h"
#include "dnurbs/constraints/curve_on_surface_constraint.h"
#include "dnurbs/constraints/point_constraints.h"
#include "dnurbs/constraints/surface_constraints.h"
#include "python/src/bindings.h"
#include "python/src/model_arguments.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

namespace {

py::dict report_dict(const ConstraintReport& report) {
  py::dict result;
  result["row_count"] = report.row_count;
  result["rank"] = report.rank;
  result["rank_deficient"] = report.rank_deficient;
  result["involved"] = report.involved;
  result["residual"] = report.residual;
  result["message"] = report.message;
  return result;
}

void bind_surface_constraints(py::class_<ConstraintSolver>& solver) {
  solver
      .def(
          "add_surface_normal",
          [](ConstraintSolver& self, const System& system, int model, const py::object& uv,
             const py::object& direction, double alpha, double beta) {
            return self.add(system,
                            SurfaceNormalConstraint(model, material_parameter(uv),
                                                    vector3_argument(direction, "direction")),
                            {alpha, beta});
          },
          py::arg("system"), py::arg("model"), py::arg("uv"), py::arg("direction"),
          py::arg("alpha") = 20.0, py::arg("beta") = -1.0,
          "The normal S_u x S_v of surface `model` at uv (2,) held parallel to `direction` (3,) "
          "(2 rows, in units of |S_u x S_v|); the model must give tangent kinematics (D-NURBS "
          "surfaces do). Returns the index.")
      .def(
          "add_hinge",
          [](ConstraintSolver& self, const System& system, int model_a, const py::object& axis_a0,
             const py::object& axis_a1, int model_b, const py::object& axis_b0,
             const py::object& axis_b1, double alpha, double beta) {
            return self.add(
                system,
                HingeConstraint(model_a, material_parameter(axis_a0), material_parameter(axis_a1),
                                model_b, material_parameter(axis_b0), material_parameter(axis_b1)),
                {alpha, beta});
          },
          py::arg("system"), py::arg("model_a"), py::arg("axis_a0"), py::arg("axis_a1"),
          py::arg("model_b"), py::arg("axis_b0"), py::arg("axis_b1"), py::arg("alpha") = 20.0,
          py::arg("beta") = -1.0,
          "A hinge: ball joints x_a(axis_a0) = x_b(axis_b0) and x_a(axis_a1) = x_b(axis_b1) (6 "
          "rows). Returns the index.")
      .def(
          "add_curve_on_surface",
          [](ConstraintSolver& self, const System& system, int curve_model, int surface_model,
             int sample_count, double alpha, double beta, bool follow) {
            std::vector<int> indices;
            if (follow) {
              indices.push_back(self.add(
                  system,
                  evenly_sampled_curve_on_surface(system, curve_model, surface_model, sample_count),
                  {alpha, beta}));
              return indices;
            }
            for (auto& constraint :
                 curve_on_surface_constraints(system, curve_model, surface_model, sample_count)) {
              indices.push_back(self.add(system, std::move(constraint), {alpha, beta}));
            }
            return indices;
          },
          py::arg("system"), py::arg("curve_model"), py::arg("surface_model"),
          py::arg("sample_count"), py::arg("alpha") = 20.0, py::arg("beta") = -1.0,
          py::arg("follow") = false,
          "Holds D-NURBS curve `curve_model` on D-NURBS surface `surface_model` at `sample_count` "
          "curve parameters spread evenly over its domain. follow=False: ball joints (3 rows "
          "each), each to the surface point nearest it now. follow=True: one constraint of "
          "sample_count rows, the signed distance of each sample from its nearest surface point "
          "re-found at every step (the curve may slide over the surface; needs sample_count >= "
          "2). Returns the constraints' indices (a list).");
}

void bind_solver_details(py::class_<ConstraintSolver>& solver) {
  solver
      .def(
          "description",
          [](const ConstraintSolver& self, int i) {
            if (i < 0 || i >= self.constraint_count()) {
              throw make_error("constraint index ", i, " is outside 0..",
                               self.constraint_count() - 1);
            }
            return self.constraint(i).description();
          },
          py::arg("i"), "A description of constraint i.")
      .def("set_projection", &ConstraintSolver::set_projection, py::arg("enabled"),
           py::arg("tolerance") = 1e-12, py::arg("iterations") = 5,
           "After each step, project the coordinates onto C = 0 (Gauss-Newton steps until max "
           "|C| <= tolerance, at most `iterations`).")
      .def("max_violation", &ConstraintSolver::max_violation, py::arg("system"),
           "max_i |C_i| at the system's current state (0 without constraints).")
      .def_property_readonly(
          "constraint_force",
          [](const ConstraintSolver& self) { return array_from_vector(self.constraint_force()); },
          "The generalized constraint force -C_q^T lambda of the last step, (m,).")
      .def_property_readonly("rank_deficient_steps", &ConstraintSolver::rank_deficient_steps,
                             "Steps whose constraint rows were rank deficient so far.");
}

void bind_constraint_solver(py::module_& module) {
  py::class_<ConstraintSolver> solver(
      module, "ConstraintSolver",
      "Holonomic constraints C(q, t) = 0 on a System, stabilized with Baumgarte's method "
      "(alpha, beta; beta < 0: beta = alpha) and solved with the step (Terzopoulos, Deformable "
      "Models, eqs. 1.39-1.40).");
  solver.def(py::init<>(), "An empty set of constraints.")
      .def(
          "add_point_target",
          [](ConstraintSolver& self, const System& system, int model, const py::object& u,
             const TargetTrajectory& target, double alpha, double beta) {
            return self.add(system, PointTargetConstraint(model, material_parameter(u), target),
                            {alpha, beta});
          },
          py::arg("system"), py::arg("model"), py::arg("u"), py::arg("target"),
          py::arg("alpha") = 20.0, py::arg("beta") = -1.0,
          "x(u) of `model` follows the TargetTrajectory `target`; returns the index.")
      .def(
          "add_point_to_point",
          [](ConstraintSolver& self, const System& system, int model_a, const py::object& u_a,
             int model_b, const py::object& u_b, double alpha, double beta) {
            return self.add(system,
                            PointToPointConstraint(model_a, material_parameter(u_a), model_b,
                                                   material_parameter(u_b)),
                            {alpha, beta});
          },
          py::arg("system"), py::arg("model_a"), py::arg("u_a"), py::arg("model_b"), py::arg("u_b"),
          py::arg("alpha") = 20.0, py::arg("beta") = -1.0,
          "x_a(u_a) = x_b(u_b) between two models.")
      .def(
          "add_control_point",
          [](ConstraintSolver& self, const System& system, int model, int control_point,
             const py::object& target, double alpha, double beta) {
            return self.add(
                system,
                ControlPointConstraint(model, control_point,
                                       matrix_from_array(target, "target", 1, 3, true).row(0)),
                {alpha, beta});
          },
          py::arg("system"), py::arg("model"), py::arg("control_point"), py::arg("target"),
          py::arg("alpha") = 20.0, py::arg("beta") = -1.0,
          "Control point `control_point` of `model` held at `target` (3,).")
      .def_property_readonly("constraint_count", &ConstraintSolver::constraint_count,
                             "Number of constraints.")
      .def_property_readonly("row_count", &ConstraintSolver::row_count,
                             "Number of constraint rows (3 per point constraint).")
      .def(
          "step",
          [](ConstraintSolver& self, Integrator& integrator, System& system, double dt, int count) {
            for (int i = 0; i < count; ++i) {
              self.step(integrator, system, dt);
            }
          },
          py::arg("integrator"), py::arg("system"), py::arg("dt"), py::arg("count") = 1,
          "Advances `system` `count` steps of dt with every constraint enforced.")
      .def(
          "violations",
          [](const ConstraintSolver& self, const System& system) {
            return array_from_vector(self.violations(system));
          },
          py::arg("system"), "|C_i| per constraint at the current state, (#constraints,).")
      .def_property_readonly(
          "multipliers",
          [](const ConstraintSolver& self) { return array_from_vector(self.multipliers()); },
          "Lagrange multipliers of the last step, (row_count,).")
      .def(
          "last_report",
          [](const ConstraintSolver& self) { return report_dict(self.last_report()); },
          "What the last step found about the rows: a dict row_count, rank, rank_deficient, "
          "involved, residual, message.");
  bind_surface_constraints(solver);
  bind_solver_details(solver);
}

}  // namespace

void bind_constraints(py::module_& module) {
  bind_constraint_solver(module);
  module.def(
      "curve_to_surface_distances",
      [](const System& system, int curve_model, int surface_model,
         const std::vector<double>& parameters) {
        return array_from_vector(
            curve_to_surface_distances(system, curve_model, surface_model, parameters));
      },
      py::arg("system"), py::arg("curve_model"), py::arg("surface_model"), py::arg("parameters"),
      "Signed distances (#t,) of the curve model's points c(t) at `parameters` (#t,) from the "
      "surface model at the current state: |c - s| at the nearest surface point s, signed by "
      "n.(c - s).");
}

}  // namespace dnurbs::python
