"""Swung surfaces from Python: the prototypes' exact geometry on arrays of parameters (a sphere of
radius r, a torus tube, a cylinder, a cone), derivatives against finite differences, the exact
tensor-product twin, refinement, and the swung D-NURBS model's coordinates, fixes, Jacobian, rest
shape and plastic flow."""

import numpy as np
import pytest

import dnurbs

U = np.linspace(0.05, 0.95, 7)[:, None]
V = np.linspace(0.0, 0.97, 5)[None, :]


def grid(surface):
    u0, u1, v0, v1 = surface.domain
    return u0 + (u1 - u0) * U, v0 + (v1 - v0) * V


def test_prototypes_are_exact():
    sphere = dnurbs.swung_sphere(2.0)
    u, v = grid(sphere)
    points = sphere(u, v)
    assert points.shape == (7, 5, 3)
    # Rational quadratic circles: radius 2 to round-off.
    np.testing.assert_allclose(np.linalg.norm(points, axis=-1), 2.0, rtol=1e-15)
    # S_u x S_v points inward on the sphere (swung_shapes.h): the normal is -x / r.
    np.testing.assert_allclose(sphere.unit_normal(u, v), -points / 2.0, atol=1e-14)
    torus = dnurbs.swung_torus(2.0, 0.5)
    t = torus(*grid(torus))
    tube = np.hypot(np.hypot(t[..., 0], t[..., 1]) - 2.0, t[..., 2])
    np.testing.assert_allclose(tube, 0.5, rtol=1e-14)
    cylinder = dnurbs.swung_cylinder(1.0, 2.0)
    c = cylinder(*grid(cylinder))
    np.testing.assert_allclose(np.hypot(c[..., 0], c[..., 1]), 1.0, rtol=1e-15)
    assert c[..., 2].min() >= 0 and c[..., 2].max() <= 2
    cone = dnurbs.swung_cone(1.0, 2.0, profile_control_points=5)
    k = cone(*grid(cone))
    np.testing.assert_allclose(np.hypot(k[..., 0], k[..., 1]), 1 - k[..., 2] / 2, atol=1e-15)
    annulus = dnurbs.swung_open_profile(0.5, 0.0, 1.0, 0.0)
    a = annulus(*grid(annulus))
    np.testing.assert_array_equal(a[..., 2], 0)
    radius = np.hypot(a[..., 0], a[..., 1])
    assert radius.min() >= 0.5 - 1e-15 and radius.max() <= 1 + 1e-15
    hat = dnurbs.swung_hat(2.0, 1.0, 1.0)
    assert hat.profile.control_point_count == 8
    np.testing.assert_allclose(np.linalg.norm(hat(hat.domain[1], 0.3)[:2]), 2.0, rtol=1e-15)
    circle = dnurbs.unit_circle_trajectory()
    np.testing.assert_allclose(np.linalg.norm(circle(np.linspace(0, 1, 9)), axis=-1), 1, rtol=1e-15)


def test_derivatives_match_finite_differences_and_the_tensor_product_twin():
    sphere = dnurbs.swung_sphere(1.5)
    u, v = np.array([0.3, 0.6]), np.array([0.2, 0.7])
    d = sphere.derivatives(u, v, 2)
    assert d.shape == (2, 3, 3, 3)
    h = 1e-5
    # Central differences: error h^2 |S'''| ~ 1e-10 relative.
    du = (sphere(u + h, v) - sphere(u - h, v)) / (2 * h)
    dv = (sphere(u, v + h) - sphere(u, v - h)) / (2 * h)
    np.testing.assert_allclose(d[:, 1, 0], du, atol=1e-8)
    np.testing.assert_allclose(d[:, 0, 1], dv, atol=1e-8)
    su = [sphere.derivatives(u, v + s * h, 1)[:, 1, 0] for s in (1, -1)]
    duv = (su[0] - su[1]) / (2 * h)
    np.testing.assert_allclose(d[:, 1, 1], duv, atol=1e-7)
    np.testing.assert_array_equal(d[:, 2, 1], 0)  # k + l > order
    twin = sphere.to_nurbs_surface()
    assert isinstance(twin, dnurbs.NurbsSurface)
    assert twin.control_point_count == 5 * 8  # profile points x distinct trajectory points
    np.testing.assert_allclose(twin(*grid(sphere)), sphere(*grid(sphere)), atol=1e-15)
    refined = dnurbs.refine_swung_surface(sphere, 1, 1)
    assert refined.profile.control_point_count == 7  # 5 + 2 spans x 1 knot
    assert refined.alpha == sphere.alpha == 1.0
    np.testing.assert_allclose(refined(*grid(sphere)), sphere(*grid(sphere)), atol=1e-15)


def test_swung_surface_rejects_curves_off_their_planes():
    sphere = dnurbs.swung_sphere(1.0)
    profile = sphere.profile
    points = np.array(profile.control_points)
    points[2, 1] = 0.1
    bent = dnurbs.NurbsCurve(profile.knots, points, profile.weights)
    with pytest.raises(ValueError, match="profile control point 2 has y = 0.1"):
        dnurbs.SwungSurface(bent, sphere.trajectory)
    with pytest.raises(ValueError, match="scale alpha is 0"):
        dnurbs.SwungSurface(profile, sphere.trajectory, 0.0)
    copy = dnurbs.SwungSurface(profile, sphere.trajectory, 2.0)
    assert copy.alpha == 2.0 and copy.trajectory.control_point_count == 8


def test_swung_model_coordinates_fixes_and_jacobian():
    sphere = dnurbs.swung_sphere(1.0)
    model = dnurbs.DNurbsSwungSurface(sphere, a10=0.1, a01=0.1)
    assert model.coordinate_count == 2 * (5 + 8) and not model.free_weights
    assert model.profile_offset(1) == 2 and model.trajectory_offset(0) == 10
    assert model.gauge_coordinate == model.profile_offset(2)  # the equator point's x
    assert model.uses_separable_assembly and model.minimum_weight == 1e-3
    u0, u1, v0, v1 = sphere.domain
    assert model.parametric_measure == pytest.approx((u1 - u0) * (v1 - v0), rel=1e-15)
    np.testing.assert_array_equal(model.surface()(0.3, 0.4), sphere(0.3, 0.4))
    assert model.initial_surface.profile.control_point_count == 5
    q = model.initial_coordinates() * 1.01
    rng = np.random.default_rng(2)
    q += 0.01 * rng.standard_normal(q.shape)
    jacobian = model.position_jacobian(q, [0.3, 0.4], dense=True)
    h = 1e-6
    at = [0.3, 0.4]
    numeric = np.stack([(model.position(q + h * e, at) - model.position(q - h * e, at)) / (2 * h)
                        for e in np.eye(q.size)], axis=1)
    # Central differences of a polynomial of degree 2 in q: round-off only (1e-16 / h).
    np.testing.assert_allclose(jacobian, numeric, atol=1e-9)
    model.fix_poles()
    assert {model.profile_offset(0), model.profile_offset(4)} <= set(model.fixed_coordinates)
    model.fix_profile_point(3)
    assert {6, 7} <= set(model.fixed_coordinates)
    model.fix_trajectory_point(1)
    assert {12, 13} <= set(model.fixed_coordinates)
    free = dnurbs.DNurbsSwungSurface(sphere, free_weights=True)
    assert free.free_weights and free.coordinate_count == 39 and not free.uses_separable_assembly
    free.fix_profile()
    free.fix_trajectory()
    assert len(free.fixed_coordinates) == 39


def test_swung_jacobians_of_derivatives_and_their_rates():
    model = dnurbs.DNurbsSwungSurface(dnurbs.swung_sphere(1.0))
    rng = np.random.default_rng(4)
    q = model.initial_coordinates() + 0.01 * rng.standard_normal(26)
    qd = rng.standard_normal(26)
    at = np.array([0.3, 0.4])
    jacobian = model.jacobian(q, at, 1)
    assert jacobian.shape == (3, 3, 26)
    np.testing.assert_array_equal(jacobian[0], model.position_jacobian(q, at, dense=True))
    # S_u's Jacobian is d/du of S's: central differences in u (error h^2 ~ 1e-10).
    h = 1e-5
    numeric = (model.jacobian(q, at + [h, 0])[0] - model.jacobian(q, at - [h, 0])[0]) / (2 * h)
    np.testing.assert_allclose(jacobian[1], numeric, atol=1e-8)
    # Jdot qd is the second derivative of S along q + t qd: S is bilinear in the two curves'
    # coordinates (fixed weights), so quadratic in t and the second difference is exact up to
    # round-off (1e-16 / h^2 with h = 1e-3).
    rates = model.jacobian_rate(q, qd, at, 1)
    assert rates.shape == (3, 3)
    t = 1e-3
    second = (model.position(q + t * qd, at) - 2 * model.position(q, at)
              + model.position(q - t * qd, at)) / t ** 2
    np.testing.assert_allclose(rates[0], second, atol=1e-9)
    with pytest.raises(ValueError, match="order 3"):
        model.jacobian(q, at, 3)


def test_swung_rest_shape_and_plastic_flow_keep_a_dent():
    material = dict(damping_density=3.0, a10=1.0, a01=1.0, b20=0.1, b11=0.1, b02=0.1)
    sphere = dnurbs.swung_sphere(1.0)
    # Measured from its initial shape the sphere is at rest: force and energy exactly 0
    model = dnurbs.DNurbsSwungSurface(sphere, initial_shape_at_rest=True, **material)
    assert model.has_rest_shape
    q = model.initial_coordinates()
    np.testing.assert_array_equal(model.rest_coordinates, q)
    assert np.abs(model.internal_force(q)).max() == 0.0 and model.potential_energy(q) == 0.0
    assert np.abs(dnurbs.DNurbsSwungSurface(sphere, **material).internal_force(q)).max() > 0.1
    # A rest shape of another profile: the energy of the change, zero at that rest
    moved = q.copy()
    moved[model.profile_offset(2)] += 0.1  # the equator's x
    model.set_rest_shape(moved)
    assert model.potential_energy(moved) == 0.0 and model.potential_energy(q) > 0.0
    # The equator pushed in for 1 s and released: the plastic sphere keeps a dent (in by 0.353,
    # 0.283 left), the elastic one springs back (in by 0.084, 1.2e-14 left; the damping's decay)
    def pushed_and_released(yield_distance):
        clay = dnurbs.DNurbsSwungSurface(sphere, initial_shape_at_rest=True, **material)
        clay.fix_poles()
        clay.fix_trajectory()
        if yield_distance is not None:
            clay.set_plastic_flow(yield_distance, rate=4.0)
        system = dnurbs.System()
        system.add_model(clay)
        system.add_point_force(0, [0.5, 0.0], [-8.0, 0.0, 0.0])
        integrator = dnurbs.Integrator("implicit-euler", newton_iterations=1)
        integrator.step(system, 0.02, count=50)
        system.clear_forces()
        integrator.step(system, 0.02, count=350)
        return 1.0 - system.position(0, [0.5, 0.0])[0]
    assert abs(pushed_and_released(None)) < 1e-6
    assert pushed_and_released(0.01) > 0.1
    with pytest.raises(dnurbs.Error, match="plastic yield -1"):
        model.set_plastic_flow(-1.0)
    model.set_plastic_flow(None)
