"""Kalman snakes from Python (Terzopoulos & Szeliski, Tracking with Kalman snakes, 1992): a
translating contour is predicted exactly, full-position and normal updates agree, and a snake
tracks a disc that moves across noisy frames."""

import numpy as np
import pytest

import dnurbs


def circle(centre, radius, count):
    t = 2 * np.pi * np.arange(count) / count
    return np.column_stack([centre[0] + radius * np.cos(t), centre[1] + radius * np.sin(t)])


def test_translation_is_exact_and_updates_agree():
    rest = circle((0.0, 0.0), 8.0, 10)
    velocity = np.tile([1.5, -0.5], (10, 1))
    snake = dnurbs.KalmanSnake(rest, rest + [20.0, 30.0], velocity, tension=0.01, rigidity=1e-5)
    for _ in range(4):
        snake.predict()
    # A translation is in the null space of the closed snake's stiffness: round-off only
    np.testing.assert_allclose(snake.positions, rest + [26.0, 28.0], atol=1e-11)
    np.testing.assert_allclose(snake.velocities, velocity, atol=1e-11)
    assert snake.covariance.shape == (40, 40)

    # Full positions, and the same as scalar measurements along x and y, give the same filter
    other = dnurbs.KalmanSnake(rest, acceleration_variance=0.01)
    coupled = dnurbs.KalmanSnake(rest, acceleration_variance=0.01)
    measured = rest + np.random.default_rng(3).normal(0.0, 0.5, rest.shape)
    other.update(measured, 0.25)
    nodes = np.repeat(np.arange(10), 2)
    normals = np.tile(np.eye(2), (10, 1))
    coupled.update_normals(nodes, normals, measured.reshape(-1), np.full(20, 0.25))
    assert other.axes_separable and not coupled.axes_separable
    np.testing.assert_allclose(coupled.positions, other.positions, atol=1e-12)
    np.testing.assert_allclose(coupled.node_covariance(4), other.node_covariance(4), atol=1e-12)


def test_tracks_a_moving_disc():
    rng = np.random.default_rng(5)
    y, x = np.mgrid[0:64, 0:64]
    snake = dnurbs.KalmanSnake(circle((24.0, 32.0), 10.0, 24), tension=3e-3, rigidity=1e-6,
                               initial_velocity_variance=9.0)
    for k in range(8):
        centre = (24.0 + 2.0 * k, 32.0)
        disc = (np.hypot(x - centre[0], y - centre[1]) <= 10.0).astype(float)
        frame = dnurbs.Image(0.2 + 0.6 * disc + rng.normal(0.0, 0.1, disc.shape))
        assert snake.track(frame, sigma=1.5, half_window=6.0) == 24
        distance = np.hypot(*(snake.positions - centre).T) - 10.0
        # The pixelated disc's edge (no coverage smoothing) is within about half a pixel
        assert np.abs(distance).max() < 1.0
    with pytest.raises(ValueError, match="frame is 64 by 64 pixels, the sequence's frames 96"):
        snake.track(frame, width=96, height=96)
    with pytest.raises(ValueError, match="unknown parameter"):
        dnurbs.KalmanSnake(circle((0, 0), 1, 5), stiffness=1.0)
