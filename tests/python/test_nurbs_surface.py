"""dnurbs.NurbsSurface and the surface primitives: values against exact formulas (bilinear
patch, sphere, torus), derivatives against finite differences, knot operations along U and V
that must leave the surface unchanged, closest points."""

import numpy as np
import pytest

import dnurbs

# Round-off of a rational tensor-product evaluation with O(1) coordinates (a few ulps per sum).
ROUND_OFF = 1e-14


def bilinear():
    corners = np.array([[0.0, 0.0, 0.0], [0.0, 1.0, 0.5], [2.0, 0.0, 1.0], [2.0, 1.0, -1.0]])
    knots = dnurbs.KnotVector(1, [0, 0, 1, 1])
    return dnurbs.NurbsSurface(knots, knots, corners), corners


def test_bilinear_patch_equals_formula_on_a_meshgrid():
    surface, c = bilinear()
    u, v = np.meshgrid(np.linspace(0, 1, 5), np.linspace(0, 1, 7), indexing="ij")
    points = surface(u, v)
    assert points.shape == (5, 7, 3)
    # Control point (i, j) is row 2 i + j (u index outer).
    expected = ((1 - u)[..., None] * (1 - v)[..., None] * c[0] + (1 - u)[..., None] * v[..., None]
                * c[1] + u[..., None] * (1 - v)[..., None] * c[2] + (u * v)[..., None] * c[3])
    np.testing.assert_allclose(points, expected, rtol=0, atol=ROUND_OFF)
    # Broadcasting: a column of u against a row of v gives the same grid.
    np.testing.assert_allclose(surface(u[:, :1], v[:1, :]), points, rtol=0, atol=0)
    d = surface.derivatives(0.25, 0.5, 2)
    assert d.shape == (3, 3, 3)
    np.testing.assert_allclose(d[1, 1], c[3] - c[2] - c[1] + c[0], rtol=0, atol=ROUND_OFF)
    np.testing.assert_allclose(d[2, 0], 0, atol=ROUND_OFF)
    np.testing.assert_array_equal(d[2, 1], 0)  # k + l > order: zero by definition


def test_sphere_radius_normals_and_curvature():
    radius = 1.7
    sphere = dnurbs.sphere(radius)
    u, v = np.meshgrid(np.linspace(0.05, 0.95, 9), np.linspace(0.0, 1.0, 13), indexing="ij")
    points = sphere(u, v)
    np.testing.assert_allclose(np.linalg.norm(points, axis=-1), radius, rtol=ROUND_OFF)
    normals = sphere.unit_normal(u, v)
    # The normal is radial (outward or inward by the parametrization's orientation).
    np.testing.assert_allclose(np.abs(np.sum(normals * points, axis=-1)), radius, rtol=1e-12)
    curvature = sphere.curvature(u, v)
    # Every point of a sphere is umbilic: K = 1 / r^2, |H| = 1 / r (second derivatives of the
    # rational surface: round-off about 1e-12 relative).
    np.testing.assert_allclose(curvature["gaussian"], 1 / radius ** 2, rtol=1e-11)
    np.testing.assert_allclose(np.abs(curvature["mean"]), 1 / radius, rtol=1e-11)
    assert curvature["direction_max"].shape == (9, 13, 3)


@pytest.mark.parametrize("make", [lambda: dnurbs.torus(3.0, 1.0),
                                  lambda: dnurbs.periodic_torus(3.0, 1.0)])
def test_torus_points_are_at_tube_radius(make):
    torus = make()
    u, v = np.meshgrid(np.linspace(0, 1, 11), np.linspace(0, 1, 11), indexing="ij")
    p = torus(u, v)
    tube = np.hypot(np.hypot(p[..., 0], p[..., 1]) - 3.0, p[..., 2])
    np.testing.assert_allclose(tube, 1.0, rtol=0, atol=1e-13)


def test_surface_derivatives_match_central_differences():
    sphere = dnurbs.sphere(1.0)
    u = np.array([0.2, 0.41, 0.7])
    v = np.array([0.1, 0.55, 0.83])
    h = 1e-5
    d = sphere.derivatives(u, v, 1)
    # Truncation h^2 |S'''| / 6 plus round-off 1e-16 / h, both below 1e-6 here.
    np.testing.assert_allclose(d[:, 1, 0], (sphere(u + h, v) - sphere(u - h, v)) / (2 * h),
                               atol=1e-6)
    np.testing.assert_allclose(d[:, 0, 1], (sphere(u, v + h) - sphere(u, v - h)) / (2 * h),
                               atol=1e-6)


@pytest.mark.parametrize("direction", [dnurbs.Direction.U, dnurbs.Direction.V])
def test_knot_operations_keep_the_surface(direction):
    sphere = dnurbs.sphere(1.0)
    u, v = np.meshgrid(np.linspace(0, 1, 9), np.linspace(0, 1, 9), indexing="ij")
    inserted = sphere.insert_knot(direction, 0.3)
    refined = sphere.refine_knots(direction, [0.2, 0.8])
    elevated = sphere.elevate_degree(direction, 1)
    for changed in (inserted, refined, elevated):
        np.testing.assert_allclose(changed(u, v), sphere(u, v), rtol=0, atol=ROUND_OFF)
    count_u, count_v = sphere.control_point_count_u, sphere.control_point_count_v
    grew = (count_u + 1, count_v) if direction == dnurbs.Direction.U else (count_u, count_v + 1)
    assert (inserted.control_point_count_u, inserted.control_point_count_v) == grew
    degrees = (elevated.degree_u, elevated.degree_v)
    assert degrees == ((3, 2) if direction == dnurbs.Direction.U else (2, 3))
    removed, count, succeeded = inserted.remove_knot(direction, 0.3, 1, 1e-12)
    assert (count, succeeded) == (1, True)
    # Least-squares removal (QR): round-off of the factorization.
    np.testing.assert_allclose(removed.control_points, sphere.control_points, atol=1e-13)
    np.testing.assert_allclose(removed.weights, sphere.weights, atol=1e-13)


def test_closest_points_on_sphere_are_radial():
    sphere = dnurbs.sphere(2.0)
    queries = np.array([[3.0, 1.0, 0.5], [0.1, -0.2, 0.3], [-4.0, 2.0, -1.0]])
    parameters, points, distances = sphere.closest_point(queries)
    assert parameters.shape == (3, 2)
    expected = 2.0 * queries / np.linalg.norm(queries, axis=1)[:, None]
    # Newton's method to round-off of the stationarity conditions.
    np.testing.assert_allclose(points, expected, atol=1e-11)
    np.testing.assert_allclose(distances, np.abs(np.linalg.norm(queries, axis=1) - 2.0),
                               atol=1e-11)
    np.testing.assert_allclose(sphere(parameters[:, 0], parameters[:, 1]), points, atol=1e-11)
    uv = sphere.invert_point(sphere(0.3, 0.6), 1e-9)
    np.testing.assert_allclose(uv, (0.3, 0.6), atol=1e-11)


def test_surface_of_revolution_of_a_half_circle_is_a_sphere():
    revolved = dnurbs.surface_of_revolution(dnurbs.half_circle_xz(1.25))
    np.testing.assert_allclose(revolved.control_points, dnurbs.sphere(1.25).control_points)
    assert revolved.is_rational
    assert "NurbsSurface" in repr(revolved)
