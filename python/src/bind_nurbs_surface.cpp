// dnurbs.NurbsSurface (nurbs/nurbs_surface.h) with knot insertion and refinement, degree
// elevation, knot removal and closest points along either direction, on arrays of parameters.

#include <pybind11/stl.h>

#include "dnurbs/nurbs/closest_point.h"
#include "dnurbs/nurbs/degree_elevation.h"
#include "dnurbs/nurbs/knot_insertion.h"
#include "dnurbs/nurbs/knot_removal.h"
#include "dnurbs/nurbs/nurbs_surface.h"
#include "python/src/bindings.h"
#include "python/src/control_net_properties.h"
#include "python/src/numpy_arrays.h"
#include "python/src/surface_arrays.h"

namespace dnurbs::python {

namespace {

using Vector3Map = Eigen::Map<Eigen::Vector3d>;

py::dict surface_curvature(const NurbsSurface& surface, const py::object& u, const py::object& v) {
  const auto [us, vs] = broadcast_items(u, v);
  py::array_t<double> gaussian = new_result(us, {});
  py::array_t<double> mean = new_result(us, {});
  py::array_t<double> principal_max = new_result(us, {});
  py::array_t<double> principal_min = new_result(us, {});
  py::array_t<double> direction_max = new_result(us, {3});
  py::array_t<double> direction_min = new_result(us, {3});
  for (py::ssize_t i = 0; i < us.count; ++i) {
    const SurfaceCurvature curvature = surface.curvature(*us.item(i), *vs.item(i));
    gaussian.mutable_data()[i] = curvature.gaussian;
    mean.mutable_data()[i] = curvature.mean;
    principal_max.mutable_data()[i] = curvature.principal_max;
    principal_min.mutable_data()[i] = curvature.principal_min;
    Vector3Map(direction_max.mutable_data() + 3 * i) = curvature.direction_max;
    Vector3Map(direction_min.mutable_data() + 3 * i) = curvature.direction_min;
  }
  py::dict result;
  result["gaussian"] = gaussian;
  result["mean"] = mean;
  result["principal_max"] = principal_max;
  result["principal_min"] = principal_min;
  result["direction_max"] = direction_max;
  result["direction_min"] = direction_min;
  return result;
}

py::tuple surface_closest_points(const NurbsSurface& surface, const py::object& points) {
  const ItemArray queries = item_array(points, "points", 3);
  const SurfaceProjector projector(surface);
  py::array_t<double> parameters = new_result(queries, {2});
  py::array_t<double> closest = new_result(queries, {3});
  py::array_t<double> distances = new_result(queries, {});
  for (py::ssize_t i = 0; i < queries.count; ++i) {
    const SurfaceProjection projection =
        projector.closest_point(Eigen::Map<const Eigen::Vector3d>(queries.item(i)));
    Eigen::Map<Eigen::Vector2d>(parameters.mutable_data() + 2 * i) = projection.parameter;
    Vector3Map(closest.mutable_data() + 3 * i) = projection.point;
    distances.mutable_data()[i] = projection.distance;
  }
  return py::make_tuple(parameters, closest, distances);
}

void bind_surface_knot_operations(py::class_<NurbsSurface>& surface) {
  surface
      .def(
          "insert_knot",
          [](const NurbsSurface& self, SurfaceDirection direction, double u, int times) {
            return insert_knot(self, direction, u, times);
          },
          py::arg("direction"), py::arg("u"), py::arg("times") = 1,
          "The same surface with the knot u inserted `times` times along `direction` "
          "(Direction.U or Direction.V; Piegl & Tiller A5.1 on every row of the net).")
      .def(
          "refine_knots",
          [](const NurbsSurface& self, SurfaceDirection direction, const py::object& knots) {
            return refine_knots(self, direction, list_from_array(knots, "knots"));
          },
          py::arg("direction"), py::arg("knots"),
          "The same surface with the non-decreasing knots (k,) inserted along `direction`.")
      .def(
          "elevate_degree",
          [](const NurbsSurface& self, SurfaceDirection direction, int increase) {
            return elevate_degree(self, direction, increase);
          },
          py::arg("direction"), py::arg("increase"),
          "The same surface with its degree along `direction` raised by `increase`.")
      .def(
          "remove_knot",
          [](const NurbsSurface& self, SurfaceDirection direction, double u, int times,
             double tolerance) {
            SurfaceKnotRemoval removal = remove_knot(self, direction, u, times, tolerance);
            return py::make_tuple(std::move(removal.surface), removal.removed_count,
                                  removal.succeeded);
          },
          py::arg("direction"), py::arg("u"), py::arg("times"), py::arg("tolerance"),
          "Removes the interior knot u along `direction` up to `times` times, each removal "
          "only if the surface moves by at most `tolerance`. Returns (surface, removed_count, "
          "succeeded).");
}

}  // namespace

void bind_nurbs_surface(py::module_& module) {
  py::class_<NurbsSurface> surface(
      module, "NurbsSurface",
      "A tensor-product NURBS surface S(u, v) with (m + 1) x (n + 1) control points "
      "(Terzopoulos, Deformable Models, eq. 1.27), open or periodic in either direction. "
      "Control point (i, j) is row i * (n + 1) + j of control_points (u index outer). A value: "
      "operations return new surfaces.");
  surface
      .def(py::init([](const KnotVector& knots_u, const KnotVector& knots_v,
                       const py::object& control_points, const py::object& weights) {
             const long count =
                 static_cast<long>(knots_u.control_point_count()) * knots_v.control_point_count();
             return NurbsSurface(knots_u, knots_v,
                                 matrix_from_array(control_points, "control_points", count, 3),
                                 optional_weights(weights, count));
           }),
           py::arg("knots_u"), py::arg("knots_v"), py::arg("control_points"),
           py::arg("weights") = py::none(),
           "knots_u, knots_v: KnotVector; control_points: array_like ((m + 1) (n + 1), 3), u "
           "index outer (a (m + 1, n + 1, 3) net reshaped in C order); weights: ((m + 1) (n + "
           "1),) all > 0, or None. Raises dnurbs.Error naming the bad value.")
      .def_property_readonly("degree_u", &NurbsSurface::degree_u, "Degree p along u.")
      .def_property_readonly("degree_v", &NurbsSurface::degree_v, "Degree q along v.")
      .def_property_readonly("knots_u", &NurbsSurface::knots_u, "The KnotVector along u.")
      .def_property_readonly("knots_v", &NurbsSurface::knots_v, "The KnotVector along v.")
      .def_property_readonly("control_point_count_u", &NurbsSurface::control_point_count_u,
                             "Distinct control points along u (m + 1).")
      .def_property_readonly("control_point_count_v", &NurbsSurface::control_point_count_v,
                             "Distinct control points along v (n + 1).");
  add_control_net_properties(surface, "(m + 1) (n + 1)");
  surface
      .def(
          "__call__",
          [](const NurbsSurface& self, const py::object& u, const py::object& v) {
            return vector_per_parameter(u, v, [&](double s, double t) { return self.point(s, t); });
          },
          py::arg("u"), py::arg("v"),
          "Points S(u, v): u, v array_like broadcast to one shape (...) -> array (..., 3).")
      .def("derivatives", &surface_derivative_array<NurbsSurface>, py::arg("u"), py::arg("v"),
           py::arg("order"),
           "Partial derivatives d^(k+l) S / du^k dv^l (Piegl & Tiller A4.4): u, v (...) -> "
           "array (..., order + 1, order + 1, 3) with [..., k, l, :] for k + l <= order (zero "
           "for k + l > order).")
      .def(
          "unit_normal",
          [](const NurbsSurface& self, const py::object& u, const py::object& v) {
            return vector_per_parameter(u, v,
                                        [&](double s, double t) { return self.unit_normal(s, t); });
          },
          py::arg("u"), py::arg("v"), "Unit normals (Su x Sv)/|Su x Sv|: (...) -> (..., 3).")
      .def("curvature", &surface_curvature, py::arg("u"), py::arg("v"),
           "Curvatures: a dict of arrays gaussian, mean, principal_max, principal_min (shape "
           "(...)) and direction_max, direction_min (shape (..., 3)).")
      .def("closest_point", &surface_closest_points, py::arg("points"),
           "Globally nearest surface points to `points` (3,) or (..., 3). Returns (parameters "
           "(..., 2), points (..., 3), distances (...)).")
      .def(
          "invert_point",
          [](const NurbsSurface& self, const py::object& point, double tolerance) {
            const Eigen::Vector2d uv =
                invert_point(self, matrix_from_array(point, "point", 1, 3, true).row(0), tolerance);
            return py::make_tuple(uv.x(), uv.y());
          },
          py::arg("point"), py::arg("tolerance"),
          "The parameters (u, v) of a point (3,) on the surface; raises dnurbs.Error if it is "
          "farther than `tolerance` from the surface.")
      .def("__repr__", [](const NurbsSurface& self) {
        return "NurbsSurface(degrees=(" + std::to_string(self.degree_u()) + ", " +
               std::to_string(self.degree_v()) +
               "), control_points=" + std::to_string(self.control_point_count_u()) + "x" +
               std::to_string(self.control_point_count_v()) +
               (self.is_rational() ? ", rational" : "") + ")";
      });
  bind_surface_knot_operations(surface);
}

}  // namespace dnurbs::python
