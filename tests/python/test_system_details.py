"""The rest of the System, Model, Scene and constraint bindings: offsets of stacked models,
velocities and kinetic energy, pressure and control-point forces against exact totals, force
bookkeeping, integrator counters, spline velocities, point-to-point constraints."""

import numpy as np
import pytest

import dnurbs
from conftest import SOURCE_DIR
from test_system import sheet


def test_offsets_velocities_and_kinetic_energy():
    system = dnurbs.System()
    system.add_model(sheet(count=4))
    system.add_model(sheet(count=5))
    assert system.model_count == 2
    assert system.coordinate_offset(1) == 48 and system.velocity_offset(1) == 48
    rng = np.random.default_rng(7)
    velocity = rng.standard_normal(75)
    system.set_velocities(1, velocity)
    mass = system.matrices()["mass"]
    stacked = system.velocities
    np.testing.assert_array_equal(stacked[48:], velocity)
    # (1/2) v^T M v with the same M: round-off of the sums.
    assert system.kinetic_energy() == pytest.approx(0.5 * stacked @ (mass @ stacked), rel=1e-13)
    # The model's own kinetic energy (the Model contract): the system's is their sum, exactly
    # (model 0 is at rest)
    model = system.model(1)
    assert model.kinetic_energy(qd=velocity) == system.kinetic_energy()
    assert model.kinetic_energy() == 0.0
    system.set_time(2.5)
    assert system.time == 2.5


def test_pressure_and_control_point_forces_have_exact_totals():
    system = dnurbs.System()
    model = sheet(count=5)
    model.fix_coordinate(4)
    assert 4 in model.fixed_coordinates
    system.add_model(model)
    system.add_pressure(0, 2.0)
    force = system.applied_forces().reshape(-1, 3)
    # p (x_u x x_v) over the unit square, normal +z: the basis functions sum to one, so the
    # z components add up to p times the area (Gauss quadrature, exact here).
    np.testing.assert_allclose(force.sum(axis=0), [0.0, 0.0, 2.0], atol=1e-14)
    system.clear_forces()
    assert system.force_count == 0
    system.add_control_point_force(0, [3, 7], [1.0, -2.0, 0.5])
    force = system.applied_forces().reshape(-1, 3)
    np.testing.assert_array_equal(force[[3, 7]], [[1.0, -2.0, 0.5]] * 2)
    assert np.count_nonzero(force) == 6
    spring = system.add_spring(0, [0.5, 0.5], [0, 0, 1.0], 1.0)
    assert system.spring_model(spring) == 0


def test_wind_force_has_the_exact_total_and_vanishes_with_the_wind():
    # The flat unit sheet at rest, normal +z, in a wind v: drag * area * (n . v) n in all (the
    # basis functions sum to one, the quadrature is exact); moving with the wind: nothing.
    system = dnurbs.System()
    system.add_model(sheet(count=4))
    index = system.add_wind(0, [1.0, -2.0, 3.0], drag=0.5)
    assert index == 0
    force = system.applied_forces().reshape(-1, 3)
    np.testing.assert_allclose(force.sum(axis=0), [0.0, 0.0, 1.5], atol=1e-14)
    system.set_velocities(0, np.tile([1.0, -2.0, 3.0], 16))
    np.testing.assert_allclose(system.applied_forces(), 0.0, atol=1e-14)
    system.clear_forces()
    system.add_wind(0, lambda t: np.array([0.0, 0.0, 2.0 + t]), 1.0, start=1.0)
    assert np.count_nonzero(system.applied_forces()) == 0  # before its start
    with pytest.raises(dnurbs.Error, match="-1"):
        system.add_wind(0, [1.0, 0.0, 0.0], -1.0)


def test_integrator_counters_and_spline_velocity():
    system = dnurbs.System()
    system.add_model(sheet())
    integrator = dnurbs.Integrator("newmark")
    integrator.step(system, 0.01, count=5)
    # A constant model is factored once per (dt, scheme) and stepped linearly.
    assert integrator.factorization_count == 1
    assert integrator.last_newton_iterations == 0
    path = dnurbs.TargetTrajectory.keyframes([0.0, 1.0, 2.0], [[0, 0, 0], [0, 0, 1], [0, 0, 2]])
    # The monotone default and the natural cubic spline through collinear keyframes are the line.
    np.testing.assert_allclose(path.velocity(0.5), [0, 0, 1.0], atol=1e-14)


def test_keyframe_interpolation_monotone_cubic_and_linear():
    # examples/scenes/swung_clay.json's push: -3 held for 1 s, released to 0 in 0.05 s.
    times = [0.0, 1.0, 1.05]
    push = [[-3, 0, 0], [-3, 0, 0], [0, 0, 0]]
    peak = 1.0 / np.sqrt(3.0)
    monotone = dnurbs.TargetTrajectory.keyframes(times, push)
    assert monotone(peak)[0] == -3.0  # the default holds the keyed value exactly
    assert dnurbs.TargetTrajectory.keyframes(times, push, interpolation="monotone")(0.3)[0] == -3.0
    # The natural spline's moment at t = 1 is 360 / 2.1: it reaches -3 - 400 / (21 sqrt 3)
    cubic = dnurbs.TargetTrajectory.keyframes(times, push, interpolation="cubic")
    np.testing.assert_allclose(cubic(peak)[0], -3.0 - 400.0 / (21.0 * np.sqrt(3.0)), atol=1e-12)
    linear = dnurbs.TargetTrajectory.keyframes(times, push, interpolation="linear")
    np.testing.assert_allclose(linear(1.025), [-1.5, 0, 0], atol=1e-12)
    np.testing.assert_allclose(linear.velocity(1.025), [60.0, 0, 0], rtol=1e-12)
    with pytest.raises(dnurbs.Error, match='expected "cubic", "monotone" or "linear", got "spline"'):
        dnurbs.TargetTrajectory.keyframes(times, push, interpolation="spline")


def test_point_to_point_constraint_joins_two_sheets():
    system = dnurbs.System()
    system.add_model(sheet(damping=2.0))
    shifted = sheet(damping=2.0)
    system.add_model(shifted)
    system.set_coordinates(1, system.model_coordinates(1) + [1.0, 0.0, 0.0] * 36)
    system.add_gravity(1, [0, 0, -1.0])
    # System.model gives a copy: boundary conditions set on it do not reach the system.
    system.model(0).fix_border()
    assert system.fixed_coordinates == []
    solver = dnurbs.ConstraintSolver()
    solver.add_point_to_point(system, 0, [1.0, 0.5], 1, [0.0, 0.5])
    integrator = dnurbs.Integrator("newmark")
    solver.step(integrator, system, 0.01, count=20)
    assert solver.multipliers.shape == (solver.row_count,) == (3,)
    # Baumgarte-stabilized rows started satisfied: the violation stays at round-off.
    np.testing.assert_allclose(system.position(0, [1.0, 0.5]), system.position(1, [0.0, 0.5]),
                               atol=1e-9)


def test_scene_attributes_and_checkpoint():
    scene = dnurbs.read_scene(SOURCE_DIR / "examples" / "scenes" / "curve_sculpting.json")
    assert scene.source.endswith("curve_sculpting.json")
    assert "D-NURBS curve" in scene.description
    simulation = dnurbs.SceneSimulation(scene)
    assert simulation.scene == scene
    simulation.step(3)
    checkpoint = simulation.checkpoint()
    assert checkpoint["step"] == 3 and checkpoint["scene_hash"] == scene.state_hash()
    np.testing.assert_array_equal(checkpoint["coordinates"], simulation.coordinates)
    assert simulation.sample()["probes"].shape == (1, 3)


def test_surface_knots_and_mesh_normals():
    sphere = dnurbs.sphere(1.0)
    assert sphere.knots_u.degree == 2 and sphere.knots_v.control_point_count == 9
    mesh = dnurbs.TriangleMesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]],
                               normals=[[0, 0, 1]] * 3)
    np.testing.assert_array_equal(mesh.normals, [[0, 0, 1]] * 3)


def free_weight_rod():
    """The curve_sculpting rod with free weights, ends fixed, from rest (far from equilibrium)."""
    points = np.zeros((8, 3))
    points[:, 0] = np.arange(8)
    curve = dnurbs.NurbsCurve(dnurbs.KnotVector.clamped_uniform(3, 8), points)
    rod = dnurbs.DNurbsCurve(curve, damping_density=2.0, tension=5.0, rigidity=0.5,
                             free_weights=True)
    rod.fix_point(0)
    rod.fix_point(7)
    system = dnurbs.System()
    system.add_model(rod)
    return system


def test_free_weights_iterate_newton_unless_told_not_to():
    # Default: Newton iterations for free weights (IntegratorSettings::automatic_newton); the
    # damped, force-free rod loses energy over 1 s.
    system = free_weight_rod()
    start = system.kinetic_energy() + system.potential_energy()
    integrator = dnurbs.Integrator()
    integrator.step(system, 0.01)
    assert integrator.last_newton_iterations > 0
    integrator.step(system, 0.01, count=99)
    assert system.kinetic_energy() + system.potential_energy() < start
    # automatic_newton=False: the linearly implicit step, which this start drives out of the
    # positive definite states (refused at step 16, state untouched: dnurbs.Error)
    system = free_weight_rod()
    linear = dnurbs.Integrator(automatic_newton=False)
    linear.step(system, 0.01)
    assert linear.last_newton_iterations == 0
    with pytest.raises(dnurbs.Error, match="not positive definite"):
        linear.step(system, 0.01, count=99)
    # keep_factor_across_steps=False: a factor at every step's predictor, the same steps within
    # the Newton tolerance (1e-8 of |a|)
    kept_system, fresh_system = free_weight_rod(), free_weight_rod()
    kept = dnurbs.Integrator()
    fresh = dnurbs.Integrator(keep_factor_across_steps=False)
    kept.step(kept_system, 0.01, count=40)
    fresh.step(fresh_system, 0.01, count=40)
    assert fresh.factorization_count >= 40
    assert kept.factorization_count < fresh.factorization_count
    q_kept, q_fresh = kept_system.coordinates, fresh_system.coordinates
    assert np.max(np.abs(q_kept - q_fresh)) <= 1e-7 * np.max(np.abs(q_fresh))


def test_data_forces_fit_and_track_points():
    # Points 0.3 outside a unit sphere pull it outward along their directions: the nearest
    # material points are the points' directions (Newton on difference derivatives: 1e-8)
    sphere = dnurbs.DeformableSuperquadricModel([1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0],
                                                damping_alpha=5.0)
    q = sphere.initial_coordinates()
    directions = np.array([[0.0, 0.0, 1.0], [0.6, 0.8, 0.0], [-0.48, 0.6, 0.64]])
    parameters, positions = dnurbs.nearest_material_points(sphere, q, 1.3 * directions)
    assert parameters.shape == (3, 2)
    np.testing.assert_allclose(positions, directions, atol=1e-8)
    system = dnurbs.System()
    system.add_model(sphere)
    cloud = np.vstack([directions, -directions])
    assert system.add_data_force(0, lambda t: cloud + [t, 0.0, 0.0], stiffness=500.0) == 0
    integrator = dnurbs.Integrator("implicit-euler")
    for _ in range(300):
        integrator.step(system, 0.01)
    # The sphere follows the cloud moving at v = 1 along x with the lag of a damped spring,
    # (k sum_k n_k n_k^T)^-1 alpha m v (tests/dynamics/core/test_data_force.cpp), to O(lag)
    mass = sphere.mass_properties()["mass"]
    lag = np.linalg.solve(500.0 * cloud.T @ cloud, 5.0 * mass * np.array([1.0, 0.0, 0.0]))
    centre = system.coordinates[:3]
    # (the six points are not isotropic: the lag has y and z parts as well)
    assert np.linalg.norm([system.time, 0.0, 0.0] - centre - lag) < 0.05 * np.linalg.norm(lag)
    with pytest.raises(dnurbs.Error, match="stiffness -1"):
        system.add_data_force(0, cloud, stiffness=-1.0)
    with pytest.raises(dnurbs.Error, match="points"):
        system.add_data_force(0, np.zeros((2, 2)), stiffness=1.0)
