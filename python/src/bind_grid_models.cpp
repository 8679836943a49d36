// The grid models of dynamics/grid/: dnurbs.Grid (surface/grid.h), dnurbs.TerzopoulosSurface (the
// elastic surface of Terzopoulos, Platt, Barr & Fleischer, Elastically deformable models, 1987,
// discretized after Wu & de Melo), dnurbs.PdeSurface (Romero 2005, eq. 8) and dnurbs.Snake
// (Terzopoulos, Deformable Models: Classic, Topology-Adaptive and Generalized Formulations,
// eqs. 1.2-1.8).

#include <pybind11/stl.h>

#include "dnurbs/dynamics/grid/pde_surface.h"
#include "dnurbs/dynamics/grid/snake.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "python/src/bindings.h"
#include "python/src/model_arguments.h"
#include "python/src/numpy_arrays.h"
#include "python/src/sparse_matrices.h"

namespace dnurbs::python {

namespace {

NodePositions node_positions(const py::object& value, const std::string& name, long rows) {
  return matrix_from_array(value, name, rows, 3);
}

Eigen::Matrix2d matrix2(const py::object& value, const std::string& name) {
  return matrix_from_array(value, name, 2, 2);
}

// set_plastic_flow of a grid surface whose rest shape can yield (dynamics/core/plastic_flow.h).
template <typename Surface>
void bind_plastic_flow(py::class_<Surface, Model>& surface_class) {
  surface_class.def(
      "set_plastic_flow",
      [](Surface& self, const py::object& yield, double rate) {
        if (yield.is_none()) {
          self.set_plastic_flow(std::nullopt);
        } else {
          self.set_plastic_flow(PlasticFlow{yield.cast<double>(), rate});
        }
      },
      py::arg("yield_distance"), py::arg("rate") = 1.0,
      "Makes the rest shape yield after every step (dynamics/core/plastic_flow.h): a node's "
      "rest position flows towards its position beyond yield_distance, at rate, so a push "
      "leaves a dent; None stops the flow. Copies in a System are unaffected.");
}

void bind_grid(py::module_& module) {
  py::class_<Grid>(module, "Grid",
                   "A regular grid of nu by nv nodes with spacing h: node (i, j) at the parameter "
                   "(i h, j h) has index k = i + nu j (u fastest).")
      .def(py::init<int, int, double, int>(), py::arg("nu"), py::arg("nv"), py::arg("h"),
           py::arg("minimum_nodes") = 2,
           "Raises dnurbs.Error if nu or nv is below minimum_nodes or h is not positive.")
      .def_property_readonly("nu", &Grid::nu, "Nodes along u.")
      .def_property_readonly("nv", &Grid::nv, "Nodes along v.")
      .def_property_readonly("spacing", &Grid::spacing, "The node spacing h.")
      .def_property_readonly("node_count", &Grid::node_count, "nu nv.")
      .def("index", &Grid::index, py::arg("i"), py::arg("j"), "The node index i + nu j.")
      .def(
          "parameter", [](const Grid& self, int k) { return array_from_vector(self.parameter(k)); },
          py::arg("k"), "The parameter (u, v) of node k, (2,).")
      .def_property_readonly("border_nodes", &Grid::border_nodes,
                             "Indices of the border nodes, ascending (a list).");
  module.def(
      "flat_grid_positions",
      [](const Grid& grid, const py::object& origin, const py::object& axis_u,
         const py::object& axis_v) {
        return array_from_matrix(flat_grid_positions(grid, vector3_argument(origin, "origin"),
                                                     vector3_argument(axis_u, "axis_u"),
                                                     vector3_argument(axis_v, "axis_v")));
      },
      py::arg("grid"), py::arg("origin") = py::make_tuple(0, 0, 0),
      py::arg("axis_u") = py::make_tuple(1, 0, 0), py::arg("axis_v") = py::make_tuple(0, 1, 0),
      "The flat sheet r(i, j) = origin + (i h) axis_u + (j h) axis_v, (#nodes, 3).");
}

TerzopoulosSurface make_terzopoulos(const Grid& grid, const py::object& rest, double mass_density,
                                    double damping_density, const py::object& eta,
                                    const py::object& xi, const std::string& normal, double delta) {
  TerzopoulosMaterial material;
  material.mass_density = mass_density;
  material.damping_density = damping_density;
  material.eta = matrix2(eta, "eta");
  material.xi = matrix2(xi, "xi");
  TerzopoulosSettings settings;
  settings.normal = parse_normal_approximation(normal);
  settings.delta = delta;
  return TerzopoulosSurface(grid, node_positions(rest, "rest", grid.node_count()), material,
                            settings);
}

void bind_terzopoulos(py::module_& module) {
  using T = TerzopoulosSurface;
  const auto zero2 = py::make_tuple(py::make_tuple(0, 0), py::make_tuple(0, 0));
  py::class_<T, Model> surface_class(
      module, "TerzopoulosSurface",
      "The elastic surface of Terzopoulos et al. 1987 on a Grid: q = [r_0, r_1, ...] (3 per "
      "node, Grid order); energy (h^2/4) sum eta_ij (G_ij - G0_ij)^2 + xi_ij (B_ij - B0_ij)^2 "
      "of the metric G and curvature B against the rest shape.");
  bind_plastic_flow(surface_class);
  surface_class
      .def(py::init(&make_terzopoulos), py::arg("grid"), py::arg("rest"),
           py::arg("mass_density") = 1.0, py::arg("damping_density") = 0.0, py::arg("eta") = zero2,
           py::arg("xi") = zero2, py::arg("normal") = "classic", py::arg("delta") = 0.5,
           "rest: (#nodes, 3) rest and initial shape; mass_density mu > 0 (mass mu h^2 per "
           "node); damping_density >= 0; eta, xi: (2, 2) symmetric >= 0 resistances to metric "
           "and curvature change; normal: 'classic', 'christoffel' (Wu & de Melo, eqs. "
           "22-26) with threshold delta > 0, or 'christoffel_unnormalized' (|B_ij| = 1, their "
           "figure 6).")
      .def(
          "set_node_elasticity",
          [](T& self, int node, const py::object& eta, const py::object& xi) {
            self.set_node_elasticity(node, matrix2(eta, "eta"), matrix2(xi, "xi"));
          },
          py::arg("node"), py::arg("eta"), py::arg("xi"),
          "Per-node weights eta, xi (2, 2) (checked as the material).")
      .def(
          "set_initial_positions",
          [](T& self, const py::object& positions) {
            self.set_initial_positions(
                node_positions(positions, "positions", self.grid().node_count()));
          },
          py::arg("positions"), "The initial shape (#nodes, 3) (default: the rest shape).")
      .def_property_readonly("grid", &T::grid, "The Grid.")
      .def_property_readonly(
          "rest_positions", [](const T& self) { return array_from_matrix(self.rest_positions()); },
          "The rest shape, (#nodes, 3): the initial one, moved by plastic flow.")
      .def(
          "positions",
          [](const T& self, const py::object& q) {
            return array_from_matrix(self.positions(model_state(self, q)));
          },
          py::arg("q") = py::none(), "The node positions at q, (#nodes, 3).")
      .def(
          "tensors",
          [](const T& self, const py::object& q) {
            const SurfaceTensors tensors = self.tensors(model_state(self, q));
            return py::dict(py::arg("metric") = array_from_matrix(tensors.metric),
                            py::arg("curvature") = array_from_matrix(tensors.curvature));
          },
          py::arg("q") = py::none(),
          "Metric G and curvature B at every node: a dict of (#nodes, 3) arrays with columns "
          "(11, 12, 22).")
      .def(
          "linearized_stiffness",
          [](const T& self, const py::object& q, bool dense) {
            return sparse_matrix_to_python(self.linearized_stiffness(model_state(self, q)), dense);
          },
          py::arg("q") = py::none(), py::arg("dense") = false,
          "K(q), #nodes by #nodes: the force at r with coefficients frozen at q is -(K (x) I_3) "
          "r.")
      .def(
          "approximate_normals",
          [](const T& self, const py::object& previous, const py::object& q) {
            const auto normals =
                self.approximate_normals(model_state(self, previous), model_state(self, q));
            return py::make_tuple(array_from_matrix(normals[0]), array_from_matrix(normals[1]),
                                  array_from_matrix(normals[2]));
          },
          py::arg("previous"), py::arg("q"),
          "The normal estimates of Wu & de Melo, eqs. 24-26, for the pairs 11, 12, 22 at q with "
          "the coefficients of `previous`: a tuple of three (#nodes, 3) arrays.");
}

PdeSurface make_pde(const Grid& grid, const py::object& rest, double b, double c, double d,
                    double mass_density, double damping_density, const py::object& tangents,
                    const std::vector<std::pair<py::object, double>>& regions) {
  PdeSurfaceMaterial material;
  material.b = b;
  material.c = c;
  material.d = d;
  material.mass_density = mass_density;
  material.damping_density = damping_density;
  const Eigen::VectorXd slopes = vector_from_array(tangents, "tangents", 4);
  material.tangent_u0 = slopes(0);
  material.tangent_u1 = slopes(1);
  material.tangent_v0 = slopes(2);
  material.tangent_v1 = slopes(3);
  std::vector<DeformationRegion> spec;
  spec.reserve(regions.size());
  for (const auto& [centre, radius] : regions) {
    spec.push_back({vector3_argument(centre, "region centre"), radius});
  }
  return PdeSurface(grid, node_positions(rest, "rest", grid.node_count()), material, spec);
}

void set_pde_material(PdeSurface& self, const py::object& b, const py::object& c,
                      const py::object& d, const py::object& mass_density,
                      const py::object& damping_density, const py::object& tangents) {
  PdeSurfaceMaterial material = self.material();
  for (const auto& [value, field] :
       {std::pair{&b, &material.b}, std::pair{&c, &material.c}, std::pair{&d, &material.d},
        std::pair{&mass_density, &material.mass_density},
        std::pair{&damping_density, &material.damping_density}}) {
    if (!value->is_none()) {
      *field = value->cast<double>();
    }
  }
  if (!tangents.is_none()) {
    const Eigen::VectorXd slopes = vector_from_array(tangents, "tangents", 4);
    material.tangent_u0 = slopes(0);
    material.tangent_u1 = slopes(1);
    material.tangent_v0 = slopes(2);
    material.tangent_v1 = slopes(3);
  }
  self.set_material(material);
}

void bind_pde_and_snake(py::module_& module) {
  py::class_<PdeSurface, Model> pde_class(
      module, "PdeSurface",
      "The PDE surface of Romero 2005 (eq. 8: b d4/du4 + c d4/du2dv2 + d d4/dv4) on a Grid: q "
      "holds the active nodes' positions (active_nodes lists them), the others stay at rest.");
  bind_plastic_flow(pde_class);
  pde_class
      .def(py::init(&make_pde), py::arg("grid"), py::arg("rest"), py::arg("b") = 1.0,
           py::arg("c") = 2.0, py::arg("d") = 1.0, py::arg("mass_density") = 1.0,
           py::arg("damping_density") = 0.0, py::arg("tangents") = py::make_tuple(0, 0, 0, 0),
           py::arg("regions") = std::vector<std::pair<py::object, double>>{},
           "rest (#nodes, 3); coefficients b, c, d >= 0; tangents (4,): the boundary slopes "
           "(u0, u1, v0, v1); regions: a list of (centre (3,), radius) deformation regions "
           "(empty: every interior node active).")
      .def_property_readonly("grid", &PdeSurface::grid, "The Grid.")
      .def_property_readonly(
          "rest_positions",
          [](const PdeSurface& self) { return array_from_matrix(self.rest_positions()); },
          "The initial rest shape, (#nodes, 3).")
      .def_property_readonly(
          "rest_coordinates",
          [](const PdeSurface& self) { return array_from_vector(self.rest_coordinates()); },
          "The active nodes' rest positions (3 per active node, the layout of q): the initial "
          "ones, moved by plastic flow.")
      .def_property_readonly("active_nodes", &PdeSurface::active_nodes,
                             "Grid indices of the active nodes, ascending (a list).")
      .def("active_slot", &PdeSurface::active_slot, py::arg("node"),
           "The active slot of a grid node, or -1 for a fixed node.")
      .def(
          "positions",
          [](const PdeSurface& self, const py::object& q) {
            return array_from_matrix(self.positions(model_state(self, q)));
          },
          py::arg("q") = py::none(), "Every grid node at q (fixed ones at rest), (#nodes, 3).")
      .def(
          "nodes_within",
          [](const PdeSurface& self, const py::object& centre, double radius) {
            return self.nodes_within(vector3_argument(centre, "centre"), radius);
          },
          py::arg("centre"), py::arg("radius"),
          "Active slots whose rest position is within `radius` of `centre` (a list): pass them "
          "to System.add_control_point_force.")
      .def_property_readonly(
          "tangent_force",
          [](const PdeSurface& self) { return array_from_vector(self.tangent_force()); },
          "The constant force t of the boundary tangents, (3 #active,).")
      .def("set_material", &set_pde_material, py::arg("b") = py::none(), py::arg("c") = py::none(),
           py::arg("d") = py::none(), py::arg("mass_density") = py::none(),
           py::arg("damping_density") = py::none(), py::arg("tangents") = py::none(),
           "Changes the coefficients given (None keeps one; tangents (4,): u0, u1, v0, v1), "
           "checked as the constructor does: M, D, K and tangent_force are recombined, the rest "
           "shape stays. A System holding a copy changes through "
           "System.set_material_parameters.");
  py::class_<Snake, Model>(
      module, "Snake",
      "A snake (Terzopoulos, Deformable Models, eqs. 1.2-1.8): N nodes on s in [0, 1], q = "
      "[u_0, u_1, ...] (3 per node), tension w1 and rigidity w2.")
      .def(py::init([](const py::object& initial, bool closed, double mass_density,
                       double damping_density, const py::object& tension,
                       const py::object& rigidity) {
             const Eigen::MatrixXd nodes = matrix_from_array(initial, "initial", -1, 3);
             const NodeChain chain(static_cast<int>(nodes.rows()), closed);
             SnakeMaterial material;
             material.mass_density = mass_density;
             material.damping_density = damping_density;
             const auto per_node = [&](const py::object& value, const char* name,
                                       Eigen::VectorXd& vector, double& constant) {
               if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
                 constant = value.cast<double>();
               } else {
                 vector = vector_from_array(value, name, nodes.rows());
               }
             };
             per_node(tension, "tension", material.tension, material.constant_tension);
             per_node(rigidity, "rigidity", material.rigidity, material.constant_rigidity);
             return Snake(chain, nodes, material);
           }),
           py::arg("initial"), py::arg("closed") = false, py::arg("mass_density") = 1.0,
           py::arg("damping_density") = 0.0, py::arg("tension") = 0.0, py::arg("rigidity") = 0.0,
           "initial: node positions (N, 3) (N >= 3 open, >= 4 closed); tension, rigidity: a "
           "number or per-node weights (N,) (>= 0).")
      .def_property_readonly(
          "closed", [](const Snake& self) { return self.chain().closed(); },
          "True for a closed (cyclic) snake.")
      .def(
          "positions",
          [](const Snake& self, const py::object& q) {
            return array_from_matrix(self.positions(model_state(self, q)));
          },
          py::arg("q") = py::none(), "The node positions at q, (N, 3).")
      .def(
          "scalar_stiffness",
          [](const Snake& self, bool dense) {
            return sparse_matrix_to_python(self.scalar().stiffness, dense);
          },
          py::arg("dense") = false, "The stiffness of eq. 1.8 per coordinate, N by N.");
}

}  // namespace

void bind_grid_models(py::module_& module) {
  bind_grid(module);
  bind_terzopoulos(module);
  bind_pde_and_snake(module);
}

}  // namespace dnurbs::python
