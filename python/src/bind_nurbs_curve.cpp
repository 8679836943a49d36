// dnurbs.NurbsCurve (nurbs/nurbs_curve.h) with knot insertion and refinement
// (nurbs/knot_insertion.h), degree elevation (nurbs/degree_elevation.h), knot removal
// (nurbs/knot_removal.h) and closest points (nurbs/closest_point.h), on arrays of parameters.

#include <pybind11/stl.h>

#include "dnurbs/nurbs/closest_point.h"
#include "dnurbs/nurbs/degree_elevation.h"
#include "dnurbs/nurbs/knot_insertion.h"
#include "dnurbs/nurbs/knot_removal.h"
#include "dnurbs/nurbs/nurbs_curve.h"
#include "python/src/bindings.h"
#include "python/src/control_net_properties.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

namespace {

using Vector3Map = Eigen::Map<Eigen::Vector3d>;

// One 3-vector per parameter: shape u.shape + (3,).
template <typename Function>
py::array_t<double> vector_per_parameter(const py::object& u, const Function& function) {
  const ItemArray parameters = item_array(u, "u", 0);
  py::array_t<double> result = new_result(parameters, {3});
  double* out = result.mutable_data();
  for (py::ssize_t i = 0; i < parameters.count; ++i) {
    Vector3Map(out + 3 * i) = function(*parameters.item(i));
  }
  return result;
}

py::array_t<double> curve_derivatives(const NurbsCurve& curve, const py::object& u, int order) {
  const ItemArray parameters = item_array(u, "u", 0);
  if (order < 0 || order > kMaxDerivativeOrder) {
    throw make_error("derivative order ", order, " is outside 0..", kMaxDerivativeOrder);
  }
  py::array_t<double> result = new_result(parameters, {order + 1, 3});
  double* out = result.mutable_data();
  CurveDerivatives derivatives;
  for (py::ssize_t i = 0; i < parameters.count; ++i) {
    curve.derivatives(*parameters.item(i), order, derivatives);
    // CurveDerivatives is row-major (order + 1) by 3, as the result's last two axes.
    std::copy(derivatives.data(), derivatives.data() + 3 * (order + 1), out + 3 * (order + 1) * i);
  }
  return result;
}

py::array_t<double> curve_curvature(const NurbsCurve& curve, const py::object& u) {
  const ItemArray parameters = item_array(u, "u", 0);
  py::array_t<double> result = new_result(parameters, {});
  double* out = result.mutable_data();
  for (py::ssize_t i = 0; i < parameters.count; ++i) {
    out[i] = curve.curvature(*parameters.item(i));
  }
  return result;
}

py::tuple curve_closest_points(const NurbsCurve& curve, const py::object& points) {
  const ItemArray queries = item_array(points, "points", 3);
  const CurveProjector projector(curve);
  py::array_t<double> parameters = new_result(queries, {});
  py::array_t<double> closest = new_result(queries, {3});
  py::array_t<double> distances = new_result(queries, {});
  for (py::ssize_t i = 0; i < queries.count; ++i) {
    const CurveProjection projection =
        projector.closest_point(Eigen::Map<const Eigen::Vector3d>(queries.item(i)));
    parameters.mutable_data()[i] = projection.parameter;
    Vector3Map(closest.mutable_data() + 3 * i) = projection.point;
    distances.mutable_data()[i] = projection.distance;
  }
  return py::make_tuple(parameters, closest, distances);
}

}  // namespace

void bind_nurbs_curve(py::module_& module) {
  py::class_<NurbsCurve> curve(
      module, "NurbsCurve",
      "A NURBS curve C(u) = sum_i N_i(u) w_i P_i / sum_i N_i(u) w_i in 3-D (Terzopoulos, "
      "Deformable Models: Classic, Topology-Adaptive and Generalized Formulations, eq. 1.21), "
      "open or periodic. A value: operations return new curves.");
  curve
      .def(py::init([](const KnotVector& knots, const py::object& control_points,
                       const py::object& weights) {
             const long count = knots.control_point_count();
             return NurbsCurve(knots, matrix_from_array(control_points, "control_points", count, 3),
                               optional_weights(weights, count));
           }),
           py::arg("knots"), py::arg("control_points"), py::arg("weights") = py::none(),
           "knots: KnotVector; control_points: array_like (n, 3) with n = "
           "knots.control_point_count (any real dtype, any memory order; copied); weights: "
           "(n,) all > 0, or None for a non-rational curve. Raises dnurbs.Error (ValueError) "
           "naming the bad value, TypeError for non-real arrays.")
      .def_property_readonly("degree", &NurbsCurve::degree, "The degree p.")
      .def_property_readonly("knots", &NurbsCurve::knots, "The KnotVector.")
      .def_property_readonly("is_periodic", &NurbsCurve::is_periodic, "True for closed curves.");
  add_control_net_properties(curve, "n");
  curve
      .def(
          "__call__",
          [](const NurbsCurve& self, const py::object& u) {
            return vector_per_parameter(u, [&](double t) { return self.point(t); });
          },
          py::arg("u"),
          "Points C(u): u array_like of any shape (...) -> array (..., 3). Raises dnurbs.Error "
          "for a parameter outside the domain of an open curve or not finite.")
      .def("derivatives", &curve_derivatives, py::arg("u"), py::arg("order"),
           "Derivatives C^(k)(u) for k = 0..order (Piegl & Tiller A4.2): u (...) -> array "
           "(..., order + 1, 3).")
      .def(
          "unit_tangent",
          [](const NurbsCurve& self, const py::object& u) {
            return vector_per_parameter(u, [&](double t) { return self.unit_tangent(t); });
          },
          py::arg("u"), "Unit tangents C'/|C'|: u (...) -> (..., 3).")
      .def(
          "principal_normal",
          [](const NurbsCurve& self, const py::object& u) {
            return vector_per_parameter(u, [&](double t) { return self.principal_normal(t); });
          },
          py::arg("u"),
          "Unit principal normals (toward the centre of curvature): u (...) -> (..., 3).")
      .def("curvature", &curve_curvature, py::arg("u"),
           "Curvature |C' x C''| / |C'|^3: u (...) -> array (...).")
      .def(
          "insert_knot",
          [](const NurbsCurve& self, double u, int times) { return insert_knot(self, u, times); },
          py::arg("u"), py::arg("times") = 1,
          "The same curve with the knot u inserted `times` times (Piegl & Tiller A5.1).")
      .def(
          "refine_knots",
          [](const NurbsCurve& self, const py::object& knots) {
            return refine_knots(self, list_from_array(knots, "knots"));
          },
          py::arg("knots"),
          "The same curve with every knot of the non-decreasing array `knots` (k,) inserted "
          "(Piegl & Tiller A5.4).")
      .def(
          "elevate_degree",
          [](const NurbsCurve& self, int increase) { return elevate_degree(self, increase); },
          py::arg("increase"), "The same curve of degree p + increase.")
      .def(
          "remove_knot",
          [](const NurbsCurve& self, double u, int times, double tolerance) {
            CurveKnotRemoval removal = remove_knot(self, u, times, tolerance);
            return py::make_tuple(std::move(removal.curve), removal.removed_count,
                                  removal.succeeded);
          },
          py::arg("u"), py::arg("times"), py::arg("tolerance"),
          "Removes the interior knot u up to `times` times, each removal only if the curve "
          "moves by at most `tolerance` (Piegl & Tiller eq. 5.30). Returns (curve, "
          "removed_count, succeeded).")
      .def("closest_point", &curve_closest_points, py::arg("points"),
           "Globally nearest curve points to `points` (3,) or (..., 3). Returns (parameters "
           "(...), points (..., 3), distances (...)).")
      .def(
          "invert_point",
          [](const NurbsCurve& self, const py::object& point, double tolerance) {
            return invert_point(self, matrix_from_array(point, "point", 1, 3, true).row(0),
                                tolerance);
          },
          py::arg("point"), py::arg("tolerance"),
          "The parameter u of a point (3,) on the curve; raises dnurbs.Error if the point is "
          "farther than `tolerance` from the curve.")
      .def("__repr__", [](const NurbsCurve& self) {
        return "NurbsCurve(degree=" + std::to_string(self.degree()) +
               ", control_point_count=" + std::to_string(self.control_point_count()) +
               (self.is_periodic() ? ", periodic" : "") + (self.is_rational() ? ", rational" : "") +
               ")";
      });
}

}  // namespace dnurbs::python
