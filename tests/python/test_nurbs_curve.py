"""dnurbs.NurbsCurve, dnurbs.KnotVector and the curve primitives: values against exact formulas,
derivatives against finite differences, knot operations that must leave the curve unchanged."""

import math

import numpy as np
import pytest

import dnurbs

# Round-off of a rational evaluation with O(1) coordinates: a few ulps of the radius per
# operation of the de Boor / quotient-rule sums (about ten of them).
ROUND_OFF = 1e-14


def bezier_quadratic():
    knots = dnurbs.KnotVector(2, [0, 0, 0, 1, 1, 1])
    points = np.array([[0.0, 0.0, 0.0], [1.0, 2.0, 0.5], [3.0, 1.0, -1.0]])
    return dnurbs.NurbsCurve(knots, points), points


def test_knot_vector_clamped_uniform_knots_and_domain():
    knots = dnurbs.KnotVector.clamped_uniform(3, 6, 0.0, 3.0)
    np.testing.assert_array_equal(knots.knots, [0, 0, 0, 0, 1, 2, 3, 3, 3, 3])
    assert knots.degree == 3
    assert knots.control_point_count == 6
    assert knots.domain == (0.0, 3.0)
    assert knots.find_span(1.5) == 4
    assert knots.multiplicity(0.0) == 4
    assert knots.non_empty_spans() == [3, 4, 5]
    assert len(knots) == 10
    assert not knots.is_periodic
    assert dnurbs.KnotVector(3, knots.knots) == knots


def test_knot_vector_factories():
    breakpoints = dnurbs.KnotVector.clamped_from_breakpoints(2, [0.0, 0.25, 1.0])
    np.testing.assert_array_equal(breakpoints.knots, [0, 0, 0, 0.25, 1, 1, 1])
    uniform = dnurbs.KnotVector.uniform(2, 5)
    np.testing.assert_array_equal(uniform.knots, np.arange(8.0))
    periodic = dnurbs.KnotVector.periodic_uniform(3, 5)
    assert periodic.is_periodic and periodic.basis_count == 8
    # start + i (end - start) / n against linspace: one rounding each, at most an ulp of 1.
    np.testing.assert_allclose(periodic.period_knots, np.linspace(0, 1, 6), rtol=0,
                               atol=np.spacing(1.0))
    same = dnurbs.KnotVector.periodic(3, periodic.period_knots)
    assert same == periodic
    assert "periodic" in repr(periodic)


def test_bezier_points_equal_bernstein_formula():
    curve, p = bezier_quadratic()
    u = np.linspace(0.0, 1.0, 11)
    expected = (np.outer((1 - u) ** 2, p[0]) + np.outer(2 * u * (1 - u), p[1])
                + np.outer(u ** 2, p[2]))
    np.testing.assert_allclose(curve(u), expected, rtol=0, atol=ROUND_OFF)
    # The first derivative of the Bezier curve: 2 (1 - u)(P1 - P0) + 2 u (P2 - P1); the second
    # 2 (P2 - 2 P1 + P0).
    d = curve.derivatives(u, 2)
    assert d.shape == (11, 3, 3)
    np.testing.assert_allclose(d[:, 0], expected, rtol=0, atol=ROUND_OFF)
    np.testing.assert_allclose(
        d[:, 1], np.outer(2 * (1 - u), p[1] - p[0]) + np.outer(2 * u, p[2] - p[1]), rtol=0,
        atol=ROUND_OFF)
    np.testing.assert_allclose(d[:, 2], np.tile(2 * (p[2] - 2 * p[1] + p[0]), (11, 1)),
                               rtol=0, atol=ROUND_OFF)


def test_full_circle_has_radius_and_curvature_everywhere():
    centre = np.array([1.0, -2.0, 0.5])
    radius = 2.5
    circle = dnurbs.full_circle(radius, centre)
    u = np.linspace(0.0, 1.0, 101)
    points = circle(u)
    np.testing.assert_allclose(np.linalg.norm(points - centre, axis=1), radius, rtol=ROUND_OFF)
    np.testing.assert_allclose(points[:, 2], 0.5, rtol=0, atol=ROUND_OFF)
    # Curvature of a circle is 1 / r; the principal normal points to the centre.
    np.testing.assert_allclose(circle.curvature(u), 1.0 / radius, rtol=1e-12)
    towards_centre = (centre - points) / radius
    np.testing.assert_allclose(circle.principal_normal(u), towards_centre, rtol=0, atol=1e-12)
    tangents = circle.unit_tangent(u)
    np.testing.assert_allclose(np.einsum("ij,ij->i", tangents, towards_centre), 0, atol=1e-12)
    assert circle.is_rational and circle.degree == 2 and circle.control_point_count == 9


def test_rational_derivatives_match_central_differences():
    circle = dnurbs.full_circle(1.5)
    u = np.array([0.05, 0.3, 0.61, 0.9])
    h = 1e-5
    d = circle.derivatives(u, 2)
    # Central differences: truncation h^2 |C'''| / 6 (|C'''| ~ 1e3 for this parametrization at
    # most) plus round-off 1e-16 / h, both below 1e-6.
    np.testing.assert_allclose(d[:, 1], (circle(u + h) - circle(u - h)) / (2 * h), rtol=0,
                               atol=1e-6)
    # Second differences: truncation h^2 |C''''| / 12 plus round-off 1e-16 / h^2 ~ 1e-6.
    second = (circle(u + h) - 2 * circle(u) + circle(u - h)) / h ** 2
    np.testing.assert_allclose(d[:, 2], second, rtol=0, atol=1e-4)


def test_periodic_circle_wraps_and_has_radius():
    circle = dnurbs.periodic_circle(2.0)
    assert circle.is_periodic and circle.control_point_count == 8
    u = np.linspace(0.0, 1.0, 37)
    np.testing.assert_allclose(np.linalg.norm(circle(u), axis=1), 2.0, rtol=ROUND_OFF)
    # Parameters one period apart give the same point: the knot vector wraps them.
    np.testing.assert_allclose(circle(u + 1.0), circle(u), rtol=0, atol=ROUND_OFF)


@pytest.mark.parametrize("make", [dnurbs.full_circle, dnurbs.periodic_circle])
def test_knot_insertion_refinement_and_elevation_keep_the_curve(make):
    circle = make(1.0)
    u = np.linspace(0.0, 1.0, 53)
    inserted = circle.insert_knot(0.3, 2)
    assert inserted.control_point_count == circle.control_point_count + 2
    assert inserted.knots.multiplicity(0.3) == 2
    refined = circle.refine_knots([0.1, 0.6, 0.6])
    assert refined.control_point_count == circle.control_point_count + 3
    elevated = circle.elevate_degree(1)
    assert elevated.degree == 3
    for changed in (inserted, refined, elevated):
        # Convex combinations of homogeneous points: round-off of a few ulps per step.
        np.testing.assert_allclose(changed(u), circle(u), rtol=0, atol=ROUND_OFF)


def test_knot_removal_undoes_insertion():
    curve, _ = bezier_quadratic()
    inserted = curve.insert_knot(0.4)
    removed, count, succeeded = inserted.remove_knot(0.4, 1, 1e-12)
    assert (count, succeeded) == (1, True)
    assert removed.control_point_count == 3
    # Least-squares solve of the removal equations: round-off of the QR factorization.
    np.testing.assert_allclose(removed.control_points, curve.control_points, rtol=0, atol=1e-13)
    # A knot the curve needs (a kink) is not removed within a tiny tolerance.
    kinked = dnurbs.NurbsCurve(dnurbs.KnotVector(1, [0, 0, 0.5, 1, 1]),
                               [[0, 0, 0], [1, 1, 0], [2, 0, 0]])
    same, count, succeeded = kinked.remove_knot(0.5, 1, 1e-6)
    assert (count, succeeded) == (0, False)
    assert same.control_point_count == 3


def test_closest_points_on_circle_are_radial():
    radius = 2.0
    circle = dnurbs.full_circle(radius)
    queries = np.array([[3.0, 4.0, 0.0], [-1.0, 0.5, 2.0], [0.2, -0.1, 0.0]])
    parameters, points, distances = circle.closest_point(queries)
    assert parameters.shape == (3,) and points.shape == (3, 3) and distances.shape == (3,)
    planar = queries.copy()
    planar[:, 2] = 0
    expected = radius * planar / np.linalg.norm(planar, axis=1)[:, None]
    # Newton's method converges to round-off of the stationarity condition.
    np.testing.assert_allclose(points, expected, rtol=0, atol=1e-12)
    np.testing.assert_allclose(distances, np.linalg.norm(queries - expected, axis=1), atol=1e-12)
    np.testing.assert_allclose(circle(parameters), points, rtol=0, atol=1e-12)
    u, point, distance = circle.closest_point([3.0, 4.0, 0.0])
    assert np.shape(u) == () and point.shape == (3,)
    assert math.isclose(distance, 3.0, abs_tol=1e-12)


def test_invert_point_recovers_the_parameter():
    curve, _ = bezier_quadratic()
    point = curve(0.37)
    assert math.isclose(curve.invert_point(point, 1e-9), 0.37, abs_tol=1e-12)
    with pytest.raises(dnurbs.Error, match="farther|distance"):
        curve.invert_point(point + [0, 0, 1.0], 1e-6)
