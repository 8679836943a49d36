// dnurbs.KnotVector (nurbs/knot_vector.h) and dnurbs.Direction (nurbs/knot_insertion.h).

#include <sstream>

#include <pybind11/stl.h>

#include "dnurbs/nurbs/knot_insertion.h"
#include "dnurbs/nurbs/knot_vector.h"
#include "python/src/bindings.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

namespace {

std::string knot_vector_repr(const KnotVector& knots) {
  std::ostringstream text;
  text << "KnotVector(degree=" << knots.degree() << ", "
       << (knots.is_periodic() ? "periodic, " : "")
       << "control_point_count=" << knots.control_point_count() << ", domain=["
       << knots.domain_start() << ", " << knots.domain_end() << "])";
  return text.str();
}

}  // namespace

void bind_knot_vector(py::module_& module) {
  py::enum_<SurfaceDirection>(module, "Direction",
                              "Parametric direction of a tensor-product surface: U or V.")
      .value("U", SurfaceDirection::kU)
      .value("V", SurfaceDirection::kV);

  py::class_<KnotVector>(
      module, "KnotVector",
      "A non-decreasing knot vector of a B-spline basis of a given degree (Piegl & Tiller, The "
      "NURBS Book, ch. 2), open or periodic.\n\n"
      "Open: knots t_0..t_m with m + 1 = control_point_count + degree + 1, domain "
      "[t_p, t_{m-p}].\nPeriodic: one period extended by p knots on each side; control point "
      "index k of the wrapped polygon is distinct control point k mod n.")
      .def(py::init([](int degree, const py::object& knots) {
             return KnotVector(degree, list_from_array(knots, "knots"));
           }),
           py::arg("degree"), py::arg("knots"),
           "Open knot vector. degree: 1..15; knots: array_like of shape (m + 1,), "
           "non-decreasing, finite. Raises dnurbs.Error naming the bad knot otherwise.")
      .def_static("clamped_uniform", &KnotVector::clamped_uniform, py::arg("degree"),
                  py::arg("control_point_count"), py::arg("start") = 0.0, py::arg("end") = 1.0,
                  "Clamped knot vector with uniformly spaced interior knots over [start, end].")
      .def_static(
          "clamped_from_breakpoints",
          [](int degree, const py::object& breakpoints) {
            return KnotVector::clamped_from_breakpoints(
                degree, list_from_array(breakpoints, "breakpoints"));
          },
          py::arg("degree"), py::arg("breakpoints"),
          "Clamped knot vector with the given breakpoints (shape (k,), strictly increasing; the "
          "first and last are the domain ends; interior ones get multiplicity 1).")
      .def_static("uniform", &KnotVector::uniform, py::arg("degree"),
                  py::arg("control_point_count"),
                  "Unclamped uniform knot vector t_i = i (domain [degree, control_point_count]).")
      .def_static(
          "periodic",
          [](int degree, const py::object& period_knots) {
            return KnotVector::periodic(degree, list_from_array(period_knots, "period_knots"));
          },
          py::arg("degree"), py::arg("period_knots"),
          "Periodic knot vector from the knots t_p..t_{p+n} of one period: shape (n + 1,) for n "
          "distinct control points (n >= degree + 1), non-decreasing, multiplicity at most "
          "degree also across the wrap.")
      .def_static("periodic_uniform", &KnotVector::periodic_uniform, py::arg("degree"),
                  py::arg("control_point_count"), py::arg("start") = 0.0, py::arg("end") = 1.0,
                  "Periodic knot vector with control_point_count equal spans over [start, end].")
      .def_property_readonly("degree", &KnotVector::degree, "The degree p.")
      .def_property_readonly("is_periodic", &KnotVector::is_periodic, "True for periodic vectors.")
      .def_property_readonly("control_point_count", &KnotVector::control_point_count,
                             "Number of distinct control points the basis drives.")
      .def_property_readonly("basis_count", &KnotVector::basis_count,
                             "Number of basis functions (n open, n + p periodic).")
      .def_property_readonly(
          "knots",
          [](const py::object& self) {
            const auto& knots = self.cast<const KnotVector&>().knots();
            return read_only_view(knots.data(), static_cast<py::ssize_t>(knots.size()), self);
          },
          "The stored knots, shape (size,), a read-only view (no copy).")
      .def_property_readonly(
          "period_knots",
          [](const KnotVector& self) {
            const std::vector<double> knots = self.period_knots();
            return array_from_vector(Eigen::Map<const Eigen::VectorXd>(
                knots.data(), static_cast<Eigen::Index>(knots.size())));
          },
          "The knots of one period t_p..t_{p+n} (periodic) or all knots (open), a new array.")
      .def_property_readonly(
          "domain",
          [](const KnotVector& self) {
            return py::make_tuple(self.domain_start(), self.domain_end());
          },
          "The parameter domain (start, end).")
      .def("find_span", &KnotVector::find_span, py::arg("u"),
           "Index k of the non-empty knot span [t_k, t_{k+1}) containing u.")
      .def("multiplicity", &KnotVector::multiplicity, py::arg("u"), "Number of knots equal to u.")
      .def("non_empty_spans", &KnotVector::non_empty_spans,
           "Indices k of the non-empty spans of the domain, increasing (a list).")
      .def("__len__", &KnotVector::size)
      .def("__eq__", [](const KnotVector& a, const KnotVector& b) { return a == b; })
      .def("__repr__", &knot_vector_repr)
      .def("__copy__", [](const KnotVector& self) { return KnotVector(self); })
      .def(
          "__deepcopy__", [](const KnotVector& self, const py::dict&) { return KnotVector(self); },
          py::arg("memo"));
}

}  // namespace dnurbs::python
