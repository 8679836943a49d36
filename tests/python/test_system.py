"""Models, System, forces, springs, integrators, constraints and static equilibrium from Python:
matrices against exact integrals, Jacobians against finite differences, springs added, moved and
removed between steps, equilibria that zero the residual, constraints held."""

import json

import numpy as np
import pytest
import scipy.sparse

import dnurbs


def line_model(tension=0.0):
    knots = dnurbs.KnotVector(1, [0, 0, 1, 1])
    curve = dnurbs.NurbsCurve(knots, [[0, 0, 0], [2, 0, 0]])
    return dnurbs.DNurbsCurve(curve, mass_density=1.0, tension=tension)


def sheet(count=6, b20=0.1, damping=1.0):
    knots = dnurbs.KnotVector.clamped_uniform(3, count)
    u, v = np.meshgrid(np.linspace(0, 1, count), np.linspace(0, 1, count), indexing="ij")
    points = np.stack([u, v, np.zeros_like(u)], axis=-1).reshape(-1, 3)
    surface = dnurbs.NurbsSurface(knots, knots, points)
    model = dnurbs.DNurbsSurface(surface, damping_density=damping, a10=1.0, a01=1.0, b20=b20,
                                 b02=b20, b11=b20)
    return model


def test_points_fixed_through_the_system_hold_and_on_the_model_do_not():
    model = sheet()
    system = dnurbs.System()
    system.add_model(model)
    model.fix_border()  # a copy is in the system: no effect there
    assert system.fixed_coordinates == []
    system.fix_border(0)
    assert system.fixed_coordinates == model.fixed_coordinates
    system.add_gravity(0, [0, 0, -1])
    integrator = dnurbs.Integrator()
    for _ in range(5):
        integrator.step(system, 0.01)
    centre = 3 * (2 * 6 + 2)
    held = system.coordinates[centre:centre + 3].copy()
    assert held[2] < -1e-5
    system.fix_point(0, 14)
    for _ in range(5):
        integrator.step(system, 0.01)
    np.testing.assert_array_equal(system.coordinates[centre:centre + 3], held)
    with pytest.raises(dnurbs.Error, match="model index 2"):
        system.fix_point(2, 0)


def test_linear_curve_matrices_equal_exact_integrals():
    model = line_model(tension=3.0)
    assert model.coordinate_count == 6 and model.parametric_dimension == 1
    assert model.matrices_are_constant
    matrices = model.matrices()
    mass = matrices["mass"]
    assert scipy.sparse.issparse(mass) and mass.shape == (6, 6)
    # M = S (x) I_3 with S_ij = integral N_i N_j du = [[1/3, 1/6], [1/6, 1/3]] (exact Gauss
    # quadrature of a quadratic: round-off only).
    np.testing.assert_allclose(mass.toarray(), np.kron([[1 / 3, 1 / 6], [1 / 6, 1 / 3]],
                                                       np.eye(3)), atol=1e-15)
    # K = w1 integral N_i' N_j' du (x) I_3 = 3 [[1, -1], [-1, 1]] (x) I_3.
    np.testing.assert_allclose(model.matrices(dense=True)["stiffness"],
                               np.kron(3.0 * np.array([[1, -1], [-1, 1]]), np.eye(3)), atol=1e-14)
    # E = (1/2) w1 |P1 - P0|^2 = 6 and f_int = -K q.
    assert model.potential_energy() == pytest.approx(6.0, rel=1e-15)
    q = model.initial_coordinates()
    np.testing.assert_allclose(model.internal_force(q), -matrices["stiffness"] @ q, atol=1e-14)


def test_jacobian_dense_sparse_and_finite_differences():
    model = sheet()
    q = model.initial_coordinates() + 0.01 * np.sin(np.arange(model.coordinate_count))
    u = np.array([0.3, 0.7])
    jacobian = model.position_jacobian(q, u)
    dense = model.position_jacobian(q, u, dense=True)
    assert jacobian.shape == (3, model.velocity_count)
    np.testing.assert_array_equal(jacobian.toarray(), dense)
    # x(u) is linear in q with fixed weights: central differences are exact up to round-off
    # (1e-16 / h with h = 1e-6).
    h = 1e-6
    columns = []
    for j in range(model.coordinate_count):
        step = np.zeros(model.coordinate_count)
        step[j] = h
        columns.append((model.position(q + step, u) - model.position(q - step, u)) / (2 * h))
    np.testing.assert_allclose(np.array(columns).T, dense, atol=1e-9)
    # The generalized force of a point force is L^T f.
    force = np.array([0.5, -1.0, 2.0])
    np.testing.assert_allclose(model.point_force(q, u, force), dense.T @ force, atol=1e-15)


def test_internal_force_is_minus_energy_gradient():
    model = sheet()
    rng = np.random.default_rng(3)
    q = model.initial_coordinates() + 0.05 * rng.standard_normal(model.coordinate_count)
    h = 1e-6
    gradient = np.array([(model.potential_energy(q + h * e) - model.potential_energy(q - h * e))
                         / (2 * h) for e in np.eye(model.coordinate_count)])
    # E is quadratic: central differences are exact but for round-off E * 1e-16 / h.
    np.testing.assert_allclose(model.internal_force(q), -gradient, atol=1e-7)


def test_model_from_json_builds_every_scene_type():
    superquadric = dnurbs.model_from_json(json.dumps({
        "name": "ball", "type": "superquadric",
        "shape": {"a": 2.0, "a1": 1, "a2": 1, "a3": 1, "e1": 1, "e2": 1},
        "centre": [1, 2, 3], "parts": "global"}))
    assert isinstance(superquadric, dnurbs.Model)
    u = np.array([[0.3, 0.5], [-1.0, 2.0], [0.0, 0.0]])
    # e1 = e2 = 1 and a1 = a2 = a3 = 1: a sphere of radius a about the centre (round-off).
    np.testing.assert_allclose(np.linalg.norm(superquadric.position(None, u) - [1, 2, 3], axis=1),
                               2.0, rtol=1e-14)
    assert superquadric.exact_shape() is None
    cloth = dnurbs.model_from_json(json.dumps({
        "name": "cloth", "type": "terzopoulos_surface",
        "grid": {"nodes": [4, 4], "spacing": 0.5},
        "material": {"eta": [[5, 0], [0, 5]]}, "boundary": {"fixed_points": [0, 3]}}))
    assert cloth.coordinate_count == 48 and cloth.fixed_coordinates == [0, 1, 2, 9, 10, 11]
    with pytest.raises(dnurbs.Error, match="model_from_json: models\\[0\\]"):
        dnurbs.model_from_json('{"name": "x", "type": "no_such_model"}')


def test_springs_added_moved_and_removed_between_steps():
    model = sheet(damping=4.0)
    model.fix_border()
    system = dnurbs.System()
    assert system.add_model(model) == 0
    integrator = dnurbs.Integrator("implicit-euler")
    start = system.position(0, [0.5, 0.5])
    target = start + [0, 0, 1.0]
    spring = system.add_spring(0, [0.5, 0.5], target, 50.0)
    integrator.step(system, 0.05, count=20)
    lifted = system.position(0, [0.5, 0.5])
    assert lifted[2] > 0.1  # pulled toward z = 1
    # Moving the spring to pull down: the point goes below its rest height.
    system.move_spring(spring, [0.5, 0.5], start - [0, 0, 1.0], 50.0)
    state = system.spring_state(spring)
    np.testing.assert_array_equal(state["target"], start - [0, 0, 1.0])
    integrator.step(system, 0.05, count=40)
    assert system.position(0, [0.5, 0.5])[2] < -0.1
    system.remove_spring(spring)
    assert not system.has_spring(spring)
    assert system.spring_energy() == 0.0
    with pytest.raises(dnurbs.Error, match=str(spring)):
        system.remove_spring(spring)
    # A second spring gets a new id.
    assert system.add_spring(0, [0.2, 0.2], start, 1.0) == spring + 1


def test_keyframed_spring_target_is_evaluated_in_cpp():
    path = dnurbs.TargetTrajectory.keyframes([0.0, 1.0, 2.0], [[0, 0, 0], [0, 0, 1], [0, 0, 0]])
    np.testing.assert_array_equal(path(1.0), [0, 0, 1])
    np.testing.assert_array_equal(path(5.0), [0, 0, 0])  # rests after the last keyframe
    system = dnurbs.System()
    system.add_model(sheet())
    spring = system.add_spring(0, [0.5, 0.5], path, 10.0)
    np.testing.assert_array_equal(system.spring_state(spring, 1.0)["target"], [0, 0, 1])
    python_target = system.add_spring(0, [0.5, 0.5], lambda t: path(t), 10.0)
    np.testing.assert_array_equal(system.spring_state(python_target, 0.5)["target"], path(0.5))


def test_static_equilibrium_zeroes_the_residual():
    model = sheet()
    model.fix_border()
    system = dnurbs.System()
    system.add_model(model)
    system.add_point_force(0, [0.5, 0.5], [0.0, 0.0, 1.0])
    system.add_spring(0, [0.3, 0.6], [0.3, 0.6, -0.2], 5.0)
    dnurbs.solve_static_equilibrium(system)
    q = system.coordinates
    residual = system.applied_forces() + system.model(0).internal_force(q)
    free = np.setdiff1d(np.arange(q.size), system.fixed_coordinates)
    # One sparse Cholesky solve: round-off relative to the force scale (1).
    np.testing.assert_allclose(residual[free], 0, atol=1e-11)
    assert system.position(0, [0.5, 0.5])[2] > 0


def test_gravity_and_integrator_errors():
    system = dnurbs.System()
    system.add_model(line_model(tension=1.0))
    system.add_gravity(0, [0, 0, -9.81])
    integrator = dnurbs.Integrator("newmark")
    assert integrator.scheme == "newmark"
    with pytest.raises(dnurbs.Error, match="dt"):
        integrator.step(system, -0.1)
    integrator.step(system, 0.01)
    # A free line under gravity from rest: after one Newmark step, z = -g dt^2 / 2 (uniform
    # acceleration, exact for the average-acceleration scheme; round-off).
    np.testing.assert_allclose(system.coordinates[2::3], -9.81 * 0.01 ** 2 / 2, rtol=1e-12)
    with pytest.raises(ValueError, match="implicit|newmark|central"):
        dnurbs.Integrator("leapfrog")


def test_control_point_constraint_is_held():
    model = sheet(damping=2.0)
    system = dnurbs.System()
    system.add_model(model)
    system.add_gravity(0, [0, 0, -1.0])
    solver = dnurbs.ConstraintSolver()
    corner = system.model_coordinates(0)[:3]
    solver.add_control_point(system, 0, 0, corner)
    solver.add_point_target(system, 0, [1.0, 1.0], dnurbs.TargetTrajectory.fixed([1.0, 1.0, 0.0]))
    assert solver.constraint_count == 2 and solver.row_count == 6
    integrator = dnurbs.Integrator("newmark")
    solver.step(integrator, system, 0.01, count=50)
    # Baumgarte stabilization holds the rows to a small violation (the drift it corrects each
    # step is O(dt^2) of the acceleration error, here round-off).
    assert solver.violations(system).max() < 1e-8
    assert system.position(0, [0.5, 0.5])[2] < -1e-3  # the rest sags under gravity
    assert solver.last_report()["rank"] == 6


def test_errors_in_python_force_functions_propagate():
    def failing(time):
        raise ZeroDivisionError("from the force function")

    for bad, error, message in [(failing, ZeroDivisionError, "from the force function"),
                                (lambda t: [1.0, 2.0], dnurbs.Error,
                                 "force\\(t\\) must have shape \\(3,\\), got \\(2,\\)"),
                                (lambda t: [np.nan, 0.0, 0.0], dnurbs.Error, "nan")]:
        system = dnurbs.System()
        system.add_model(sheet())
        system.add_point_force(0, [0.5, 0.5], bad)
        before = system.coordinates
        with pytest.raises(error, match=message):
            dnurbs.Integrator().step(system, 0.01)
        np.testing.assert_array_equal(system.coordinates, before)  # the state is untouched
    system = dnurbs.System()
    system.add_model(sheet())
    system.add_spring(0, [0.5, 0.5], lambda t: [np.nan, 0.0, 0.0], 1.0)
    with pytest.raises(dnurbs.Error, match="spring 0 at t = 0: target \\(nan, 0, 0\\) is not finite"):
        dnurbs.Integrator().step(system, 0.01)


def test_a_sphere_with_its_initial_shape_as_rest_feels_no_force():
    surface = dnurbs.sphere(1.0)
    at_rest = dnurbs.DNurbsSurface(surface, a10=1.0, a01=1.0, b20=0.1, b11=0.1, b02=0.1,
                                   initial_shape_at_rest=True)
    from_zero = dnurbs.DNurbsSurface(surface, a10=1.0, a01=1.0, b20=0.1, b11=0.1, b02=0.1)
    q = at_rest.initial_coordinates()
    assert at_rest.has_rest_shape and not from_zero.has_rest_shape
    assert np.abs(at_rest.internal_force(q)).max() < 1e-13
    assert np.abs(from_zero.internal_force(q)).max() > 0.1
    # Any state can be the rest shape; the energy is that of the change from it
    moved = q + 0.01 * np.sin(np.arange(q.size))
    from_zero.set_rest_shape(moved)
    # Fixed weights: E is expanded about the initial state, E(q0) + d.K(q0 - q_r) + d.K d / 2,
    # which cancels to round-off of E(q0) at the rest shape.
    assert abs(from_zero.potential_energy(moved)) < 1e-12 * from_zero.potential_energy(q)
    change = q - moved
    stiffness = from_zero.matrices(q)["stiffness"]
    np.testing.assert_allclose(from_zero.potential_energy(q), 0.5 * change @ (stiffness @ change),
                               rtol=1e-12)
    with pytest.raises(dnurbs.Error, match="rest shape: coordinate 2 is nan"):
        bad = moved.copy()
        bad[2] = np.nan
        from_zero.set_rest_shape(bad)
    curve = dnurbs.DNurbsCurve(dnurbs.full_circle(1.0), tension=1.0, initial_shape_at_rest=True)
    assert curve.has_rest_shape
    assert np.abs(curve.internal_force(curve.initial_coordinates())).max() < 1e-13
    curve.set_rest_shape(curve.initial_coordinates() + 0.1)  # a translated circle: no force
    assert np.abs(curve.internal_force(curve.initial_coordinates())).max() < 1e-13
    np.testing.assert_array_equal(curve.rest_coordinates, curve.initial_coordinates() + 0.1)
    curve.set_plastic_flow(0.5, rate=2.0)  # keeps the rest shape it has
    np.testing.assert_array_equal(curve.rest_coordinates, curve.initial_coordinates() + 0.1)


def test_a_plastic_rest_shape_keeps_a_dent():
    knots = dnurbs.KnotVector.clamped_uniform(3, 6)
    u, v = np.meshgrid(dnurbs.greville_abscissae(knots), dnurbs.greville_abscissae(knots),
                       indexing="ij")
    sheet = dnurbs.NurbsSurface(knots, knots,
                                np.stack([u, v, np.zeros_like(u)], axis=-1).reshape(-1, 3))
    model = dnurbs.DNurbsSurface(sheet, damping_density=3.0, a10=1.0, a01=1.0, b20=0.1,
                                 b11=0.1, b02=0.1)
    assert model.rest_coordinates.size == 0
    model.set_plastic_flow(0.01, rate=4.0)
    np.testing.assert_array_equal(model.rest_coordinates, model.initial_coordinates())
    system = dnurbs.System()
    system.add_model(model)
    system.fix_border(0)
    system.add_point_force(0, [0.5, 0.5], [0, 0, -3])
    integrator = dnurbs.Integrator()
    for _ in range(30):
        integrator.step(system, 0.05)
    system.clear_forces()
    for _ in range(300):
        integrator.step(system, 0.5)
    # The centre stays dented after the release; without the flow it springs back
    assert system.position(0, [0.5, 0.5])[2] < -1e-3
    model.set_plastic_flow(None)
    with pytest.raises(dnurbs.Error, match="plastic yield -1"):
        model.set_plastic_flow(-1.0)
