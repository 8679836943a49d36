// The dnurbs Python module (compiled part `dnurbs._dnurbs`; the package python/dnurbs re-exports
// it). docs/python.md describes it.

#include <pybind11/pybind11.h>

#include "python/src/bindings.h"

PYBIND11_MODULE(_dnurbs, module) {
  using namespace dnurbs::python;
  module.doc() =
      "dnurbs: physics-based geometric design (D-NURBS, deformable superquadrics, grid "
      "surfaces).\n\nArrays cross as NumPy float64 arrays; bad input raises dnurbs.Error (a "
      "ValueError) with the library's message.";
  bind_errors(module);
  bind_knot_vector(module);
  bind_nurbs_curve(module);
  bind_nurbs_surface(module);
  bind_primitive_shapes(module);
  bind_shape_generators(module);
  bind_triangle_mesh(module);
  bind_model(module);
  bind_superquadric(module);
  bind_grid_models(module);
  bind_generalized_spline(module);
  bind_swung(module);
  bind_triangular(module);
  bind_deformation_field(module);
  bind_system(module);
  bind_integrator(module);
  bind_design(module);
  bind_scene(module);
  bind_scene_simulation(module);
  bind_shape_files(module);
  bind_constraints(module);
  bind_vision(module);
}
