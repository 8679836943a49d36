"""Scenes from Python: the same scene stepped by a Python loop and by the C++ command `dnurbs run`
(and by the library's run_scene) ends in bit-identical coordinates and log rows; runs write their
output files, which read back as NumPy arrays; bad scenes and diverging runs raise."""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import dnurbs
from conftest import BINARY_DIR, SOURCE_DIR

SCENES = SOURCE_DIR / "examples" / "scenes"
TOOL = pathlib.Path(os.environ.get("DNURBS_TOOL", BINARY_DIR / "tools" / "dnurbs"))


def shortened_scene(name, steps, folder):
    """The example scene `name` run for `steps` steps, written into `folder`."""
    scene = json.loads((SCENES / f"{name}.json").read_text())
    scene["run"] = {"steps": steps}
    scene["output"]["preview"] = False
    path = folder / f"{name}.json"
    path.write_text(json.dumps(scene))
    # The scan that fit_and_sculpt fits, beside the copy of the scene.
    (folder / "dome_scan.xyz").write_bytes((SCENES / "dome_scan.xyz").read_bytes())
    return path


# fit_and_sculpt: a fitted D-NURBS surface pulled by a keyframed spring; swung_egg: a swung
# D-NURBS surface and a spring; snake_contour: a snake with a spring and a control point force.
@pytest.mark.parametrize("name, steps", [("curve_sculpting", 120), ("constraints", 40),
                                         ("cloth_terzopoulos", 20), ("fit_and_sculpt", 30),
                                         ("swung_egg", 10), ("snake_contour", 20)])
def test_python_loop_equals_cpp_command_bit_for_bit(name, steps, tmp_path):
    if not TOOL.exists():
        pytest.skip(f"the dnurbs command is not built ({TOOL})")
    path = shortened_scene(name, steps, tmp_path)
    subprocess.run([str(TOOL), "run", str(path), "--out", str(tmp_path / "cpp"), "--no-preview"],
                   check=True, capture_output=True)
    expected = dnurbs.read_checkpoint(tmp_path / "cpp" / "checkpoint.json")
    simulation = dnurbs.SceneSimulation(dnurbs.read_scene(path))
    for _ in range(steps):
        simulation.step()
    assert expected["step"] == simulation.steps_done == steps
    # Bit for bit: the same library calls in the same order (the checkpoint's doubles are
    # written with 17 significant digits and read back exactly).
    np.testing.assert_array_equal(simulation.coordinates, expected["coordinates"])
    np.testing.assert_array_equal(simulation.velocities, expected["velocities"])
    assert simulation.time == expected["time"]
    columns, log = dnurbs.read_log(tmp_path / "cpp" / "log.csv")
    sample = simulation.sample()
    assert columns[:4] == ["step", "time", "kinetic_energy", "potential_energy"]
    np.testing.assert_array_equal(log[-1, :4], [steps, sample["time"], sample["kinetic_energy"],
                                                sample["potential_energy"]])


def test_python_loop_equals_library_run_and_outputs_read_back(tmp_path):
    path = shortened_scene("curve_sculpting", 100, tmp_path)
    scene = dnurbs.read_scene(path)
    assert scene.step_count == 100 and scene.dt == 0.01 and scene.scheme == "central"
    assert scene.model_names == ["rod"] and scene.model_types == ["dnurbs_curve"]
    stepped = dnurbs.SceneSimulation(scene)
    stepped.step(100)
    ran = dnurbs.SceneSimulation(scene)
    progress = []
    result = ran.run(tmp_path / "out",
                     progress=lambda step, total, time, energy: progress.append((step, energy)))
    assert result["steps_done"] == 100 and not result["diverged"]
    assert [step for step, _ in progress] == list(range(1, 101))
    assert result["final_meshes"] == [result["final_mesh"]]
    np.testing.assert_array_equal(ran.coordinates, stepped.coordinates)
    checkpoint = dnurbs.read_checkpoint(result["checkpoint"])
    np.testing.assert_array_equal(checkpoint["coordinates"], stepped.coordinates)
    columns, log = dnurbs.read_log(result["log"])
    assert log.shape == (101, len(columns))  # step 0 and every step (log_every 1)
    assert columns[1:] == stepped.log_columns
    np.testing.assert_array_equal(log[:, 0], np.arange(101))
    # The energy the callback saw is the log's total_energy at that step
    total = columns.index("total_energy")
    np.testing.assert_array_equal([energy for _, energy in progress], log[1:, total])
    # The probe "middle" at u = 0.5: its logged position is the curve's point there.
    probe = [columns.index(f"middle_{axis}") for axis in "xyz"]
    shape = stepped.shape(0)
    np.testing.assert_allclose(log[-1, probe], shape(0.5), rtol=0, atol=1e-15)
    meshes = dnurbs.import_meshes(result["final_mesh"])
    assert len(meshes) == 1 and meshes[0].vertex_count > 0
    frames = sorted((tmp_path / "out" / "frames").iterdir())
    # mesh_every 50: frames at steps 0, 50 and 100 (an OBJ and its MTL each).
    assert result["frames_written"] == 3
    assert len([frame for frame in frames if frame.suffix == ".obj"]) == 3


def test_state_shapes_and_meshes_of_a_curve_scene(tmp_path):
    simulation = dnurbs.SceneSimulation(
        dnurbs.read_scene(shortened_scene("curve_sculpting", 10, tmp_path)))
    q = simulation.coordinates
    assert q.shape == (24,) and q.dtype == np.float64
    # Fixed weights: q = [P_0, P_1, ...], the shape's control points row by row.
    np.testing.assert_array_equal(simulation.shape(0).control_points, q.reshape(8, 3))
    np.testing.assert_array_equal(simulation.model_coordinates(0), q)
    moved = q + 0.25
    simulation.set_coordinates(moved)
    np.testing.assert_array_equal(simulation.coordinates, moved)
    np.testing.assert_array_equal(simulation.velocities, np.zeros(24))
    mesh = simulation.meshes(8)[0]
    assert mesh.name == "rod" and mesh.vertices.shape[1] == 3 and mesh.triangles.dtype == np.int32
    assert mesh.triangles.max() < mesh.vertex_count
    cost = simulation.cost()[0]
    assert cost["type"] == "dnurbs_curve" and cost["coordinates"] == 24 and cost["fixed"] == 6
    with pytest.raises(dnurbs.Error, match="coordinates must have shape \\(24,\\)"):
        simulation.set_coordinates(np.zeros(3))
    with pytest.raises(dnurbs.Error, match="model index 1 is outside 0..0"):
        simulation.shape(1)


def test_bad_scene_text_raises_the_library_message():
    with pytest.raises(dnurbs.Error, match="^mine.json: "):
        dnurbs.parse_scene('{"models": 3}', "mine.json")
    with pytest.raises(dnurbs.Error, match="mine.json"):
        dnurbs.parse_scene("{not json", "mine.json")
    with pytest.raises(dnurbs.Error):
        dnurbs.read_scene(SCENES / "no_such_scene.json")


def test_diverging_scene_raises_and_run_reports_it(tmp_path):
    scene = dnurbs.read_scene(SCENES / "diverging_sheet.json")
    simulation = dnurbs.SceneSimulation(scene)
    with pytest.raises(dnurbs.SimulationDiverged) as raised:
        simulation.step(scene.step_count)
    # The state is back at the last step that passed the energy check (newmark_gamma < 1/2
    # makes the first step fail it already).
    good = simulation.steps_done
    assert good == 0
    np.testing.assert_array_equal(simulation.coordinates,
                                  dnurbs.SceneSimulation(scene).coordinates)
    assert np.all(np.isfinite(simulation.coordinates))
    assert "diverged" in str(raised.value) and "newmark_gamma" in str(raised.value)
    result = dnurbs.SceneSimulation(scene).run(tmp_path / "out")
    assert result["diverged"] and result["steps_done"] == good
    assert result["message"] == str(raised.value)


def test_scene_json_round_trip():
    scene = dnurbs.read_scene(SCENES / "constraints.json")
    again = dnurbs.parse_scene(scene.to_json(), "again")
    assert again == scene
    assert len(scene.state_hash()) == 16
