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
