#pragma once
// The parts of the dnurbs Python module: each bind_* function adds one concept's classes and
// functions (with their docstrings) to the module `_dnurbs` (python/src/module.cpp).

#include <pybind11/pybind11.h>

namespace dnurbs {
struct Checkpoint;
}  // namespace dnurbs

namespace dnurbs::python {

namespace py = pybind11;

/// dnurbs.Error (a ValueError) and dnurbs.SimulationDiverged; the translation of dnurbs::Error.
void bind_errors(py::module_& module);
/// dnurbs.KnotVector and dnurbs.Direction.
void bind_knot_vector(py::module_& module);
/// dnurbs.NurbsCurve with knot operations and closest points.
void bind_nurbs_curve(py::module_& module);
/// dnurbs.NurbsSurface with knot operations and closest points.
void bind_nurbs_surface(py::module_& module);
/// The exact primitive shapes (circles, spheres, tori, surfaces of revolution).
void bind_primitive_shapes(py::module_& module);
/// The shape generators (Greville rods and sheets, box, cylinder, cone, revolve, extrude, loft).
void bind_shape_generators(py::module_& module);
/// dnurbs.TriangleMesh, export_meshes and import_meshes.
void bind_triangle_mesh(py::module_& module);
/// dnurbs.Scene, read_scene, parse_scene and read_checkpoint.
void bind_scene(py::module_& module);
/// dnurbs.SceneSimulation (step, run, state, samples, meshes).
void bind_scene_simulation(py::module_& module);

/// dnurbs.Model (every model type), DNurbsCurve, DNurbsSurface and model_from_json.
void bind_model(py::module_& module);
/// dnurbs.System with forces and springs.
void bind_system(py::module_& module);
/// dnurbs.Integrator, solve_static_equilibrium and TargetTrajectory.
void bind_integrator(py::module_& module);

/// fit_dnurbs_surface, fit_dnurbs_curve, their starts and minimize_energy.
void bind_design(py::module_& module);

/// A checkpoint as a dict of Python values and arrays (scene, scene_hash, step, time,
/// coordinates, velocities, accelerations_valid, accelerations).
py::dict checkpoint_dict(const Checkpoint& checkpoint);
/// The inverse of checkpoint_dict; Error naming a missing key or a bad array.
Checkpoint checkpoint_from_dict(const py::dict& values);

/// dnurbs.DeformableSuperquadricModel and superquadric_parameter_names.
void bind_superquadric(py::module_& module);
/// dnurbs.Grid, flat_grid_positions, TerzopoulosSurface, PdeSurface and Snake.
void bind_grid_models(py::module_& module);
/// dnurbs.GeneralizedSpline (dynamics/grid/generalized_spline.h).
void bind_generalized_spline(py::module_& module);
/// dnurbs.SwungSurface, the swung prototypes, refine_swung_surface and DNurbsSwungSurface.
void bind_swung(py::module_& module);
/// dnurbs.Triangulation, TriangularBSplineBasis, TriangularNurbsSurface and
/// TriangularDNurbsSurface.
void bind_triangular(py::module_& module);
/// dnurbs.DeformationFieldModel (dynamics/fields/deformation_field_model.h).
void bind_deformation_field(py::module_& module);
/// Shape files (parse, read, write, to_json; triangular ones too) and checkpoint files.
void bind_shape_files(py::module_& module);
/// dnurbs.ConstraintSolver with point, surface normal, curve-on-surface and hinge constraints.
void bind_constraints(py::module_& module);
/// dnurbs.Image, image filters and potentials, contours, TSnake and TSurface (vision/).
void bind_vision(py::module_& module);

}  // namespace dnurbs::python
