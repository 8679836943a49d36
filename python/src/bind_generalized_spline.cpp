// dnurbs.GeneralizedSpline (dynamics/grid/generalized_spline.h): the controlled-continuity spline
// of order n of Terzopoulos, Deformable Models: Classic, Topology-Adaptive and Generalized
// Formulations, eq. 1.17, on a node chain or a grid, with its membrane and thin-plate presets.

#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/grid/generalized_spline.h"
#include "python/src/bindings.h"
#include "python/src/model_arguments.h"
#include "python/src/numpy_arrays.h"
#include "python/src/sparse_matrices.h"

namespace dnurbs::python {

namespace {

// A weight given from Python: a number (constant), a callable f(u, v) evaluated at the stencil
// centres, or #nodes per-stencil values.
void set_weight(SplineTerm& term, const py::object& value, long nodes) {
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
    term.weight = value.cast<double>();
  } else if (PyCallable_Check(value.ptr()) != 0) {
    const auto function = value.cast<std::function<double(double, double)>>();
    term.weight =
        MaterialFunction([function](const Eigen::Vector2d& u) { return function(u.x(), u.y()); });
  } else {
    term.node_weights = vector_from_array(
        value, "weight of term (" + std::to_string(term.ju) + ", " + std::to_string(term.jv) + ")",
        nodes);
  }
}

GeneralizedSplineMaterial material_from_python(int order, double mass_density,
                                               double damping_density, const py::object& terms,
                                               long nodes) {
  GeneralizedSplineMaterial material;
  material.order = order;
  material.mass_density = mass_density;
  material.damping_density = damping_density;
  if (!terms.is_none()) {
    for (const py::handle item : terms) {
      const auto entry = item.cast<py::tuple>();
      if (entry.size() != 3) {
        throw make_error("a generalized spline term has ", entry.size(),
                         " entries, not 3 (ju, jv, weight)");
      }
      SplineTerm term;
      term.ju = entry[0].cast<int>();
      term.jv = entry[1].cast<int>();
      set_weight(term, py::reinterpret_borrow<py::object>(entry[2]), nodes);
      material.terms.push_back(term);
    }
  }
  return material;
}

}  // namespace

void bind_generalized_spline(py::module_& module) {
  py::class_<GeneralizedSpline, Model>(
      module, "GeneralizedSpline",
      "The controlled-continuity spline of order n (Terzopoulos, Deformable Models, eq. 1.17) on "
      "a node chain (no grid) or a dnurbs.Grid: q = [u_0, u_1, ...] (3 per node), "
      "K = sum_j (m!/j!) h^p D_j^T W_j D_j (dynamics/grid/generalized_spline.h). mass_density 0 "
      "with damping_density > 0 is the massless flow gamma u_t = -K u + f (implicit-euler).")
      .def(py::init([](const py::object& initial, int order, bool closed, const py::object& grid,
                       double mass_density, double damping_density, const py::object& terms) {
             if (grid.is_none()) {
               const Eigen::MatrixXd nodes = matrix_from_array(initial, "initial", -1, 3);
               return GeneralizedSpline(
                   NodeChain(static_cast<int>(nodes.rows()), closed), nodes,
                   material_from_python(order, mass_density, damping_density, terms, nodes.rows()));
             }
             const Grid& g = grid.cast<const Grid&>();
             const Eigen::MatrixXd nodes = matrix_from_array(initial, "initial", g.node_count(), 3);
             return GeneralizedSpline(
                 g, nodes,
                 material_from_python(order, mass_density, damping_density, terms, nodes.rows()));
           }),
           py::arg("initial"), py::arg("order") = 1, py::arg("closed") = false,
           py::arg("grid") = py::none(), py::arg("mass_density") = 1.0,
           py::arg("damping_density") = 0.0, py::arg("terms") = py::none(),
           "initial: node positions (N, 3); grid: a dnurbs.Grid for p = 2, None for a chain "
           "(open, or closed when `closed`); terms: None (every j with 1 <= |j| <= order at "
           "weight 1) or a list of (ju, jv, weight), weight a number, a function w(u, v) "
           "sampled at the stencil centres or per-stencil values (N,). Raises dnurbs.Error as "
           "the C++ constructor.")
      .def_static(
          "membrane_terms",
          [](int dimension, double tension) {
            py::list result;
            for (const SplineTerm& term : membrane_material(dimension, tension).terms) {
              result.append(py::make_tuple(term.ju, term.jv, tension));
            }
            return result;
          },
          py::arg("dimension"), py::arg("tension"),
          "The terms of the membrane (order 1) in 1 or 2 dimensions: [(1, 0, w)] or "
          "[(1, 0, w), (0, 1, w)].")
      .def_static(
          "thin_plate_terms",
          [](double w10, double w01, double w20, double w11, double w02) {
            py::list result;
            const double weights[] = {w10, w01, w20, w11, w02};
            int k = 0;
            for (const SplineTerm& term : thin_plate_material(w10, w01, w20, w11, w02).terms) {
              result.append(py::make_tuple(term.ju, term.jv, weights[k++]));
            }
            return result;
          },
          py::arg("w10"), py::arg("w01"), py::arg("w20"), py::arg("w11"), py::arg("w02"),
          "The terms of the thin plate under tension (order 2, eq. 1.20; |v_uv|^2 weighs 2 w11).")
      .def_property_readonly(
          "node_measure",
          [](const GeneralizedSpline& self) { return array_from_vector(self.node_measure()); },
          "Each node's measure h^p (halved per open end it lies on), (N,).")
      .def(
          "positions",
          [](const GeneralizedSpline& self, const py::object& q) {
            return array_from_matrix(self.positions(model_state(self, q)));
          },
          py::arg("q") = py::none(), "The node positions at q, (N, 3).")
      .def(
          "scalar_stiffness",
          [](const GeneralizedSpline& self, bool dense) {
            return sparse_matrix_to_python(self.scalar().stiffness, dense);
          },
          py::arg("dense") = false, "The scalar stiffness S_K (K = S_K kron I_3), N by N.");
}

}  // namespace dnurbs::python
