"""Surface normal, curve-on-surface and hinge constraints from Python: held to the Baumgarte
solver's accuracy while forces push the models, with projection to round-off; descriptions,
multipliers and constraint forces read back."""

import numpy as np
import pytest

import dnurbs


def sheet(count=5):
    knots = dnurbs.KnotVector.clamped_uniform(3, count)
    u, v = np.meshgrid(np.linspace(0, 1, count), np.linspace(0, 1, count), indexing="ij")
    points = np.stack([u, v, np.zeros_like(u)], axis=-1).reshape(-1, 3)
    return dnurbs.DNurbsSurface(dnurbs.NurbsSurface(knots, knots, points), damping_density=2.0,
                                a10=1.0, a01=1.0, b20=0.1, b11=0.1, b02=0.1)


def test_surface_normal_held_while_a_force_tilts_the_sheet():
    system = dnurbs.System()
    system.add_model(sheet())
    system.model(0)
    system.add_point_force(0, [0.7, 0.5], [0, 0, 2.0])
    solver = dnurbs.ConstraintSolver()
    index = solver.add_surface_normal(system, 0, [0.5, 0.5], [0, 0, 1])
    assert index == 0 and solver.row_count == 2
    assert "normal" in solver.description(0)
    integrator = dnurbs.Integrator("implicit-euler")
    solver.set_projection(True, 1e-12, 5)
    solver.step(integrator, system, 0.01, 20)
    # Projection holds C (units of |S_u x S_v| ~ 1) at its tolerance.
    assert solver.max_violation(system) <= 1e-12
    assert solver.violations(system)[0] <= 1e-12
    derivatives = system.model(0).surface(system.coordinates).derivatives(0.5, 0.5, 1)
    normal = np.cross(derivatives[1, 0], derivatives[0, 1])
    assert abs(normal[0]) + abs(normal[1]) <= 1e-12 * np.linalg.norm(normal)
    # The sheet did move: the force point rose.
    assert system.position(0, [0.7, 0.5])[2] > 1e-3
    assert solver.constraint_force.shape == system.velocities.shape
    assert np.abs(solver.constraint_force).max() > 0
    assert solver.rank_deficient_steps == 0
    with pytest.raises(ValueError, match="constraint index 3"):
        solver.description(3)


def test_local_sculpting_freezes_the_control_points_away_from_a_point():
    model = sheet(count=7)
    # Bicubic on 4 x 4 spans: the span holding (0.5, 0.5) has (p + 1)^2 = 16 control points;
    # with margin 0 the other 33 of the 7 x 7 net are frozen, never one that moves the point.
    frozen = model.freeze_outside([0.5, 0.5], margin=0)
    assert frozen == 49 - 16 and len(model.fixed_coordinates) == 3 * frozen
    jacobian = model.position_jacobian(None, [0.5, 0.5], dense=True)
    moving = set(np.flatnonzero(np.abs(jacobian).sum(axis=0)))
    assert moving and not moving & set(model.fixed_coordinates)
    curve = dnurbs.DNurbsCurve(dnurbs.NurbsCurve(dnurbs.KnotVector.clamped_uniform(2, 6),
                                                 np.eye(6, 3)))
    assert curve.freeze_outside(None, [0], margin=0) == 5
    with pytest.raises(ValueError):
        dnurbs.DeformableSuperquadricModel([1] * 6 + [0] * 8).freeze_outside([0.5, 0.5])


def test_curve_glued_on_a_surface_and_a_hinge():
    system = dnurbs.System()
    system.add_model(sheet())
    knots = dnurbs.KnotVector.clamped_uniform(2, 4)
    line = np.column_stack([np.linspace(0.2, 0.8, 4), np.full(4, 0.4), np.zeros(4)])
    system.add_model(dnurbs.DNurbsCurve(dnurbs.NurbsCurve(knots, line), tension=0.5))
    solver = dnurbs.ConstraintSolver()
    indices = solver.add_curve_on_surface(system, 1, 0, 5)
    assert indices == [0, 1, 2, 3, 4] and solver.row_count == 15
    # The curve lies on the sheet: each joint starts at the closest point (violation round-off).
    assert solver.max_violation(system) <= 1e-12
    system.add_gravity(1, [0, 0, -1])
    integrator = dnurbs.Integrator("implicit-euler")
    solver.step(integrator, system, 0.01, 10)
    # Ball joints between control-net models with fixed weights are linear in q, so the step's
    # constraint rows hold them to round-off (measured 2.5e-16).
    assert solver.max_violation(system) <= 1e-13
    assert system.position(1, 0.5)[2] < -1e-4  # gravity pulled the curve and the sheet down
    hinge = dnurbs.System()
    hinge.add_model(sheet())
    hinge.add_model(sheet())
    hinges = dnurbs.ConstraintSolver()
    hinges.add_hinge(hinge, 0, [1, 0], [1, 1], 1, [0, 0], [0, 1])
    assert hinges.row_count == 6
    # The second sheet sits on the first (both on [0, 1]^2): each of the two joints is off by
    # x_a(1, t) - x_b(0, t) = (1, 0, 0), so |C| = sqrt(2) (exact corner points).
    np.testing.assert_allclose(hinges.violations(hinge), [np.sqrt(2)], rtol=1e-15)
    with pytest.raises(ValueError, match="model 2|model index 2"):
        hinges.add_hinge(hinge, 0, [1, 0], [1, 1], 2, [0, 0], [0, 1])


def test_curve_following_the_sheet_is_pulled_onto_it():
    system = dnurbs.System()
    clamped = sheet()
    clamped.fix_border()
    system.add_model(clamped)
    knots = dnurbs.KnotVector.clamped_uniform(2, 4)
    # A straight curve 0.1 above the flat sheet (z = 0): every sample is 0.1 from it (exact).
    line = np.column_stack([np.linspace(0.2, 0.8, 4), np.full(4, 0.4), np.full(4, 0.1)])
    system.add_model(dnurbs.DNurbsCurve(dnurbs.NurbsCurve(knots, line), rigidity=0.01,
                                        damping_density=2.0))
    samples = np.linspace(0, 1, 5)
    np.testing.assert_allclose(dnurbs.curve_to_surface_distances(system, 1, 0, samples),
                               np.full(5, 0.1), rtol=1e-14)
    solver = dnurbs.ConstraintSolver()
    assert solver.add_curve_on_surface(system, 1, 0, 5, follow=True) == [0]
    assert solver.row_count == 5 and "following" in solver.description(0)
    # One constraint of 5 rows, each the signed distance 0.1: |C| = 0.1 sqrt(5).
    np.testing.assert_allclose(solver.violations(system), [0.1 * np.sqrt(5)], rtol=1e-14)
    integrator = dnurbs.Integrator("newmark")
    solver.step(integrator, system, 0.01, 100)
    # Baumgarte (alpha = 20, critical) decays the start's 0.22 as (1 + 20 t) exp(-20 t), 1e-8
    # after 1 s; what remains is Newmark's O(dt^2) error on the non-linear rows while the sheet
    # still swings (measured 2.5e-5 at the samples, 6.8e-5 between them): below 1 % of the
    # starting 0.1 at the samples and at 41 parameters between them.
    assert solver.violations(system)[0] < 1e-3
    between = dnurbs.curve_to_surface_distances(system, 1, 0, np.linspace(0, 1, 41))
    assert np.abs(between).max() < 1e-3
    with pytest.raises(ValueError, match="at least 2"):
        solver.add_curve_on_surface(system, 1, 0, 1, follow=True)
    with pytest.raises(ValueError, match="model index 3"):
        dnurbs.curve_to_surface_distances(system, 3, 0, samples)
