"""Triangular NURBS from Python: triangulations and their areas, the basis's affine reproduction
(a surface whose control points are the blossoms of a plane is that plane, with exact
derivatives), and the triangular D-NURBS model's energy of a tilted plane against its integral."""

import numpy as np
import pytest

import dnurbs

POINTS = np.array([[0.1, 0.2], [0.5, 0.5], [0.9, 0.3], [0.25, 0.75]])


def test_triangulations_and_their_areas():
    square = dnurbs.rectangle_triangulation([0, 0], [1, 1], 2, 2)
    assert square.vertices.shape == (9, 2) and square.triangles.shape == (8, 3)
    assert square.domain_area == pytest.approx(1.0, rel=1e-15)
    assert square.area(0) == pytest.approx(0.125, rel=1e-15)
    assert square.boundary_edges().shape == (8, 2)
    uniform = dnurbs.rectangle_triangulation([0, 0], [2, 1], 2, 1, alternating=False)
    assert uniform.domain_area == pytest.approx(2.0, rel=1e-15)
    assert dnurbs.l_shape_triangulation(1).domain_area == pytest.approx(3.0, rel=1e-15)
    assert dnurbs.square_with_hole_triangulation(1).domain_area == pytest.approx(8.0, rel=1e-15)
    refined = dnurbs.refine_triangulation(square)
    assert refined.triangles.shape == (32, 3) and refined.domain_area == pytest.approx(1.0)
    same = dnurbs.Triangulation(square.vertices, square.triangles)
    np.testing.assert_array_equal(same.triangles, square.triangles)
    with pytest.raises(ValueError, match="triangle 0"):
        dnurbs.Triangulation([[0, 0], [1, 0], [0, 1]], [[0, 2, 1]])  # clockwise


def plane_surface(a=0.3, b=-0.2, c=0.1, weights=None):
    basis = dnurbs.TriangularBSplineBasis(dnurbs.rectangle_triangulation([0, 0], [1, 1], 2, 2), 2)
    domain = basis.domain_points()
    # The blossom of an affine map is the map of the mean: control z = a u + b v + c reproduces
    # the plane exactly.
    points = np.column_stack([domain, a * domain[:, 0] + b * domain[:, 1] + c])
    return basis, dnurbs.TriangularNurbsSurface(basis, points, weights)


def test_affine_reproduction_and_derivatives():
    basis, surface = plane_surface()
    assert basis.degree == 2 and basis.function_count == 6 * 8
    assert basis.triangulation.triangles.shape == (8, 3)
    assert surface.basis.function_count == 48 and not surface.is_rational
    assert surface.control_points.shape == (48, 3)
    np.testing.assert_array_equal(surface.weights, np.ones(48))  # None: all weights 1
    points = surface(POINTS)
    assert points.shape == (4, 3)
    expected = np.column_stack([POINTS, 0.3 * POINTS[:, 0] - 0.2 * POINTS[:, 1] + 0.1])
    np.testing.assert_allclose(points, expected, atol=1e-14)
    d = surface.derivatives(POINTS.reshape(2, 2, 2), 2)
    assert d.shape == (2, 2, 6, 3)
    np.testing.assert_allclose(d[..., 1, :], np.broadcast_to([1, 0, 0.3], (2, 2, 3)), atol=1e-12)
    np.testing.assert_allclose(d[..., 2, :], np.broadcast_to([0, 1, -0.2], (2, 2, 3)), atol=1e-12)
    np.testing.assert_allclose(d[..., 3:, :], 0, atol=1e-10)
    normal = np.array([-0.3, 0.2, 1]) / np.linalg.norm([-0.3, 0.2, 1])
    np.testing.assert_allclose(surface.unit_normal(POINTS), np.broadcast_to(normal, (4, 3)),
                               atol=1e-12)
    # Fortran order and strided slices read the same parameters.
    np.testing.assert_array_equal(surface(np.asfortranarray(POINTS)), points)
    np.testing.assert_array_equal(surface(np.repeat(POINTS, 2, axis=0)[::2]), points)
    # The basis at a point: a partition of unity that reproduces u (the domain points are the
    # blossoms of the identity), with derivatives of the sums 0 and (1, 0), (0, 1).
    functions, values = basis.evaluate([0.3, 0.6], 2)
    assert values.shape == (6, len(functions))
    sums = values @ basis.domain_points()[functions]
    np.testing.assert_allclose(values.sum(axis=1), [1, 0, 0, 0, 0, 0], atol=1e-13)
    np.testing.assert_allclose(sums[0], [0.3, 0.6], atol=1e-14)
    np.testing.assert_allclose(sums[1:3], np.eye(2), atol=1e-13)
    np.testing.assert_array_equal(basis.evaluate([0.3, 0.6], 0)[1][1:], 0)
    flat = dnurbs.flat_triangular_surface(basis)
    np.testing.assert_allclose(flat(POINTS)[:, :2], POINTS, atol=1e-15)
    equal = dnurbs.TriangularNurbsSurface(basis, surface.control_points, np.full(48, 3.0))
    np.testing.assert_allclose(equal(POINTS), points, atol=1e-15)
    with pytest.raises(ValueError, match="outside"):
        surface([2.0, 2.0])
    with pytest.raises(ValueError, match="order 3"):
        surface.derivatives(POINTS, 3)
    with pytest.raises(ValueError, match="weight"):
        dnurbs.TriangularNurbsSurface(basis, surface.control_points, -np.ones(48))
    with pytest.raises(ValueError, match=r"control_points must have shape \(48, 3\)"):
        dnurbs.TriangularNurbsSurface(basis, surface.control_points[:5])


def test_triangular_dnurbs_energy_of_a_tilted_plane():
    _, surface = plane_surface(a=0.3, b=-0.2)
    model = dnurbs.TriangularDNurbsSurface(surface, a10=2.0, a01=1.0)
    assert model.coordinate_count == 144 and model.parametric_measure == pytest.approx(1.0)
    # E = 1/2 integral a10 |x_u|^2 + a01 |x_v|^2 = 1/2 (2 (1 + 0.09) + (1 + 0.04)) over the unit
    # square; the Dunavant rule of degree 2n on the polynomial cells is exact (round-off).
    assert model.potential_energy() == pytest.approx(0.5 * (2 * 1.09 + 1.04), rel=1e-13)
    np.testing.assert_array_equal(model.surface()(POINTS), surface(POINTS))
    np.testing.assert_array_equal(model.initial_surface.control_points, surface.control_points)
    np.testing.assert_allclose(model.position(None, POINTS), surface(POINTS), atol=1e-15)
    free = dnurbs.TriangularDNurbsSurface(surface, free_weights=True, quadrature_degree=6,
                                          quadrature_subdivisions=0)
    assert free.coordinate_count == 4 * 48


def test_triangular_dnurbs_rest_shape_and_plastic_flow():
    _, surface = plane_surface(a=0.3, b=-0.2)
    # The tilted plane under tension: measured from zero it is not at rest, from itself it is
    model = dnurbs.TriangularDNurbsSurface(surface, a10=2.0, a01=1.0, initial_shape_at_rest=True)
    assert model.has_rest_shape
    np.testing.assert_array_equal(model.rest_coordinates, model.initial_coordinates())
    assert model.potential_energy() == pytest.approx(0.0, abs=1e-28)
    q = model.initial_coordinates()
    shifted = q + 0.1
    model.set_rest_shape(shifted)  # a translation: the energy of the change is still zero
    assert model.potential_energy(q) == pytest.approx(0.0, abs=1e-26)
    model.set_plastic_flow(0.05, rate=2.0)
    model.set_plastic_flow(None)
    with pytest.raises(dnurbs.Error, match="plastic yield -1"):
        model.set_plastic_flow(-1.0)
