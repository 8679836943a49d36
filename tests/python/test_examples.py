"""The Python examples (examples/python) run small, with checks on their numbers."""

import importlib.util

import numpy as np

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
