"""dnurbs.GeneralizedSpline from Python (dynamics/grid/generalized_spline.h): the energy of order n
against its closed form, the presets' terms, weights as numbers, functions and per-stencil values,
and the massless flow (Terzopoulos, Deformable Models, eq. 1.17 and section 2.6)."""

import math

import numpy as np
import pytest

import dnurbs


def circle(n, radius=1.0):
    angles = 2 * np.pi * np.arange(n) / n
    return np.stack([radius * np.cos(angles), radius * np.sin(angles), 0 * angles], axis=1)


def test_closed_chain_energy_of_order_three_is_the_circle_integral():
    # v = (cos 2 pi s, sin 2 pi s, 0): S_3 = 1/2 sum_{m<=3} (2 pi)^(2m). The m-th difference has
    # the modulus (2 sin(pi h) / h)^m, so the m = 3 term, which dominates, is low by about
    # (pi h)^2 = 6e-4 at 128 nodes
    nodes = circle(128)
    spline = dnurbs.GeneralizedSpline(nodes, order=3, closed=True)
    exact = sum(0.5 * (2 * np.pi) ** (2 * m) for m in (1, 2, 3))
    energy = spline.potential_energy(spline.initial_coordinates())
    assert energy == pytest.approx(exact, rel=1e-3)
    assert spline.node_measure.sum() == pytest.approx(1.0, rel=1e-15)
    np.testing.assert_array_equal(spline.positions(), nodes)


def test_thin_plate_weights_as_numbers_functions_and_values_agree():
    grid = dnurbs.Grid(6, 5, 0.25)
    rest = dnurbs.flat_grid_positions(grid)
    terms = dnurbs.GeneralizedSpline.thin_plate_terms(1.0, 1.0, 0.5, 0.5, 0.5)
    assert terms == [(1, 0, 1.0), (0, 1, 1.0), (2, 0, 0.5), (1, 1, 0.5), (0, 2, 0.5)]
    plate = dnurbs.GeneralizedSpline(rest, order=2, grid=grid, terms=terms)
    by_function = dnurbs.GeneralizedSpline(
        rest, order=2, grid=grid,
        terms=[(ju, jv, (lambda u, v, w=w: w)) for ju, jv, w in terms])
    by_values = dnurbs.GeneralizedSpline(
        rest, order=2, grid=grid, terms=[(ju, jv, [w] * 30) for ju, jv, w in terms])
    k = plate.scalar_stiffness(dense=True)
    np.testing.assert_array_equal(by_function.scalar_stiffness(dense=True), k)
    np.testing.assert_array_equal(by_values.scalar_stiffness(dense=True), k)
    # Differences of a constant vanish: a translation costs no energy (rounding of 1/h^2 sums)
    np.testing.assert_allclose(k.sum(axis=1), 0, atol=1e-12 * abs(k).max())
    assert plate.node_measure.sum() == pytest.approx(1.25 * 1.0, rel=1e-15)  # the rectangle
    assert dnurbs.GeneralizedSpline.membrane_terms(2, 3.0) == [(1, 0, 3.0), (0, 1, 3.0)]
    with pytest.raises(ValueError, match=r"weight of term \(1, 0\) must have shape \(30,\)"):
        dnurbs.GeneralizedSpline(rest, order=1, grid=grid, terms=[(1, 0, [1.0] * 6)])


def test_massless_membrane_circle_shrinks_by_backward_euler():
    # gamma u_t = -K u: R_1 = R_0 / (1 + dt lambda / gamma), lambda = 4 w sin^2(pi/N) / h^2;
    # exact to rounding (1e-13)
    n, tension, gamma, dt = 16, 0.5, 2.0, 0.01
    spline = dnurbs.GeneralizedSpline(
        circle(n), closed=True, mass_density=0.0, damping_density=gamma,
        terms=dnurbs.GeneralizedSpline.membrane_terms(1, tension))
    system = dnurbs.System()
    system.add_model(spline)
    dnurbs.Integrator("implicit-euler").step(system, dt)
    lam = 4 * tension * math.sin(math.pi / n) ** 2 * n * n
    expected = circle(n, 1.0 / (1 + dt * lam / gamma))
    np.testing.assert_allclose(spline.positions(system.coordinates), expected, atol=1e-13)
    with pytest.raises(ValueError, match="newmark integrator cannot step model 0"):
        dnurbs.Integrator("newmark").step(system, dt)
    with pytest.raises(ValueError, match="gamma > 0"):
        dnurbs.GeneralizedSpline(circle(n), closed=True, mass_density=0.0)
