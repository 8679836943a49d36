"""The shape generators from Python: Greville rods and sheets linear in their parameters, the
exact box, cylinder and cone, revolution by an angle, extrusion, lofts through their sections,
span splitting and shape recipes (the JSON of a scene's "make")."""

import math

import numpy as np
import pytest

import dnurbs

# Round-off of a tensor-product evaluation with O(1) coordinates (a few ulps per sum).
ROUND_OFF = 1e-13


def test_greville_line_and_plane_are_linear():
    knots = dnurbs.KnotVector(3, [0, 0, 0, 0, 1, 2, 2, 2, 2])
    np.testing.assert_allclose(dnurbs.greville_abscissae(knots), [0, 1 / 3, 1, 5 / 3, 2],
                               rtol=0, atol=1e-15)
    line = dnurbs.greville_line((0, 0, 0), (3, 4, 0), control_points=6, degree=2)
    u = np.linspace(0, 5, 11)
    np.testing.assert_allclose(line(u), np.outer(u / 5, [3, 4, 0]), rtol=0, atol=ROUND_OFF)
    unit = dnurbs.greville_line((0, 0, 0), (3, 4, 0), domain=1.0)
    np.testing.assert_allclose(unit(0.5), [1.5, 2, 0], rtol=0, atol=ROUND_OFF)
    sheet = dnurbs.greville_plane(size=(3, 2), control_points=(7, 5), degree=(3, 2),
                                  origin=(1, 1, 0), domain=(1, 1))
    assert (sheet.control_point_count_u, sheet.control_point_count_v) == (7, 5)
    uu, vv = np.meshgrid(np.linspace(0, 1, 6), np.linspace(0, 1, 4), indexing="ij")
    expected = np.stack([1 + 3 * uu, 1 + 2 * vv, 0 * uu], axis=-1)
    np.testing.assert_allclose(sheet(uu, vv), expected, rtol=0, atol=ROUND_OFF)


def test_box_cylinder_and_cone_are_exact():
    b = dnurbs.box((2, 4, 1))
    uu, vv = np.meshgrid(np.linspace(1, 2, 5), np.linspace(0, 4, 9), indexing="ij")
    side = b(uu, vv)  # u in [1, 2]: the side faces
    on_x = np.abs(np.abs(side[..., 0]) - 1)
    on_y = np.abs(np.abs(side[..., 1]) - 2)
    np.testing.assert_allclose(np.minimum(on_x, on_y), 0, atol=ROUND_OFF)
    tube = dnurbs.cylinder(radius=0.5, height=2, profile_control_points=5)
    uu, vv = np.meshgrid(np.linspace(0, 2, 5), np.linspace(0, 1, 9), indexing="ij")
    p = tube(uu, vv)
    np.testing.assert_allclose(np.hypot(p[..., 0], p[..., 1]), 0.5, rtol=ROUND_OFF)
    np.testing.assert_allclose(p[..., 2], uu, atol=ROUND_OFF)
    spike = dnurbs.cone(radius=1, height=2)
    height = math.hypot(1, 2)
    p = spike(uu * height / 2, vv)
    np.testing.assert_allclose(np.hypot(p[..., 0], p[..., 1]), 1 - p[..., 2] / 2, atol=ROUND_OFF)


def test_revolve_extrude_loft_and_split_keep_their_curves():
    profile = dnurbs.half_circle_xz(1.5)
    quarter = dnurbs.revolve(profile, math.pi / 2)
    u = np.linspace(0, 1, 7)
    end = quarter(u, np.ones_like(u))
    start = profile(u)
    np.testing.assert_allclose(end, np.stack([-start[:, 1], start[:, 0], start[:, 2]], axis=-1),
                               atol=ROUND_OFF)
    wall = dnurbs.extrude(profile, (0, 2, 0))
    np.testing.assert_allclose(wall(u, np.full_like(u, 1.0)), start + [0, 1, 0], atol=ROUND_OFF)
    top = dnurbs.greville_line((0, 0, 1), (1, 0, 1))
    surface, parameters = dnurbs.loft([profile, top], degree=3)
    assert parameters == [0.0, 1.0]
    np.testing.assert_allclose(surface(u, np.zeros_like(u)), start, atol=ROUND_OFF)
    np.testing.assert_allclose(surface(u, np.ones_like(u)), top(u), atol=ROUND_OFF)
    finer = dnurbs.split_spans(quarter, (2, 3))
    assert finer.control_point_count_u == quarter.control_point_count_u + 2
    vv = np.linspace(0, 1, 7)
    np.testing.assert_allclose(finer(u[:, None], vv[None, :]), quarter(u[:, None], vv[None, :]),
                               atol=ROUND_OFF)
    assert dnurbs.split_spans(top, 4).control_point_count == top.control_point_count + 3


def test_make_shape_reads_recipes_and_names_bad_values():
    sphere = dnurbs.make_shape('{"kind": "sphere", "radius": 2, "translate": [0, 0, 1]}')
    p = sphere(np.linspace(0, 1, 5)[:, None], np.linspace(0, 1, 5)[None, :])
    np.testing.assert_allclose(np.linalg.norm(p - [0, 0, 1], axis=-1), 2, rtol=ROUND_OFF)
    rod = dnurbs.make_shape('{"kind": "line", "end": [2, 0, 0]}')
    assert isinstance(rod, dnurbs.NurbsCurve)
    with pytest.raises(dnurbs.Error, match=r"recipe: size\[0\]: expected a number > 0"):
        dnurbs.make_shape('{"kind": "plane", "size": [0, 1]}')
    with pytest.raises(dnurbs.Error, match="kind: expected one of line, plane"):
        dnurbs.make_shape('{"kind": "teapot"}')
