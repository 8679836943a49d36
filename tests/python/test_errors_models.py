"""Bad input to the model, shape, file, constraint and vision bindings raises ValueError
(dnurbs.Error) with the library's message or TypeError naming the type, never a crash: NaN,
negative weights and sizes, wrong shapes and wrong types."""

import numpy as np
import pytest

import dnurbs
from conftest import SOURCE_DIR

NAN = float("nan")
SPHERE = [1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0]


def square_basis():
    return dnurbs.TriangularBSplineBasis(dnurbs.rectangle_triangulation([0, 0], [1, 1], 1, 1), 1)


def nan_rest():
    rest = dnurbs.flat_grid_positions(dnurbs.Grid(3, 3, 1.0))
    rest[4, 2] = NAN
    return rest


VALUE_ERRORS = [
    (lambda: dnurbs.Grid(3, 3, NAN), "h|spacing"),
    (lambda: dnurbs.Grid(1, 3, 1.0), "1"),
    (lambda: dnurbs.DeformableSuperquadricModel(SPHERE, centre=[0, NAN, 0]), "centre|finite"),
    (lambda: dnurbs.DeformableSuperquadricModel(SPHERE, mesh_cells=(1, 16)), "cells|1"),
    (lambda: dnurbs.TerzopoulosSurface(dnurbs.Grid(3, 3, 1.0), nan_rest()), "rest|finite"),
    (lambda: dnurbs.TerzopoulosSurface(dnurbs.Grid(3, 3, 1.0), nan_rest()[:, :2]),
     r"rest must have shape \(9, 3\)"),
    (lambda: dnurbs.PdeSurface(dnurbs.Grid(3, 3, 1.0), nan_rest()), "rest|finite"),
    (lambda: dnurbs.PdeSurface(dnurbs.Grid(5, 5, 1.0), dnurbs.flat_grid_positions(
        dnurbs.Grid(5, 5, 1.0)), b=-1.0), "b|negative|>= 0"),
    (lambda: dnurbs.Snake(np.zeros((2, 3))), "2|count"),
    (lambda: dnurbs.swung_torus(1.0, 2.0), "minor_radius|radius"),
    (lambda: dnurbs.swung_sphere(1.0).derivatives(0.5, 0.5, 99), "order 99"),
    (lambda: dnurbs.DNurbsSwungSurface(dnurbs.swung_sphere(1.0), mass_density=-1.0), "mass|density"),
    (lambda: dnurbs.DNurbsSwungSurface(dnurbs.swung_sphere(1.0), minimum_weight=0.0), "minimum_weight|weight"),
    (lambda: dnurbs.TriangularNurbsSurface(square_basis(), [[0, 0, 0]] * 5 + [[NAN, 0, 0]]),
     "finite|control"),
    (lambda: dnurbs.TriangularBSplineBasis(dnurbs.rectangle_triangulation([0, 0], [1, 1], 1, 1),
                                           2, cloud_radius=0.9), "radius|rho"),
    (lambda: dnurbs.rectangle_triangulation([0, 0], [1, 1], 0, 1), "0|count"),
    (lambda: dnurbs.Triangulation([[0, 0], [1, 0], [NAN, 1]], [[0, 1, 2]]), "finite|vertex"),
    (lambda: dnurbs.image_edge_potential(dnurbs.Image(np.full((3, 3), NAN)), 1.0),
     "finite|pixel|sample"),
    (lambda: dnurbs.gaussian_kernel(-1.0), "sigma"),
    (lambda: dnurbs.Volume(np.zeros((2, 2))), "3 dimensions|dimensions"),
    (lambda: dnurbs.signed_area(np.zeros((3, 3))), r"contour must have shape \(n, 2\)"),
    (lambda: dnurbs.image_potential(np.zeros((1, 1)), 1.0), "2 by 2|image"),
    (lambda: dnurbs.parse_triangular_shape("{}", "empty"), "^empty: "),
    (lambda: dnurbs.parse_checkpoint("[]", "list"), "^list: "),
    (lambda: dnurbs.write_checkpoint("/nonexistent/dir/c.json", {}), "checkpoint has no"),
]


@pytest.mark.parametrize("call, message", VALUE_ERRORS)
def test_bad_values_raise_value_errors_with_the_library_message(call, message):
    with pytest.raises(ValueError, match=message):
        call()


TYPE_ERRORS = [
    lambda: dnurbs.DeformableSuperquadricModel("sphere"),
    lambda: dnurbs.DeformableSuperquadricModel(np.full(14, 1 + 1j)),
    lambda: dnurbs.TerzopoulosSurface("grid", np.zeros((9, 3))),
    lambda: dnurbs.DNurbsSwungSurface(dnurbs.sphere(1.0)),
    lambda: dnurbs.SwungSurface(1, 2),
    lambda: dnurbs.TriangularDNurbsSurface(dnurbs.sphere(1.0)),
    lambda: dnurbs.Triangulation(np.array([["a", "b"]]), [[0, 1, 2]]),
    lambda: dnurbs.Image(np.zeros((3, 3), dtype=complex)),
    lambda: dnurbs.TSnake(np.zeros((4, 4))),
    lambda: dnurbs.write_shape("x.json", "not a shape"),
    lambda: dnurbs.ConstraintSolver().add_surface_normal("system", 0, [0.5, 0.5], [0, 0, 1]),
]


@pytest.mark.parametrize("call", TYPE_ERRORS)
def test_wrong_types_raise_type_errors(call):
    with pytest.raises(TypeError):
        call()


def test_restore_rejects_a_number_and_a_bad_model_index():
    simulation = dnurbs.SceneSimulation(dnurbs.read_scene(
        SOURCE_DIR / "examples" / "scenes" / "curve_sculpting.json"))
    with pytest.raises(TypeError, match="checkpoint is a int, must be a dict or a path"):
        simulation.restore(42)
    system = dnurbs.System()
    with pytest.raises(ValueError, match="model"):
        dnurbs.ConstraintSolver().add_surface_normal(system, 0, [0.5, 0.5], [0, 0, 1])
