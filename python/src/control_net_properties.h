#pragma once
// The control net of a NURBS curve or surface as Python properties: `control_points` and
// `weights` read as read-only views of the shape's storage (no copy) and assigned through the
// library's setters (which check counts, finiteness and positive weights).

#include <string>

#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

/// Adds the properties control_points ((n, 3)), weights ((n,)), is_rational and
/// control_point_count to the binding of `Shape` (NurbsCurve or NurbsSurface).
template <typename Shape>
void add_control_net_properties(py::class_<Shape>& shape_class, const std::string& count_text) {
  shape_class
      .def_property(
          "control_points",
          [](const py::object& self) {
            const auto& points = self.cast<const Shape&>().control_points();
            return read_only_view(points.data(), points.rows(), 3, self);
          },
          [](Shape& self, const py::object& points) {
            self.set_control_points(
                matrix_from_array(points, "control_points", self.control_point_count(), 3));
          },
          ("The control points, shape (" + count_text +
           ", 3): a read-only view of the shape's storage (no copy; Fortran order). Assign a "
           "new array of the same shape to move them (checked: finite values).")
              .c_str())
      .def_property(
          "weights",
          [](const py::object& self) {
            const auto& weights = self.cast<const Shape&>().weights();
            return read_only_view(weights.data(), weights.size(), self);
          },
          [](Shape& self, const py::object& weights) {
            self.set_weights(vector_from_array(weights, "weights", self.control_point_count()));
          },
          ("The weights, shape (" + count_text +
           ",): a read-only view (no copy). Assign a new array of the same shape (checked: "
           "finite, > 0).")
              .c_str())
      .def_property_readonly("is_rational", &Shape::is_rational,
                             "True if some weight differs from the others.")
      .def_property_readonly("control_point_count", &Shape::control_point_count,
                             "Number of distinct control points.")
      .def("__copy__", [](const Shape& self) { return Shape(self); })
      .def(
          "__deepcopy__", [](const Shape& self, const py::dict&) { return Shape(self); },
          py::arg("memo"));
}

/// The optional weights argument of a shape constructor: empty (non-rational) for None.
inline Eigen::VectorXd optional_weights(const py::object& weights, long count) {
  if (weights.is_none()) {
    return {};
  }
  return vector_from_array(weights, "weights", count);
}

}  // namespace dnurbs::python
