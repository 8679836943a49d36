// The exact rational shapes of nurbs/primitive_shapes.h (Piegl & Tiller, The NURBS Book, ch. 7-8).

#include "dnurbs/nurbs/primitive_shapes.h"
#include "python/src/bindings.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

namespace {

Eigen::Vector3d centre_from(const py::object& centre) {
  return matrix_from_array(centre, "centre", 1, 3, true).row(0).transpose();
}

}  // namespace

void bind_primitive_shapes(py::module_& module) {
  const auto origin = py::make_tuple(0.0, 0.0, 0.0);
  module.def(
      "full_circle",
      [](double radius, const py::object& centre) {
        return full_circle(radius, centre_from(centre));
      },
      py::arg("radius"), py::arg("centre") = origin,
      "The rational quadratic full circle in the xy plane about `centre` (3,): 9 control "
      "points, weights 1 and sqrt(2)/2, knots {0,0,0,1/4,1/4,1/2,1/2,3/4,3/4,1,1,1}.");
  module.def(
      "periodic_circle",
      [](double radius, const py::object& centre) {
        return periodic_circle(radius, centre_from(centre));
      },
      py::arg("radius"), py::arg("centre") = origin,
      "The same circle as a periodic curve without a seam: 8 distinct control points.");
  module.def("half_circle_xz", &half_circle_xz, py::arg("radius"),
             "The rational quadratic half circle in the xz plane from (0, 0, -r) through "
             "(r, 0, 0) to (0, 0, r).");
  module.def("surface_of_revolution", &surface_of_revolution, py::arg("profile"),
             "The surface sweeping the NurbsCurve `profile` (u) once around the z axis (v).");
  module.def("sphere", &sphere, py::arg("radius"),
             "The rational sphere of the given radius about the origin.");
  module.def("torus", &torus, py::arg("major_radius"), py::arg("minor_radius"),
             "A torus about the z axis (open knot vectors, seams at u and v ends).");
  module.def(
      "periodic_torus",
      [](double major_radius, double minor_radius, const py::object& centre) {
        return periodic_torus(major_radius, minor_radius, centre_from(centre));
      },
      py::arg("major_radius"), py::arg("minor_radius"), py::arg("centre") = origin,
      "The torus periodic in both directions (8 x 8 distinct control points) about `centre`.");
}

}  // namespace dnurbs::python
