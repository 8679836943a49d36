"""NumPy round trips of the dnurbs module: shapes and dtypes of results, read-only views without
copies where promised, C and Fortran order, non-contiguous and integer inputs read correctly."""

import copy

import numpy as np
import pytest

import dnurbs


def grid_surface(points):
    knots_u = dnurbs.KnotVector.clamped_uniform(2, 4)
    knots_v = dnurbs.KnotVector.clamped_uniform(2, 3)
    return dnurbs.NurbsSurface(knots_u, knots_v, points)


def net():
    i, j = np.meshgrid(np.arange(4.0), np.arange(3.0), indexing="ij")
    return np.stack([i, j, np.sin(i + 2 * j)], axis=-1).reshape(12, 3)


def test_control_points_are_read_only_views_without_copy():
    curve = dnurbs.full_circle(1.0)
    points = curve.control_points
    assert points.shape == (9, 3) and points.dtype == np.float64
    assert np.shares_memory(points, curve.control_points)
    assert np.shares_memory(curve.weights, curve.weights)
    assert np.shares_memory(curve.knots.knots, curve.knots.knots)
    assert not points.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        points[0, 0] = 5.0
    # The view keeps the curve alive after the last reference to it goes.
    del curve
    assert points[0, 0] == 1.0


def test_assigning_control_points_and_weights_goes_through_the_checks():
    curve = dnurbs.full_circle(1.0)
    moved = np.asarray(curve.control_points) * 2.0
    curve.control_points = moved
    np.testing.assert_array_equal(curve.control_points, moved)
    with pytest.raises(ValueError, match="control_points must have shape \\(9, 3\\), got \\(8, 3\\)"):
        curve.control_points = moved[:8]
    with pytest.raises(dnurbs.Error, match="weight 3 is -1"):
        curve.weights = [1, 1, 1, -1, 1, 1, 1, 1, 1]
    assert curve.weights[3] == pytest.approx(np.sqrt(0.5))


def test_fortran_order_non_contiguous_and_integer_inputs_read_the_same_values():
    points = net()
    reference = grid_surface(points)
    fortran = grid_surface(np.asfortranarray(points))
    wide = np.zeros((12, 6))
    wide[:, ::2] = points
    strided = grid_surface(wide[:, ::2])
    assert not wide[:, ::2].flags.c_contiguous
    for other in (fortran, strided):
        np.testing.assert_array_equal(other.control_points, reference.control_points)
    integer = dnurbs.NurbsCurve(dnurbs.KnotVector(1, [0, 0, 1, 1]),
                                np.array([[0, 0, 0], [2, 4, 6]], dtype=np.int32))
    np.testing.assert_array_equal(integer(0.5), [1.0, 2.0, 3.0])
    listed = dnurbs.NurbsCurve(dnurbs.KnotVector(1, [0, 0, 1, 1]), [[0, 0, 0], [2, 4, 6]])
    np.testing.assert_array_equal(listed(0.25), [0.5, 1.0, 1.5])


def test_result_shapes_follow_the_parameter_shapes():
    surface = grid_surface(net())
    assert surface(0.5, 0.5).shape == (3,)
    assert surface(np.zeros((2, 5)), 0.5).shape == (2, 5, 3)
    assert surface.derivatives(np.zeros(4), np.zeros(4), 2).shape == (4, 3, 3, 3)
    curve = dnurbs.full_circle(1.0)
    assert curve(np.zeros((2, 3))).shape == (2, 3, 3)
    assert curve.curvature(0.25).shape == ()
    assert curve.derivatives(np.linspace(0, 1, 4)[::2], 1).shape == (2, 2, 3)
    # Non-contiguous parameters read correctly.
    u = np.linspace(0, 1, 9)
    np.testing.assert_array_equal(curve(u[::4]), curve(np.array([0.0, 0.5, 1.0])))
    assert curve(u).dtype == np.float64 and curve(u).flags.c_contiguous


def test_shapes_are_values_copies_are_independent():
    curve = dnurbs.full_circle(1.0)
    twin = copy.deepcopy(curve)
    twin.control_points = np.asarray(twin.control_points) + 1.0
    assert curve.control_points[0, 0] == 1.0
    assert twin.control_points[0, 0] == 2.0
    assert not np.shares_memory(curve.control_points, twin.control_points)
