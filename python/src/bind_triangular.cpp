// Triangular NURBS: dnurbs.Triangulation (nurbs/triangulation.h, nurbs/triangulation_shapes.h),
// dnurbs.TriangularBSplineBasis (nurbs/triangular_bspline_basis.h with the standard knot clouds of
// nurbs/triangular_knot_clouds.h), dnurbs.TriangularNurbsSurface
// (nurbs/triangular_nurbs_surface.h) and the model dnurbs.TriangularDNurbsSurface
// (dynamics/triangular/triangular_dnurbs_surface.h; Qin & Terzopoulos, Triangular NURBS and their
// dynamic generalizations, CAGD 14(4) 1997).

#include <memory>

#include <pybind11/stl.h>

#include "dnurbs/dynamics/triangular/triangular_dnurbs_surface.h"
#include "dnurbs/nurbs/triangular_nurbs_surface.h"
#include "dnurbs/nurbs/triangulation_shapes.h"
#include "python/src/bindings.h"
#include "python/src/control_net_properties.h"
#include "python/src/model_arguments.h"
#include "python/src/numpy_arrays.h"
#include "python/src/rest_shape_binding.h"

namespace dnurbs::python {

namespace {

using BasisPointer = std::shared_ptr<TriangularBSplineBasis>;

Eigen::Vector2d point2(const py::object& value, const std::string& name) {
  return matrix_from_array(value, name, 1, 2, true).row(0).transpose();
}

void bind_triangulation(py::module_& module) {
  py::class_<Triangulation>(
      module, "Triangulation",
      "A conforming triangulation of a planar parameter domain (possibly non-convex, with "
      "holes): vertices (V, 2), triangles (T, 3) counter-clockwise vertex indices.")
      .def(py::init([](const py::object& vertices, const py::object& triangles) {
             return Triangulation(matrix_from_array(vertices, "vertices", -1, 2),
                                  index_matrix_from_array(triangles, "triangles", 3));
           }),
           py::arg("vertices"), py::arg("triangles"),
           "vertices (V, 2), triangles (T, 3) integer indices; raises dnurbs.Error naming the "
           "triangle, edge or vertex that is not valid (orientation, conformity, T-junctions).")
      .def_property_readonly(
          "vertices",
          [](const py::object& self) {
            const auto& v = self.cast<const Triangulation&>().vertices();
            return read_only_view(v.data(), v.rows(), 2, self);
          },
          "Vertices (V, 2): a read-only view.")
      .def_property_readonly(
          "triangles",
          [](const py::object& self) {
            const auto& t = self.cast<const Triangulation&>().triangles();
            return read_only_view(t.data(), t.rows(), 3, self);
          },
          "Triangles (T, 3) int32: a read-only view.")
      .def_property_readonly("domain_area", &Triangulation::domain_area, "Area of the domain.")
      .def("area", &Triangulation::area, py::arg("t"), "Area of triangle t.")
      .def(
          "boundary_edges",
          [](const Triangulation& self) {
            return array_from_index_matrix(Eigen::MatrixXi(self.boundary_edges()));
          },
          "Boundary edges (a, b) with the domain on their left, (#edges, 2).");
  module.def(
      "rectangle_triangulation",
      [](const py::object& lo, const py::object& hi, int cells_u, int cells_v, bool alternating) {
        return rectangle_triangulation(
            point2(lo, "lo"), point2(hi, "hi"), cells_u, cells_v,
            alternating ? DiagonalPattern::kAlternating : DiagonalPattern::kUniform);
      },
      py::arg("lo"), py::arg("hi"), py::arg("cells_u"), py::arg("cells_v"),
      py::arg("alternating") = true,
      "The rectangle [lo, hi] ((2,) each) split into cells_u x cells_v cells of two triangles "
      "(diagonals alternating like a checkerboard, or all alike).");
  module.def("l_shape_triangulation", &l_shape_triangulation, py::arg("cells"),
             "The L-shaped domain [0, 2]^2 minus (1, 2] x (1, 2], `cells` per unit length.");
  module.def("square_with_hole_triangulation", &square_with_hole_triangulation, py::arg("cells"),
             "The square [0, 3]^2 with the hole (1, 2)^2, `cells` per unit length.");
  module.def("refine_triangulation", &refine_triangulation, py::arg("triangulation"),
             "Every triangle split into four at its edge midpoints.");
}

// Points u of shape (..., 2) -> (..., tail) with one evaluation per point.
template <typename Function>
py::array_t<double> per_domain_point(const py::object& u, const std::vector<py::ssize_t>& tail,
                                     const Function& function) {
  const ItemArray points = item_array(u, "u", 2);
  py::array_t<double> result = new_result(points, tail);
  py::ssize_t size = 1;
  for (const py::ssize_t extent : tail) {
    size *= extent;
  }
  for (py::ssize_t i = 0; i < points.count; ++i) {
    function(Eigen::Vector2d(points.item(i)[0], points.item(i)[1]),
             result.mutable_data() + i * size);
  }
  return result;
}

void bind_triangular_surface(py::module_& module) {
  py::class_<TriangularBSplineBasis, BasisPointer>(
      module, "TriangularBSplineBasis",
      "The triangular B-spline basis of degree n over a Triangulation with the standard knot "
      "clouds (Dahmen, Micchelli & Seidel 1992; Qin & Terzopoulos, CAGD 14(4) 1997): "
      "(n + 1)(n + 2)/2 functions per triangle.")
      .def(py::init([](const Triangulation& triangulation, int degree, double cloud_radius) {
             KnotCloudSettings settings;
             settings.radius = cloud_radius;
             TriangularKnotClouds clouds = standard_knot_clouds(triangulation, degree, settings);
             return std::make_shared<TriangularBSplineBasis>(triangulation, std::move(clouds));
           }),
           py::arg("triangulation"), py::arg("degree"), py::arg("cloud_radius") = 0.3,
           "Degree n >= 1; cloud_radius: the knot clouds' radius as a fraction (0, 0.5) of each "
           "vertex's local size.")
      .def_property_readonly("degree", &TriangularBSplineBasis::degree, "The degree n.")
      .def_property_readonly("function_count", &TriangularBSplineBasis::function_count,
                             "Number of B-splines (control points of a surface).")
      .def_property_readonly("triangulation", &TriangularBSplineBasis::triangulation,
                             "The Triangulation.")
      .def(
          "evaluate",
          [](const TriangularBSplineBasis& self, const py::object& u, int order) {
            TriangularBasisValues values;
            self.evaluate(point2(u, "u"), order, values);
            Eigen::MatrixXd table = values.value.leftCols(values.count);
            const int filled = (order + 1) * (order + 2) / 2;
            table.bottomRows(6 - filled).setZero();
            return py::make_tuple(values.function, array_from_matrix(table));
          },
          py::arg("u"), py::arg("order") = 0,
          "The B-splines that may be non-zero at the domain point u (2,) with derivatives up to "
          "`order` (0..2): (functions, values) with functions a list of B-spline indices and "
          "values (6, #functions): rows N, N_u, N_v, N_uu, N_uv, N_vv (zero beyond `order`).")
      .def(
          "domain_points",
          [](const TriangularBSplineBasis& self) {
            return array_from_matrix(self.domain_points());
          },
          "The coefficients that reproduce u -> u, (function_count, 2).");
  py::class_<TriangularNurbsSurface> surface(
      module, "TriangularNurbsSurface",
      "A triangular NURBS surface x(u) = sum w_a P_a N_a(u) / sum w_a N_a(u) over a "
      "TriangularBSplineBasis. A value.");
  surface
      .def(py::init([](const BasisPointer& basis, const py::object& control_points,
                       const py::object& weights) {
             const long count = basis ? basis->function_count() : 0;
             return TriangularNurbsSurface(
                 basis, matrix_from_array(control_points, "control_points", count, 3),
                 optional_weights(weights, count));
           }),
           py::arg("basis"), py::arg("control_points"), py::arg("weights") = py::none(),
           "control_points (function_count, 3); weights (function_count,) all > 0, or None.")
      .def_property_readonly(
          "basis",
          [](const TriangularNurbsSurface& self) {
            return std::const_pointer_cast<TriangularBSplineBasis>(self.shared_basis());
          },
          "The TriangularBSplineBasis.")
      .def_property_readonly(
          "control_points",
          [](const py::object& self) {
            const auto& p = self.cast<const TriangularNurbsSurface&>().control_points();
            return read_only_view(p.data(), p.rows(), 3, self);
          },
          "Control points (function_count, 3): a read-only view.")
      .def_property_readonly(
          "weights",
          [](const py::object& self) {
            const auto& w = self.cast<const TriangularNurbsSurface&>().weights();
            return read_only_view(w.data(), w.size(), self);
          },
          "Weights (function_count,) (empty when all are 1): a read-only view.")
      .def_property_readonly("is_rational", &TriangularNurbsSurface::is_rational,
                             "True if some weight differs from the others.")
      .def(
          "__call__",
          [](const TriangularNurbsSurface& self, const py::object& u) {
            return per_domain_point(u, {3}, [&](const Eigen::Vector2d& p, double* out) {
              Eigen::Vector3d::Map(out) = self.point(p);
            });
          },
          py::arg("u"), "Points x(u): u (..., 2) in the domain -> (..., 3).")
      .def(
          "derivatives",
          [](const TriangularNurbsSurface& self, const py::object& u, int order) {
            if (order < 0 || order > 2) {
              throw make_error("derivative order ", order, " is outside 0..2");
            }
            return per_domain_point(u, {6, 3}, [&](const Eigen::Vector2d& p, double* out) {
              const auto d = self.derivatives(p, order);
              for (int k = 0; k < 6; ++k) {
                Eigen::Map<Eigen::Vector3d>(out + 3 * k) = d[static_cast<size_t>(k)];
              }
            });
          },
          py::arg("u"), py::arg("order"),
          "x, x_u, x_v, x_uu, x_uv, x_vv at u (..., 2) -> (..., 6, 3), entries beyond `order` "
          "(0..2) zero.")
      .def(
          "unit_normal",
          [](const TriangularNurbsSurface& self, const py::object& u) {
            return per_domain_point(u, {3}, [&](const Eigen::Vector2d& p, double* out) {
              Eigen::Vector3d::Map(out) = self.unit_normal(p);
            });
          },
          py::arg("u"), "Unit normals (x_u x x_v)/|x_u x x_v|: (..., 2) -> (..., 3).");
  module.def(
      "flat_triangular_surface",
      [](const BasisPointer& basis) { return flat_triangular_surface(basis); }, py::arg("basis"),
      "The flat surface x(u, v) = (u, v, 0) over the basis's domain.");
}

void bind_triangular_model(py::module_& module) {
  using T = TriangularDNurbsSurface;
  py::class_<T, Model> model_class(
      module, "TriangularDNurbsSurface",
      "A triangular D-NURBS surface (Qin & Terzopoulos, CAGD 14(4) 1997): q = [P_0, P_1, ...] "
      "or [P_0, w_0, ...] with free weights, the material of DNurbsSurface per unit parametric "
      "area. Material points are domain points (u, v).");
  bind_rest_shape(model_class);
  model_class
      .def(py::init([](const TriangularNurbsSurface& surface, double mass_density,
                       double damping_density, double a10, double a01, double b20, double b11,
                       double b02, bool free_weights, int quadrature_degree,
                       int quadrature_subdivisions, bool initial_shape_at_rest) {
             TriangularDNurbsSettings settings;
             settings.weight_mode = free_weights ? WeightMode::kFree : WeightMode::kFixed;
             settings.quadrature_degree = quadrature_degree;
             settings.quadrature_subdivisions = quadrature_subdivisions;
             settings.initial_shape_at_rest = initial_shape_at_rest;
             return T(surface, {mass_density, damping_density, a10, a01, b20, b11, b02}, settings);
           }),
           py::arg("surface"), py::arg("mass_density") = 1.0, py::arg("damping_density") = 0.0,
           py::arg("a10") = 0.0, py::arg("a01") = 0.0, py::arg("b20") = 0.0, py::arg("b11") = 0.0,
           py::arg("b02") = 0.0, py::arg("free_weights") = false, py::arg("quadrature_degree") = 0,
           py::arg("quadrature_subdivisions") = 0, py::arg("initial_shape_at_rest") = false,
           "surface: a TriangularNurbsSurface; densities and stiffnesses as DNurbsSurface; "
           "quadrature_degree of the Dunavant rule (0: 2n, exact for polynomial surfaces); "
           "quadrature_subdivisions 0: exact polynomial cells; initial_shape_at_rest: the energy "
           "of the change from the surface as given (set_rest_shape).")
      .def(
          "surface",
          [](const T& self, const py::object& q) { return self.surface(model_state(self, q)); },
          py::arg("q") = py::none(), "The TriangularNurbsSurface at q.")
      .def_property_readonly("initial_surface", &T::initial_surface,
                             "The TriangularNurbsSurface the model was built from.")
      .def_property_readonly("parametric_measure", &T::parametric_measure,
                             "Area of the parametric domain.");
}

}  // namespace

void bind_triangular(py::module_& module) {
  bind_triangulation(module);
  bind_triangular_surface(module);
  bind_triangular_model(module);
}

}  // namespace dnurbs::python
