"""The Python examples (examples/python) run small, with checks on their numbers."""

import importlib.util

import numpy as np
import pytest

import dnurbs
from conftest import SOURCE_DIR


def load(name):
    spec = importlib.util.spec_from_file_location(name, SOURCE_DIR / "examples" / "python"
                                                  / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_sculpting_lifts_the_handles_and_exports_obj_and_gltf(tmp_path):
    result = load("sculpting").sculpt(tmp_path, count=7, steps=60)
    high, wave = result["heights"]
    # The first handle's target ends at z = 0.4 and the second's at 0.25; springs of stiffness
    # 40 against the sheet's tension hold each point part of the way up.
    assert 0.05 < high < 0.4
    assert 0.02 < wave < 0.25
    assert np.all(result["energies"][:, 1] >= 0)
    obj, gltf = result["paths"]
    assert obj.exists() and gltf.exists() and (tmp_path / "sheet.bin").exists()
    for path in (obj, gltf):
        meshes = dnurbs.import_meshes(path)
        assert len(meshes) == 1
        # assimp may reorder the vertices; their bounding box is the sheet's.
        np.testing.assert_allclose(meshes[0].vertices.min(axis=0),
                                   result["mesh"].vertices.min(axis=0), atol=1e-6)
        np.testing.assert_allclose(meshes[0].vertices.max(axis=0),
                                   result["mesh"].vertices.max(axis=0), atol=1e-6)
    assert isinstance(result["surface"], dnurbs.NurbsSurface)


def test_energy_sweep_conserves_without_damping_and_decays_with_it(tmp_path):
    plot = tmp_path / "sweep.png"
    example = load("energy_sweep")
    histories = example.sweep([0.0, 2.0], plot, steps=200)
    time, kinetic, elastic = histories[0.0]
    total = kinetic + elastic
    assert time.shape == (201,) and abs(time[-1] - 1.0) < 1e-12
    # Newmark's average acceleration conserves the energy of an undamped linear model up to
    # the round-off of the solves (measured: 9e-16 relative over 200 steps).
    np.testing.assert_allclose(total, total[0], rtol=1e-12)
    damped = histories[2.0][1] + histories[2.0][2] - example.STRAIGHT_ENERGY
    assert np.all(np.diff(damped) <= 1e-12)  # never gains energy (round-off of the sums)
    # D = (gamma / mu) M: every mode's energy decays as exp(-gamma t / mu) = exp(-2) at t = 1;
    # the scheme's error in the decay is second order in dt (measured: 0.135314 against
    # 0.135335), bounded here by 1e-3 relative.
    assert abs(damped[-1] / damped[0] - np.exp(-2.0)) < 1e-3 * np.exp(-2.0)
    assert plot.stat().st_size > 1000 and plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_point_cloud_fit_reaches_the_dome():
    example = load("fit_point_cloud")
    points = example.dome_points(count=15)
    surface, result = example.fit(points)
    # The dome z = 0.3 (1 - x^2 - y^2) over the flat start's linear parametrization is a
    # polynomial of degree 2 in (u, v): the bicubic reproduces it, the points sit at their own
    # parameters, and the errors are round-off (measured: rms 8e-16, max 4e-15).
    assert result["rms_error"] < 1e-13
    assert result["max_error"] < 1e-13
    assert result["parameters"].shape == (225, 2)
    np.testing.assert_allclose(surface(0.5, 0.5), [0.0, 0.0, 0.3], atol=1e-13)


def test_topology_adaptive_models_merge_wrap_a_ring_grow_vessels_and_find_a_torus(tmp_path):
    example = load("topology_adaptive")
    results = example.run(tmp_path, small=True)

    # (a) Two T-snakes seeded in the overlapping discs touch and merge into one outer contour.
    discs = results["discs"]
    assert discs["initial_contours"] == 2 and discs["contours"] == 1
    assert discs["orientations"] == ["counter-clockwise"]
    assert [count for _, count in discs["contour_count_changes"]] == [1]
    # The nodes rest where the coverage image, bilinear, crosses the threshold 1/2: on the
    # discs' edge to a fraction of a pixel. 0.1 px along the outline (perimeter 169 px) bounds
    # the area error by 17 px^2 (measured: 1567.2 against the image's 1569.3).
    assert abs(discs["enclosed_area"] - discs["object_area"]) < 0.1 * 169

    # (b) The ring: the snake meets itself around the hole and ends as an outer boundary
    # (counter-clockwise) and a hole (clockwise).
    ring = results["ring"]
    assert ring["initial_contours"] == 1 and ring["contours"] == 2
    assert sorted(ring["orientations"]) == ["clockwise", "counter-clockwise"]
    outer, hole = sorted(ring["signed_areas"], reverse=True)
    # The same 0.1 px along both circles (perimeter 2 pi (26 + 12) = 239 px) bounds the error
    # of the enclosed area against the annulus pi (26^2 - 12^2) = 1671.3 by 24 px^2 (measured:
    # 1673.0), and of each circle's area by 0.1 px times its perimeter.
    assert abs(ring["enclosed_area"] - np.pi * (26**2 - 12**2)) < 0.1 * 2 * np.pi * (26 + 12)
    assert abs(outer - np.pi * 26**2) < 0.1 * 2 * np.pi * 26
    assert abs(-hole - np.pi * 12**2) < 0.1 * 2 * np.pi * 12

    # (c) One snake grows from the root through the noisy tree (noise sigma 0.05 against a
    # contrast of 0.8): one component that covers the tree's pixels (coverage >= 1/2) but for
    # a few at the twigs' tips (measured: 99.4%) and takes in few background pixels, on the
    # outline where the noise moves the threshold crossing (measured: 16 of 1365).
    vessels = results["vessels"]
    assert vessels["contours"] == 1 and vessels["orientations"] == ["counter-clockwise"]
    assert vessels["tree_fraction_covered"] > 0.97
    assert vessels["background_pixels_inside"] < 0.03 * vessels["tree_pixels"]

    # (d) T-surfaces: a closed, oriented manifold of one component, chi = 0 in the torus
    # (genus 1) and 2 in the ball (genus 0). The flat triangles cut inside the curved surface:
    # the volume is a few percent small (measured on cells of 2 voxels: torus -2.8%, ball -2.1%).
    for name, chi in (("torus", 0), ("sphere", 2)):
        surface = results[name]
        assert surface["closed_manifold"] and surface["components"] == 1
        assert surface["euler_characteristic"] == chi
        assert 0.94 < surface["enclosed_volume"] / surface["object_volume"] < 1.0
        # The seed ball (chi = 2) grows around the tube and closes on itself: chi changes once
        # in the torus (measured at step 149 of 194), never in the ball.
        assert (surface["euler_characteristic_changed_at"] is None) == (name == "sphere")
        # The OBJ keeps the mesh's topology (assimp writes shared vertices).
        mesh = dnurbs.import_meshes(surface["obj"])[0]
        assert example.mesh_topology(mesh.triangles, mesh.vertex_count)["euler_characteristic"] \
            == chi

    assert len(results["pictures"]) == 5
    for picture in results["pictures"]:
        assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert 5_000 < picture.stat().st_size < 100_000


def test_topology_adaptive_mesh_check_tells_closed_from_open_and_pinched():
    example = load("topology_adaptive")
    tetrahedron = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
    corners = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    closed = example.mesh_topology(tetrahedron, 4)
    assert closed["closed_manifold"] and closed["euler_characteristic"] == 2
    assert example.enclosed_volume(corners, tetrahedron) == pytest.approx(1 / 6, rel=1e-15)
    assert not example.mesh_topology(tetrahedron[:3], 4)["closed_manifold"]  # open
    flipped = tetrahedron.copy()
    flipped[:2] = flipped[:2, ::-1]  # closed, but two faces turned inside out
    assert not example.mesh_topology(flipped, 4)["closed_manifold"]
    two = example.mesh_topology(np.vstack([tetrahedron, tetrahedron + 4]), 8)
    assert two["closed_manifold"] and two["components"] == 2
    # Two tetrahedra sharing vertex 0: every edge has two triangles, but two fans at vertex 0.
    pinched = np.vstack([tetrahedron, np.where(tetrahedron == 0, 0, tetrahedron + 3)])
    assert not example.mesh_topology(pinched, 7)["closed_manifold"]


def test_kalman_snake_tracks_the_generated_ellipse_sequence(tmp_path):
    result = load("kalman_tracking").track(tmp_path, picture=False)
    # Every node finds an edge along its normal in each of the 20 frames, and the tracked contour
    # stays within a pixel of the true ellipse in every frame (measured: 0.27-0.86 px; the noise
    # of sigma 0.15 on a step of 0.6 and the 8-bit frames move the edges by a fraction of a pixel)
    assert result["edges"].shape == (20,) and (result["edges"] == result["nodes"]).all()
    assert result["largest"].max() < 1.0
