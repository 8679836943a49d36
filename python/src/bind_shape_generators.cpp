// The shape generators of nurbs/shape_generators.h: rods and sheets at the Greville abscissae
// (at rest under the D-NURBS energy with a clamped border), box, cylinder, cone, revolution,
// extrusion, loft (Piegl & Tiller, The NURBS Book, ch. 8-10) and span splitting.

#include <optional>
#include <vector>

#include <pybind11/stl.h>

#include "dnurbs/nurbs/shape_generators.h"
#include "python/src/bindings.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

namespace {

Eigen::Vector3d point_from(const py::object& value, const std::string& name) {
  return matrix_from_array(value, name, 1, 3, true).row(0).transpose();
}

Eigen::Vector2d pair_from(const py::object& value, const std::string& name) {
  return vector_from_array(value, name, 2);
}

}  // namespace

void bind_shape_generators(py::module_& module) {
  const auto origin = py::make_tuple(0.0, 0.0, 0.0);
  module.def(
      "greville_abscissae", &greville_abscissae, py::arg("knots"),
      "The Greville abscissae (t_{i+1} + ... + t_{i+p}) / p of an open KnotVector (n values): "
      "control values there reproduce u.");
  module.def(
      "greville_line",
      [](const py::object& start, const py::object& end, int control_points, int degree,
         std::optional<double> domain) {
        return greville_line(point_from(start, "start"), point_from(end, "end"), control_points,
                             degree, domain);
      },
      py::arg("start"), py::arg("end"), py::arg("control_points") = 4, py::arg("degree") = 3,
      py::arg("domain") = py::none(),
      "A straight rod from `start` (3,) to `end` (3,), control points at the Greville abscissae "
      "over [0, domain] (default: its length, so u is the distance): at rest.");
  module.def(
      "greville_plane",
      [](const py::object& size, const py::object& control_points, const py::object& degree,
         const py::object& origin_point, const py::object& domain) {
        const Eigen::Vector2d counts = pair_from(control_points, "control_points");
        const Eigen::Vector2d degrees = pair_from(degree, "degree");
        std::optional<Eigen::Vector2d> extent;
        if (!domain.is_none()) {
          extent = pair_from(domain, "domain");
        }
        return greville_plane(pair_from(size, "size"), counts.cast<int>(), degrees.cast<int>(),
                              point_from(origin_point, "origin"), extent);
      },
      py::arg("size") = py::make_tuple(1.0, 1.0), py::arg("control_points") = py::make_tuple(4, 4),
      py::arg("degree") = py::make_tuple(3, 3), py::arg("origin") = origin,
      py::arg("domain") = py::none(),
      "A flat sheet origin + (u size_x / domain_x, v size_y / domain_y, 0), control points "
      "(n_u, n_v) at the Greville abscissae: at rest with its border clamped.");
  module.def(
      "box", [](const py::object& size) { return box(point_from(size, "size")); },
      py::arg("size") = py::make_tuple(1.0, 1.0, 1.0),
      "The closed surface of a box of edge lengths `size` (3,) standing on z = 0 (bilinear, 4 x "
      "5 control points).");
  module.def("cylinder", &cylinder, py::arg("radius") = 1.0, py::arg("height") = 1.0,
             py::arg("profile_control_points") = 4,
             "The exact open cylinder about the z axis from z = 0 up.");
  module.def("cone", &cone, py::arg("radius") = 1.0, py::arg("height") = 1.0,
             py::arg("profile_control_points") = 4,
             "The exact cone with its base circle on z = 0 and apex (0, 0, height).");
  module.def("revolve", &revolve, py::arg("profile"), py::arg("angle"),
             "The NurbsCurve `profile` revolved about the z axis by `angle` radians (0 < angle "
             "<= 2 pi), rational quadratic arcs of at most a quarter turn.");
  module.def(
      "extrude",
      [](const NurbsCurve& curve, const py::object& direction) {
        return extrude(curve, point_from(direction, "direction"));
      },
      py::arg("curve"), py::arg("direction"),
      "The surface C(u) + v d / |d|, v in [0, |d|], of a NurbsCurve swept along `direction` (3,).");
  module.def(
      "loft",
      [](const std::vector<NurbsCurve>& sections, int degree) {
        std::vector<double> parameters;
        NurbsSurface surface = loft(sections, degree, &parameters);
        return py::make_tuple(std::move(surface), parameters);
      },
      py::arg("sections"), py::arg("degree") = 3,
      "The skinned surface through the section curves, and the v parameter of each section: "
      "(surface, [v_0, ..., v_k]), S(u, v_k) being section k.");
  module.def(
      "split_spans",
      [](const NurbsSurface& surface, const py::object& parts) {
        return split_spans(surface, pair_from(parts, "parts").cast<int>());
      },
      py::arg("surface"), py::arg("parts"),
      "The same surface with every knot span split into (parts_u, parts_v) equal spans.");
  module.def("split_spans", py::overload_cast<const NurbsCurve&, int>(&split_spans),
             py::arg("curve"), py::arg("parts"),
             "The same curve with every knot span split into `parts` equal spans.");
}

}  // namespace dnurbs::python
