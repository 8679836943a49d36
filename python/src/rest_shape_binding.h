#pragma once
// The rest shape and plastic flow of the rational control-net models as Python methods.

#include <optional>

#include "dnurbs/dynamics/core/plastic_flow.h"
#include "python/src/bindings.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

/// set_rest_shape, has_rest_shape, rest_coordinates and set_plastic_flow of a rational
/// control-net model (rational_control_net_model.h) on its class: DNurbsCurve, DNurbsSurface,
/// TriangularDNurbsSurface; and of DNurbsSwungSurface, whose control points are its curves'.
template <typename DNurbsClass>
void bind_rest_shape(py::class_<DNurbsClass, Model>& model_class) {
  model_class
      .def(
          "set_rest_shape",
          [](DNurbsClass& self, const py::array_t<double>& q_rest) {
            self.set_rest_shape(vector_from_array(q_rest, "q_rest", self.coordinate_count()));
          },
          py::arg("q_rest"),
          "Measures the energy from the shape at q_rest (n,): E = 1/2 integral sum_alpha k_alpha "
          "|x^alpha(q) - x^alpha(q_rest)|^2, so q_rest is at rest. Copies in a System are "
          "unaffected.")
      .def_property_readonly("has_rest_shape", &DNurbsClass::has_rest_shape,
                             "True once a rest shape is set.")
      .def_property_readonly(
          "rest_coordinates",
          [](const DNurbsClass& self) { return array_from_vector(self.rest_coordinates()); },
          "The rest shape's coordinates (n,), empty without a rest shape.")
      .def(
          "set_plastic_flow",
          [](DNurbsClass& self, const py::object& yield, double rate) {
            if (yield.is_none()) {
              self.set_plastic_flow(std::nullopt);
            } else {
              self.set_plastic_flow(PlasticFlow{yield.cast<double>(), rate});
            }
          },
          py::arg("yield_distance"), py::arg("rate") = 1.0,
          "Makes the rest shape yield after every step (dynamics/core/plastic_flow.h): a control "
          "point's rest position flows towards its position beyond yield_distance, at rate; "
          "None stops the flow. Sets the rest shape to the initial one when there is none.");
}

}  // namespace dnurbs::python
