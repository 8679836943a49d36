"""Fitting and energy-minimizing design from Python: fits reproduce shapes they can represent,
the design optimum matches the static equilibrium of the same linear system."""

import numpy as np
import pytest

import dnurbs


def test_curve_fit_errors_are_the_distances_and_shrink_with_iterations():
    t = np.linspace(0, 1, 40)
    points = np.stack([t, t ** 2 - t, 0.5 * t ** 3], axis=-1)
    start = dnurbs.principal_axis_curve(points, 3, 2)
    assert start.degree == 3 and start.control_point_count == 5
    model = dnurbs.DNurbsCurve(start)
    first = dnurbs.fit_dnurbs_curve(model, points, max_iterations=1)
    result = dnurbs.fit_dnurbs_curve(model, points, max_iterations=30)
    # Parameter correction converges linearly: 30 iterations improve on one (measured:
    # rms 5.5e-4 after 1 and 3.2e-4 after 30 iterations).
    assert result["rms_error"] < first["rms_error"]
    assert result["iterations"] <= 30 and result["parameters"].shape == (40, 2)
    # The reported errors are the distances of the points to the fitted curve at their
    # parameters (round-off of the evaluation).
    fitted = model.curve(result["coordinates"])
    distances = np.linalg.norm(fitted(result["parameters"][:, 0]) - points, axis=1)
    assert result["rms_error"] == pytest.approx(np.sqrt(np.mean(distances ** 2)), rel=1e-12)
    assert result["max_error"] == pytest.approx(distances.max(), rel=1e-12)
    with pytest.raises(dnurbs.Error):
        dnurbs.fit_dnurbs_curve(model, np.full((5, 3), np.nan))


def test_surface_fit_of_a_plane_is_exact():
    x, y = np.meshgrid(np.linspace(0, 2, 8), np.linspace(0, 1, 8), indexing="ij")
    points = np.stack([x, y, 0.5 * x - 0.25 * y], axis=-1).reshape(-1, 3)
    start = dnurbs.principal_plane_surface(points, 2, 2)
    result = dnurbs.fit_dnurbs_surface(dnurbs.DNurbsSurface(start), points)
    # The start is the plane itself (linear in (u, v)): round-off only.
    assert result["max_error"] < 1e-12


def test_minimize_energy_equals_static_equilibrium():
    knots = dnurbs.KnotVector.clamped_uniform(3, 5)
    u, v = np.meshgrid(np.linspace(0, 1, 5), np.linspace(0, 1, 5), indexing="ij")
    net = np.stack([u, v, np.zeros_like(u)], axis=-1).reshape(-1, 3)
    model = dnurbs.DNurbsSurface(dnurbs.NurbsSurface(knots, knots, net), a10=1.0, a01=1.0,
                                 b20=0.1, b02=0.1)
    model.fix_border()
    system = dnurbs.System()
    system.add_model(model)
    system.add_point_force(0, [0.5, 0.5], [0, 0, 1.0])
    optimum = dnurbs.minimize_energy(system)
    assert optimum["converged"], optimum["status_name"]
    dnurbs.solve_static_equilibrium(system)
    # SLSQP on a quadratic: converged to its variable tolerance, far below 1e-8 here.
    np.testing.assert_allclose(optimum["coordinates"], system.coordinates, atol=1e-8)
    solver = dnurbs.ConstraintSolver()
    solver.add_point_target(system, 0, [0.5, 0.5], dnurbs.TargetTrajectory.fixed([0.5, 0.5, 0.2]))
    constrained = dnurbs.minimize_energy(system, solver)
    assert constrained["constraint_violation"] < 1e-10
    with pytest.raises(dnurbs.Error, match="design algorithm"):
        dnurbs.minimize_energy(system, algorithm="simplex")


def _superquadric_points(model, nu, nv):
    u, v = np.meshgrid(-np.pi / 2 + np.pi * (np.arange(nu) + 0.5) / nu,
                       -np.pi + 2 * np.pi * (np.arange(nv) + 0.3) / nv, indexing="ij")
    return model.position(None, np.stack([u.ravel(), v.ravel()], axis=-1))


def test_superquadric_fit_recovers_twist_and_shear():
    # q_s = (a, a1, a2, a3, e1, e2, t1, t2, b1, b2, b3, tau, sx, sy): tapered, bent, twisted and
    # sheared, away from the origin.
    shape = [1.0, 1.2, 0.7, 1.8, 0.6, 1.4, 0.2, -0.1, 0.15, 0.0, 0.5, 0.4, 0.1, -0.15]
    model = dnurbs.DeformableSuperquadricModel(shape, centre=[0.5, -1.0, 2.0])
    points = _superquadric_points(model, 12, 18)
    fit = dnurbs.fit_superquadric(points)
    # Noise-free points: exact up to round-off (tests/design measures <= 1e-14).
    np.testing.assert_allclose(fit["shape"], shape, atol=1e-10)
    np.testing.assert_allclose(fit["centre"], [0.5, -1.0, 2.0], atol=1e-10)
    np.testing.assert_allclose(fit["rotation"], np.eye(3), atol=1e-10)
    assert fit["rms_error"] < 1e-12 and fit["local"] is None
    # Twist and shear held at 0: the shape cannot be reached, the residual stays.
    held = dnurbs.fit_superquadric(points, twist=False, shear=False)
    assert held["shape"][11:].tolist() == [0.0, 0.0, 0.0] and held["rms_error"] > 1e-3
    with pytest.raises(dnurbs.Error, match="17 parameters"):
        dnurbs.fit_superquadric(points[:16])


def test_superquadric_local_fit_gives_the_models_local_coordinates():
    # A unit sphere with a Gaussian bump of 0.1 around the x axis.
    sphere = dnurbs.DeformableSuperquadricModel([1.0, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0])
    points = _superquadric_points(sphere, 24, 48)
    angle = np.arccos(np.clip(points[:, 0], -1, 1))
    points *= (1 + 0.1 * np.exp(-angle ** 2 / (2 * 0.3 ** 2)))[:, None]
    fit = dnurbs.fit_superquadric(points, local=True, local_cells=(12, 24),
                                  local_smoothness=1e-5)
    local = fit["local"]
    assert local["mesh_cells"] == (12, 24) and local["q_d"].shape == (3 * (2 + 11 * 24),)
    assert local["rms_error"] < local["global_rms_error"] / 4
    # q_d is the model's own local block: a 'full' model at the fitted pose and shape with these
    # displacements puts each material point at the reported distance from its point.
    w, x, y, z = _quaternion(fit["rotation"])
    model = dnurbs.DeformableSuperquadricModel(fit["shape"], centre=fit["centre"],
                                               orientation=[w, x, y, z], parts="full",
                                               mesh_cells=(12, 24))
    q = model.initial_coordinates()
    q[model.layout["local_coordinate"]:] = local["q_d"]
    distances = np.linalg.norm(model.position(q, local["parameters"]) - points, axis=1)
    assert np.sqrt(np.mean(distances ** 2)) == pytest.approx(local["rms_error"], rel=1e-9)
    with pytest.raises(dnurbs.Error, match="smoothness is -1"):
        dnurbs.fit_superquadric(points, local=True, local_smoothness=-1.0)


def _quaternion(rotation):
    """(w, x, y, z) of a proper rotation matrix (3, 3) with trace > -1."""
    w = np.sqrt(max(0.0, 1.0 + np.trace(rotation))) / 2
    return (w, (rotation[2, 1] - rotation[1, 2]) / (4 * w),
            (rotation[0, 2] - rotation[2, 0]) / (4 * w),
            (rotation[1, 0] - rotation[0, 1]) / (4 * w))
