"""The vision kernel from Python: images and volumes as NumPy arrays and files, Gaussian kernels,
edge potentials of ramps (P = -c |slope| away from the borders), contour geometry, T-snakes and
T-surfaces that find a bright disk and ball, and image forces on a snake."""

import numpy as np
import pytest

import dnurbs


def disk_image(width=40, height=30, centre=(20, 15), radius=8.0):
    y, x = np.mgrid[0:height, 0:width]
    return (np.hypot(x - centre[0], y - centre[1]) <= radius).astype(float)


def test_images_round_trip_through_arrays_and_files(tmp_path):
    pixels = np.arange(600).reshape(20, 30) % 256 / 255.0
    image = dnurbs.Image(pixels)
    assert (image.width, image.height) == (30, 20)
    np.testing.assert_array_equal(image.pixels, pixels)
    np.testing.assert_array_equal(dnurbs.Image(np.asfortranarray(pixels)).pixels, pixels)
    np.testing.assert_array_equal(dnurbs.Image(np.repeat(pixels, 2, axis=1)[:, ::2]).pixels,
                                  pixels)
    for name, write in [("a.png", dnurbs.write_png), ("a.pgm", dnurbs.write_pgm)]:
        write(image, str(tmp_path / name), 8)
        # 8-bit files hold k / 255 exactly: the read value is the same double.
        np.testing.assert_array_equal(dnurbs.read_image(str(tmp_path / name)).pixels, pixels)
    with pytest.raises(ValueError, match="bit"):
        dnurbs.write_png(image, str(tmp_path / "b.png"), 12)
    with pytest.raises(ValueError, match="pixels must have shape"):
        dnurbs.Image(np.zeros(5))
    voxels = np.arange(24.0).reshape(4, 3, 2) / 7
    volume = dnurbs.Volume(voxels)
    assert volume.size == [2, 3, 4]
    np.testing.assert_array_equal(volume.voxels, voxels)
    np.testing.assert_array_equal(volume.spacing, [1, 1, 1])
    dnurbs.write_nrrd(volume, str(tmp_path / "v.nrrd"))
    # Raw doubles: an exact round trip.
    np.testing.assert_array_equal(dnurbs.read_nrrd(str(tmp_path / "v.nrrd")).voxels, voxels)
    slices = dnurbs.read_volume_slices([str(tmp_path / "a.png"), str(tmp_path / "a.pgm")])
    np.testing.assert_array_equal(slices.voxels, np.stack([pixels, pixels]))


def test_gaussian_kernel_smoothing_and_edge_potential_of_a_ramp():
    kernel = dnurbs.gaussian_kernel(1.0)
    assert kernel.shape == (11,) and kernel.sum() == pytest.approx(1.0, rel=1e-15)
    constant = dnurbs.gaussian_smooth(dnurbs.Image(np.full((10, 12), 0.25)), 2.0)
    np.testing.assert_allclose(constant.pixels, 0.25, rtol=1e-15)
    x = np.arange(30.0)
    ramp = dnurbs.Image(np.tile(0.1 * x, (20, 1)))
    potential = dnurbs.image_edge_potential(ramp, 1.0, 2.0)
    # Away from the borders (> 5 sigma) the smoothed ramp is the ramp and |grad| = 0.1, so
    # P = -2 * 0.1; the derivative kernel is exact on linear data (round-off only).
    points = np.array([[8.0, 7.0], [12.5, 9.25], [20.0, 12.0]])
    np.testing.assert_allclose(potential.value(points), -0.2, rtol=1e-12)
    np.testing.assert_allclose(potential.gradient(points), 0, atol=1e-12)
    np.testing.assert_allclose(potential.smoothed_intensity(points), 0.1 * points[:, 0], rtol=1e-12)
    z, y, x3 = np.mgrid[0:14, 0:14, 0:14]
    volume = dnurbs.Volume(0.05 * z)
    vpotential = dnurbs.volume_edge_potential(volume, 1.0)
    np.testing.assert_allclose(vpotential.value([[7.0, 7.0, 7.0]]), [-0.05], rtol=1e-12)
    assert vpotential.gradient([7.0, 7.0, 7.0]).shape == (3,)
    assert vpotential.smoothed_intensity([6.5, 7, 7]) == pytest.approx(0.05 * 7, rel=1e-12)
    with pytest.raises(ValueError, match="sigma"):
        dnurbs.image_edge_potential(ramp, -1.0)


def test_contour_geometry():
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
    assert dnurbs.signed_area(square) == 1.0
    assert dnurbs.signed_area(square[::-1]) == -1.0
    assert dnurbs.winding_number([square], [0.5, 0.5]) == 1
    assert dnurbs.winding_number([square, square + 3], [3.5, 3.5]) == 1
    assert dnurbs.winding_number([square], [2.0, 0.5]) == 0
    assert dnurbs.contours_intersect([square, square + 0.5])
    assert not dnurbs.contours_intersect([square, square + 3])


def test_t_snake_finds_a_bright_disk():
    image = dnurbs.Image(disk_image())
    snake = dnurbs.TSnake(image, sigma=1.0, cell_size=1.0, threshold=0.5, inflation=1.0)
    snake.add_circle([20, 15], 3.0)
    assert len(snake.contours) == 1 and snake.contours[0].shape == (snake.contours[0].shape[0], 2)
    assert snake.intensity([20, 15]) == 1.0 and snake.intensity([2, 2]) == 0.0
    steps = snake.run(400)
    assert steps == snake.steps_taken and 0 < steps <= 400
    # The disk of radius 8 is a binary image: its edge is known to a pixel (+-0.5 px about the
    # radius, the pixel quantization), so the nodes stop within 8 +- 0.6 (measured 7.42..8.47)
    # and the area within 2 pi r 0.5 of pi r^2 (measured 196.9 against 201.1).
    contour = snake.contours[0]
    radii = np.linalg.norm(contour - [20, 15], axis=1)
    assert np.abs(radii - 8).max() <= 0.6
    assert abs(snake.enclosed_area - np.pi * 64) <= 2 * np.pi * 8 * 0.5
    assert snake.node_forces(contour).shape == contour.shape
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
    np.testing.assert_allclose(dnurbs.TSnake.outward_normals(square)[0],
                               [-np.sqrt(0.5), -np.sqrt(0.5)], atol=1e-15)
    snake.add_contour(square * 4 + [2, 2])
    assert len(snake.contours) == 2
    snake.remove_contour(1)
    assert len(snake.contours) == 1
    snake.step()
    with pytest.raises(ValueError, match="unknown parameter \"tensile\""):
        dnurbs.TSnake(image, tensile=1.0)


def test_t_surface_finds_a_bright_ball():
    z, y, x = np.mgrid[0:16, 0:16, 0:16]
    ball = (np.sqrt((x - 8.0) ** 2 + (y - 8.0) ** 2 + (z - 8.0) ** 2) <= 5.0).astype(float)
    surface = dnurbs.TSurface(dnurbs.Volume(ball), sigma=1.0, cell_size=1.0)
    surface.add_sphere([8, 8, 8], 2.0)
    assert surface.intensity([8, 8, 8]) == 1.0
    surface.step()
    surface.run(200)
    radii = np.linalg.norm(surface.mesh.vertices - 8.0, axis=1)
    # The binary ball of radius 5 voxels: every vertex within the voxel quantization, 5 +- 0.5
    # (measured 4.62..5.39, mean 4.95).
    assert np.abs(radii - 5.0).max() <= 0.5
    assert surface.vertex_forces().shape == surface.mesh.vertices.shape


def test_image_force_pulls_a_snake_to_an_edge():
    pixels = disk_image()
    potential = dnurbs.image_potential(pixels, 1.0, 1.0)
    assert potential(20.0, 15.0) == pytest.approx(0.0, abs=1e-12)  # flat inside the disk
    assert potential(28.0, 15.0) < -0.1  # on the edge |grad| is large
    angles = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    nodes = np.column_stack([20 + 6 * np.cos(angles), 15 + 6 * np.sin(angles), 0 * angles])
    system = dnurbs.System()
    system.add_model(dnurbs.Snake(nodes, closed=True, tension=0.1))
    assert dnurbs.add_image_force(system, 0, pixels, 1.0) == 0
    force = system.applied_forces().reshape(-1, 3)
    # Inside the edge the force -grad P points outward (toward the edge) at every node.
    radial = np.einsum("ij,ij->i", force[:, :2], nodes[:, :2] - [20, 15])
    assert (radial > 0).all() and np.abs(force[:, 2]).max() == 0


def test_edge_force_is_minus_the_gradient_in_model_space():
    # The image placed with pixel (x, y) at origin + pixel_size * (x, y): the force at each node is
    # -grad_p P / pixel_size at the node's pixel (the chain rule), with no z component.
    potential = dnurbs.image_edge_potential(dnurbs.Image(disk_image()), 1.5, 2.0)
    origin, size = np.array([-1.0, 0.5, 0.0]), 0.1
    angles = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    pixels = np.column_stack([20 + 7.5 * np.cos(angles), 15 + 7.5 * np.sin(angles)])
    nodes = np.column_stack([origin[:2] + size * pixels, 0 * angles])
    system = dnurbs.System()
    system.add_model(dnurbs.Snake(nodes, closed=True, tension=0.1))
    assert dnurbs.add_edge_force(system, 0, potential, origin=origin, pixel_size=size) == 0
    force = system.applied_forces().reshape(-1, 3)
    # (the node positions round-trip through the frame to the pixels up to round-off)
    np.testing.assert_allclose(force[:, :2], -potential.gradient(pixels) / size, rtol=1e-10,
                               atol=1e-12)
    assert np.abs(force[:, 2]).max() == 0 and np.abs(force).max() > 0.1
    # A volume's force has all three components; pixel_size may differ per axis.
    ball = np.zeros((12, 12, 12))
    z, y, x = np.mgrid[0:12, 0:12, 0:12]
    ball[(x - 6) ** 2 + (y - 6) ** 2 + (z - 6) ** 2 <= 16] = 1.0
    volume = dnurbs.volume_edge_potential(dnurbs.Volume(ball), 1.0)
    voxels = np.column_stack([6 + 4 * np.cos(angles), 6 + 4 * np.sin(angles), 7.5 + 0 * angles])
    nodes = voxels * [0.5, 0.5, 1.0]
    system = dnurbs.System()
    system.add_model(dnurbs.Snake(nodes, closed=True, tension=0.1))
    dnurbs.add_edge_force(system, 0, volume, pixel_size=(0.5, 0.5, 1.0))
    force = system.applied_forces().reshape(-1, 3)
    np.testing.assert_allclose(force, -volume.gradient(voxels) / [0.5, 0.5, 1.0], rtol=1e-10,
                               atol=1e-12)
    assert np.abs(force[:, 2]).min() > 1e-3
    with pytest.raises(dnurbs.Error, match="spacing x = 0"):
        dnurbs.add_edge_force(system, 0, volume, pixel_size=0.0)
