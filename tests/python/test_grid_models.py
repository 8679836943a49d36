"""The grid models from Python: dnurbs.Grid numbering, the Terzopoulos elastic surface's metric
tensors, energy and linearized force, the PDE surface's active nodes and quadratic energy, and the
snake's stiffness; checked against the definitions in their headers."""

import numpy as np
import pytest

import dnurbs


def test_grid_numbering_and_flat_positions():
    grid = dnurbs.Grid(3, 4, 0.5)
    assert (grid.nu, grid.nv, grid.spacing, grid.node_count) == (3, 4, 0.5, 12)
    assert grid.index(1, 2) == 7
    np.testing.assert_array_equal(grid.parameter(7), [0.5, 1.0])
    assert grid.border_nodes == [0, 1, 2, 3, 5, 6, 8, 9, 10, 11]  # all but (1, 1) and (1, 2)
    positions = dnurbs.flat_grid_positions(grid, [1, 0, 2], [0, 1, 0], [0, 0, 1])
    assert positions.shape == (12, 3)
    np.testing.assert_array_equal(positions[7], [1, 0.5, 3.0])  # origin + 0.5 y + 1.0 z
    with pytest.raises(ValueError, match="h"):
        dnurbs.Grid(3, 3, -1.0)


def sheet(nu=5, nv=4, h=0.25, **material):
    grid = dnurbs.Grid(nu, nv, h)
    rest = dnurbs.flat_grid_positions(grid)
    return grid, rest, dnurbs.TerzopoulosSurface(grid, rest, **material)


def test_terzopoulos_energy_is_the_metric_sum_of_its_tensors():
    grid, rest, surface = sheet(eta=[[1, 0], [0, 0.5]])
    assert surface.grid.node_count == 20
    np.testing.assert_array_equal(surface.rest_positions, rest)
    rest_tensors = surface.tensors()
    # The flat sheet is isometric: G = identity where a forward difference exists, B = 0.
    interior = rest_tensors["metric"][:, 0] != 0
    np.testing.assert_allclose(rest_tensors["metric"][interior][:, 0], 1, rtol=1e-15)
    np.testing.assert_array_equal(rest_tensors["curvature"], 0)
    stretched = rest * [1.2, 1, 1]
    q = stretched.reshape(-1)
    np.testing.assert_array_equal(surface.positions(q), stretched)
    metric = surface.tensors(q)["metric"]
    g0 = rest_tensors["metric"]
    # E = (h^2 / 4) sum eta_ij (G_ij - G0_ij)^2, the 12 term twice (eta_12 = 0 here).
    squares = (metric[:, 0] - g0[:, 0]) ** 2 + 0.5 * (metric[:, 2] - g0[:, 2]) ** 2
    expected = 0.25 ** 2 / 4 * squares.sum()
    assert expected > 0
    assert surface.potential_energy(q) == pytest.approx(expected, rel=1e-13)
    # Per-node weights: switching node 0 off removes its term.
    surface.set_node_elasticity(0, [[0, 0], [0, 0]], [[0, 0], [0, 0]])
    node0 = 0.25 ** 2 / 4 * (metric[0, 0] - g0[0, 0]) ** 2
    assert surface.potential_energy(q) == pytest.approx(expected - node0, rel=1e-13)


def test_terzopoulos_internal_force_is_minus_the_linearized_stiffness_times_q():
    grid, rest, surface = sheet(eta=[[1, 0.2], [0.2, 1]], xi=[[0.1, 0], [0, 0.1]])
    rng = np.random.default_rng(3)
    q = (rest + 0.05 * rng.standard_normal(rest.shape)).reshape(-1)
    stiffness = surface.linearized_stiffness(q, dense=True)
    assert stiffness.shape == (20, 20)
    expected = -(stiffness @ q.reshape(-1, 3)).reshape(-1)
    np.testing.assert_allclose(surface.internal_force(q), expected, rtol=0,
                               atol=1e-12 * np.abs(expected).max())
    assert surface.control_point_offset(7) == 21  # node i at 3 i
    np.testing.assert_array_equal(surface.advance_coordinates(q, np.ones(60)), q + 1)
    surface.set_initial_positions(q.reshape(-1, 3))
    np.testing.assert_array_equal(surface.initial_coordinates(), q)
    normals = surface.approximate_normals(rest.reshape(-1), rest.reshape(-1))
    assert len(normals) == 3 and all(n.shape == (20, 3) for n in normals)
    # Flat rest state: |B_ij| = 0 < delta, so the estimates are B_ij n = 0 (Wu & de Melo eq. 25).
    np.testing.assert_array_equal(np.abs(normals[0]), 0)
    with pytest.raises(ValueError, match="symmetric"):
        dnurbs.TerzopoulosSurface(grid, rest, eta=[[1, 1], [0, 1]])
    with pytest.raises(ValueError, match="normal is \"bent\""):
        dnurbs.TerzopoulosSurface(grid, rest, normal="bent")
    with pytest.raises(ValueError, match=r"rest must have shape \(20, 3\)"):
        dnurbs.TerzopoulosSurface(grid, rest[:5])


def test_pde_surface_energy_is_its_quadratic_form():
    grid = dnurbs.Grid(7, 7, 1 / 6)
    rest = dnurbs.flat_grid_positions(grid)
    surface = dnurbs.PdeSurface(grid, rest, tangents=[0.1, 0, 0, -0.2])
    assert surface.grid.nu == 7
    np.testing.assert_array_equal(surface.rest_positions, rest)
    assert surface.active_nodes == [i + 7 * j for j in range(1, 6) for i in range(1, 6)]
    assert surface.active_slot(0) == -1 and surface.active_slot(8) == 0
    assert surface.coordinate_count == 75
    np.testing.assert_array_equal(surface.positions(), rest)
    # The middle node (slot 12) and its 4 neighbors at h = 1/6; the diagonals are at 0.236.
    assert surface.nodes_within([0.5, 0.5, 0], 0.2) == [7, 11, 12, 13, 17]
    t = surface.tangent_force
    assert t.shape == (75,) and np.abs(t).max() > 0
    rng = np.random.default_rng(5)
    q0 = surface.initial_coordinates()
    d = 0.01 * rng.standard_normal(75)
    stiffness = surface.matrices(dense=True)["stiffness"]
    # E = 1/2 (q - r0)^T K (q - r0) - t . (q - r0) (pde_surface.h).
    assert surface.potential_energy(q0 + d) == pytest.approx(0.5 * d @ stiffness @ d - t @ d,
                                                             rel=1e-12)
    region = dnurbs.PdeSurface(grid, rest, regions=[([0.5, 0.5, 0], 0.3)])
    # The 3 x 3 nodes within 0.3 of the middle form the region; only its interior node moves.
    assert region.active_nodes == [24]
    with pytest.raises(ValueError, match="radius"):
        dnurbs.PdeSurface(grid, rest, regions=[([0.5, 0.5, 0], -1.0)])


def test_pde_surface_material_changes_in_place_and_in_a_running_system():
    grid = dnurbs.Grid(9, 9, 0.125)
    rest = dnurbs.flat_grid_positions(grid)
    surface = dnurbs.PdeSurface(grid, rest)
    # b, c, d, density, damping, su0, su1, sv0, sv1 (pde_surface.h, pde_material_parameters)
    np.testing.assert_array_equal(surface.material_parameters, [1, 2, 1, 1, 0, 0, 0, 0, 0])
    unit = surface.matrices(dense=True)["stiffness"]
    surface.set_material(b=3, c=6, d=3, damping_density=2)
    np.testing.assert_array_equal(surface.material_parameters, [3, 6, 3, 1, 2, 0, 0, 0, 0])
    # K is linear in (b, c, d): three times the unit one, to the round-off of the sums
    np.testing.assert_allclose(surface.matrices(dense=True)["stiffness"], 3 * unit,
                               rtol=0, atol=1e-13 * np.abs(unit).max())
    with pytest.raises(ValueError, match="-1"):
        surface.set_material(mass_density=-1)
    np.testing.assert_array_equal(surface.material_parameters, [3, 6, 3, 1, 2, 0, 0, 0, 0])

    # A run whose material jumps after 20 steps equals one restarted there with a new surface
    def run(first_steps):
        system = dnurbs.System()
        system.add_model(dnurbs.PdeSurface(grid, rest, damping_density=1.0))
        system.add_point_force(0, [0.5, 0.5], [0, 0, 1])
        integrator = dnurbs.Integrator("newmark")
        for _ in range(first_steps):
            integrator.step(system, 0.01)
        return system, integrator

    jumped, integrator = run(20)
    assert jumped.set_material_parameters(0, [4, 8, 4, 0.5, 3, 0, 0, 0, 0])
    assert not jumped.set_material_parameters(0, [4, 8, 4, 0.5, 3, 0, 0, 0, 0])
    for _ in range(20):
        integrator.step(jumped, 0.01)
    np.testing.assert_array_equal(jumped.model(0).material_parameters, [4, 8, 4, 0.5, 3, 0, 0, 0, 0])
    first, _ = run(20)
    restarted = dnurbs.System()
    restarted.add_model(dnurbs.PdeSurface(grid, rest, b=4, c=8, d=4, mass_density=0.5,
                                          damping_density=3))
    restarted.add_point_force(0, [0.5, 0.5], [0, 0, 1])
    restarted.set_coordinates(0, first.coordinates)
    restarted.set_velocities(0, first.velocities)
    restarted.set_time(first.time)
    integrator = dnurbs.Integrator("newmark")
    for _ in range(20):
        integrator.step(restarted, 0.01)
    moved = restarted.coordinates - rest_of(restarted)
    assert np.linalg.norm(moved) > 1e-4
    np.testing.assert_allclose(jumped.coordinates, restarted.coordinates, rtol=0,
                               atol=1e-12 * np.linalg.norm(moved))
    with pytest.raises(ValueError, match="nan"):
        jumped.set_material_parameters(0, [1, 2, np.nan, 1, 0, 0, 0, 0, 0])


def rest_of(system):
    return system.model(0).initial_coordinates()


def test_snake_stiffness_is_translation_free():
    angles = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    nodes = np.stack([np.cos(angles), np.sin(angles), 0 * angles], axis=1)
    snake = dnurbs.Snake(nodes, closed=True, tension=1.0, rigidity=[0.0] * 8)
    assert snake.closed and snake.coordinate_count == 24
    np.testing.assert_array_equal(snake.positions(), nodes)
    k = snake.scalar_stiffness(dense=True)
    # Tension only: a second difference on the cycle, rows summing to zero.
    np.testing.assert_allclose(k.sum(axis=1), 0, atol=1e-12 * abs(k[0, 0]))
    assert k[0, 0] == pytest.approx(-2 * k[0, 1], rel=1e-15) and k[0, 2] == 0 and k[0, 7] == k[0, 1]
    with pytest.raises(ValueError, match="tension"):
        dnurbs.Snake(nodes, tension=[1.0] * 3)


def test_grid_surfaces_with_a_plastic_rest_shape_keep_a_dent():
    grid = dnurbs.Grid(9, 9, 0.125)
    rest = dnurbs.flat_grid_positions(grid)
    pde = dnurbs.PdeSurface(grid, rest, damping_density=5.0)
    pde.set_plastic_flow(0.05, rate=2.0)
    system = dnurbs.System()
    system.add_model(pde)
    system.add_point_force(0, [0.5, 0.5], [0, 0, -20])
    integrator = dnurbs.Integrator("implicit-euler")
    for _ in range(40):
        integrator.step(system, 0.1)
    loaded = system.position(0, [0.5, 0.5])[2]
    system.clear_forces()
    for _ in range(600):
        integrator.step(system, 0.1)
    # The centre stays dented after the release, less deep than under the load (-0.75 and -0.64
    # in tests/dynamics/grid/test_grid_plastic_flow.cpp)
    assert loaded < system.position(0, [0.5, 0.5])[2] < 0.5 * loaded
    # The System flowed its own copy; the model here keeps its initial rest shape
    np.testing.assert_array_equal(pde.rest_coordinates, pde.initial_coordinates())
    pde.set_plastic_flow(None)
    sheet = dnurbs.TerzopoulosSurface(grid, rest, eta=[[1, 0], [0, 1]])
    sheet.set_plastic_flow(0.1, rate=3.0)
    np.testing.assert_array_equal(sheet.rest_positions, rest)
    with pytest.raises(dnurbs.Error, match="plastic rate 0"):
        sheet.set_plastic_flow(0.1, rate=0.0)


def test_unnormalized_christoffel_normal_is_the_normalized_one_times_its_length():
    # On a paraboloid the Gauss-formula estimates of the normal (Wu & de Melo, eqs 23-26): the
    # normalized variant has unit length where |B_ij| >= delta, the unnormalized one (|B_ij| = 1,
    # their figure 6) the same direction and length |B_ij|, so not 1 in general.
    grid = dnurbs.Grid(7, 7, 0.25)
    rest = dnurbs.flat_grid_positions(grid)
    bumped = rest.copy()
    bumped[:, 2] = 2.0 * ((rest[:, 0] - 0.75) ** 2 + (rest[:, 1] - 0.75) ** 2)
    q = bumped.reshape(-1)
    normalized = dnurbs.TerzopoulosSurface(grid, rest, normal="christoffel", delta=0.5)
    unnormalized = dnurbs.TerzopoulosSurface(grid, rest, normal="christoffel_unnormalized")
    estimates = zip(normalized.approximate_normals(q, q), unnormalized.approximate_normals(q, q))
    for n, u in estimates:
        lengths = np.linalg.norm(u, axis=1)
        unit = np.linalg.norm(n, axis=1)
        shown = lengths > 0.5  # where |B_ij| >= delta: the normalized estimate is a unit vector
        if not shown.any():  # B_12 = 0 on this paraboloid: both estimates vanish
            assert np.abs(n).max() == 0 and np.abs(u).max() == 0
            continue
        np.testing.assert_allclose(unit[shown], 1.0, atol=1e-12)
        np.testing.assert_allclose(np.cross(n[shown], u[shown]), 0.0, atol=1e-12)
        assert np.abs(lengths[shown] - 1.0).max() > 0.1
