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
    (lambda: dnurbs.Grid(3, 3, NAN), "grid spacing h = nan is not positive and finite"),
    (lambda: dnurbs.Grid(1, 3, 1.0), "grid of 1 by 3 nodes is smaller than the 2 by 2"),
    (lambda: dnurbs.DeformableSuperquadricModel(SPHERE, centre=[0, NAN, 0]),
     "centre coordinate nan is not finite"),
    (lambda: dnurbs.DeformableSuperquadricModel(SPHERE, mesh_cells=(1, 16)),
     "cells_u is 1; it must be at least 2"),
    (lambda: dnurbs.TerzopoulosSurface(dnurbs.Grid(3, 3, 1.0), nan_rest()),
     r"rest position of node \(1, 1\) coordinate 2 is nan"),
    (lambda: dnurbs.TerzopoulosSurface(dnurbs.Grid(3, 3, 1.0), nan_rest()[:, :2]),
     r"rest must have shape \(9, 3\)"),
    (lambda: dnurbs.PdeSurface(dnurbs.Grid(3, 3, 1.0), nan_rest()),
     r"rest position of node \(1, 1\) coordinate 2 is nan"),
    (lambda: dnurbs.PdeSurface(dnurbs.Grid(5, 5, 1.0),
                               dnurbs.flat_grid_positions(dnurbs.Grid(5, 5, 1.0)), b=-1.0),
     "PDE surface b = -1 is not non-negative"),
    (lambda: dnurbs.Snake(np.zeros((2, 3))),
     "open node chain of 2 nodes has fewer than the 3 needed"),
    (lambda: dnurbs.swung_torus(1.0, 2.0), "minor radius 2 must be below the major radius 1"),
    (lambda: dnurbs.swung_sphere(1.0).derivatives(0.5, 0.5, 99), "order 99"),
    (lambda: dnurbs.DNurbsSwungSurface(dnurbs.swung_sphere(1.0), mass_density=-1.0),
     r"mass density is negative \(-1\)"),
    (lambda: dnurbs.DNurbsSwungSurface(dnurbs.swung_sphere(1.0), minimum_weight=0.0),
     "minimum weight 0 is not a positive finite number"),
    (lambda: dnurbs.TriangularNurbsSurface(square_basis(), [[0, 0, 0]] * 5 + [[NAN, 0, 0]]),
     "control point 5 of the triangular NURBS surface is not finite"),
    (lambda: dnurbs.TriangularBSplineBasis(
        dnurbs.rectangle_triangulation([0, 0], [1, 1], 1, 1), 2, cloud_radius=0.9),
     r"knot cloud radius 0.9 is outside \(0, 0.5\)"),
    (lambda: dnurbs.rectangle_triangulation([0, 0], [1, 1], 0, 1), "grid of 0 by 1 cells"),
    (lambda: dnurbs.Triangulation([[0, 0], [1, 0], [NAN, 1]], [[0, 1, 2]]),
     r"triangulation vertex 2 \(nan, 1\) is not finite"),
    (lambda: dnurbs.image_edge_potential(dnurbs.Image(np.full((3, 3), NAN)), 1.0),
     r"pixel \(0, 0\) is nan"),
    (lambda: dnurbs.gaussian_kernel(-1.0), r"sigma = -1 is not in \[0, 256\]"),
    (lambda: dnurbs.Volume(np.zeros((2, 2))),
     r"voxels has 2 dimensions, must be 3 \(nz, ny, nx\)"),
    (lambda: dnurbs.signed_area(np.zeros((3, 3))), r"contour must have shape \(n, 2\)"),
    (lambda: dnurbs.image_potential(np.zeros((1, 1)), 1.0),
     "image of 1 by 1 pixels is smaller than 2 by 2"),
    (lambda: dnurbs.parse_triangular_shape("{}", "empty"), "^empty: type: missing key"),
    (lambda: dnurbs.parse_checkpoint("[]", "list"), "^list: .*expected a checkpoint object"),
    (lambda: dnurbs.write_checkpoint("/nonexistent/dir/c.json", {}),
     "checkpoint has no \"scene\""),
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
