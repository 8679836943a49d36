"""Bad input from Python raises exceptions with the library's messages and never crashes:
dnurbs.Error (a ValueError) for bad values and shapes, TypeError for wrong types."""

import numpy as np
import pytest

import dnurbs


def line_knots():
    return dnurbs.KnotVector(1, [0, 0, 1, 1])


def test_error_is_a_value_error():
    assert issubclass(dnurbs.Error, ValueError)
    assert issubclass(dnurbs.SimulationDiverged, dnurbs.Error)


@pytest.mark.parametrize("knots, message", [
    ([0, 0, 0.5, 0.2, 1, 1], "knot vector decreases at index 3: 0.5 > 0.2"),
    ([0, 0, np.nan, 1, 1, 1], "knot 2 is not finite"),
    ([0, 1], "needs at least 4 knots, got 2"),
])
def test_bad_knot_vectors_raise_the_library_message(knots, message):
    with pytest.raises(ValueError, match=message.replace(".", "\\.")):
        dnurbs.KnotVector(1, knots)


def test_bad_degree_and_periodic_knots():
    with pytest.raises(dnurbs.Error, match="degree 0 is outside 1..15"):
        dnurbs.KnotVector.clamped_uniform(0, 4)
    with pytest.raises(dnurbs.Error, match="period knots decrease"):
        dnurbs.KnotVector.periodic(2, [0.0, 0.5, 0.3, 1.0])


def test_bad_control_points_and_weights():
    with pytest.raises(dnurbs.Error, match="control point 1 has a non-finite coordinate 2"):
        dnurbs.NurbsCurve(line_knots(), [[0, 0, 0], [1, 1, np.nan]])
    with pytest.raises(dnurbs.Error, match="weight 0 is -0.5; weights must be finite and > 0"):
        dnurbs.NurbsCurve(line_knots(), np.zeros((2, 3)), [-0.5, 1.0])
    with pytest.raises(dnurbs.Error, match="weight 1 is 0"):
        dnurbs.NurbsCurve(line_knots(), np.zeros((2, 3)), [1.0, 0.0])


@pytest.mark.parametrize("points, message", [
    (np.zeros((3, 3)), "control_points must have shape \\(2, 3\\), got \\(3, 3\\)"),
    (np.zeros((2, 2)), "control_points must have shape \\(2, 3\\), got \\(2, 2\\)"),
    (np.zeros(6), "control_points must have shape \\(2, 3\\), got \\(6,\\)"),
    (np.zeros((2, 3, 1)), "got \\(2, 3, 1\\)"),
])
def test_wrong_shapes_name_the_argument_and_both_shapes(points, message):
    with pytest.raises(dnurbs.Error, match=message):
        dnurbs.NurbsCurve(line_knots(), points)


def test_wrong_weight_count():
    with pytest.raises(dnurbs.Error, match="weights must have shape \\(2,\\), got \\(3,\\)"):
        dnurbs.NurbsCurve(line_knots(), np.zeros((2, 3)), [1, 1, 1])


@pytest.mark.parametrize("points", [
    np.zeros((2, 3), dtype=complex), np.array([["a", "b", "c"]] * 2), [[None] * 3] * 2,
])
def test_non_real_arrays_are_type_errors(points):
    with pytest.raises(TypeError, match="control_points must be an array of real numbers"):
        dnurbs.NurbsCurve(line_knots(), points)


def test_wrong_argument_types_are_type_errors():
    with pytest.raises(TypeError):
        dnurbs.NurbsCurve("not knots", np.zeros((2, 3)))
    with pytest.raises(TypeError):
        dnurbs.KnotVector("one", [0, 0, 1, 1])
    with pytest.raises(TypeError):
        dnurbs.sphere(1.0).insert_knot("u", 0.5)


def test_bad_parameters():
    curve = dnurbs.NurbsCurve(line_knots(), [[0, 0, 0], [1, 0, 0]])
    with pytest.raises(dnurbs.Error, match="parameter 2 is outside the domain \\[0, 1\\]"):
        curve(np.array([0.5, 2.0]))
    with pytest.raises(dnurbs.Error, match="parameter nan is not finite"):
        curve(np.nan)
    with pytest.raises(dnurbs.Error, match="derivative order 16 is outside 0..15"):
        curve.derivatives(0.5, 16)
    with pytest.raises(dnurbs.Error, match="derivative order -1"):
        dnurbs.sphere(1.0).derivatives(0.5, 0.5, -1)
    with pytest.raises(dnurbs.Error, match="do not broadcast"):
        dnurbs.sphere(1.0)(np.zeros(3), np.zeros(4))
    with pytest.raises(dnurbs.Error, match="points must have shape \\(3,\\) or \\(\\.\\.\\., 3\\)"):
        curve.closest_point(np.zeros((4, 2)))


def test_bad_knot_operations():
    curve = dnurbs.full_circle(1.0)
    with pytest.raises(dnurbs.Error, match="multiplicity"):
        curve.insert_knot(0.25, 1)
    with pytest.raises(dnurbs.Error):
        curve.elevate_degree(-1)
    with pytest.raises(dnurbs.Error):
        curve.remove_knot(0.3, 1, 1e-9)
    with pytest.raises(dnurbs.Error):
        curve.refine_knots([0.6, 0.2])
