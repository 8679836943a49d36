"""Checkpoints from Python: a scene restored from a checkpoint dict, file or JSON text continues
bit for bit like the uninterrupted run; the simulation's System copy, log row, constraints,
integrator and energy budget read back; a checkpoint of another scene is rejected."""

import numpy as np
import pytest

import dnurbs
from conftest import SOURCE_DIR

SCENES = SOURCE_DIR / "examples" / "scenes"


def test_restore_continues_bit_for_bit(tmp_path):
    scene = dnurbs.read_scene(SCENES / "constraints.json")
    straight = dnurbs.SceneSimulation(scene)
    straight.step(20)
    first = dnurbs.SceneSimulation(scene)
    first.step(10)
    checkpoint = first.checkpoint()
    assert checkpoint["step"] == 10
    text = dnurbs.checkpoint_to_json(checkpoint)
    again = dnurbs.parse_checkpoint(text, "text")
    np.testing.assert_array_equal(again["coordinates"], checkpoint["coordinates"])
    assert again["time"] == checkpoint["time"] and again["scene_hash"] == scene.state_hash()
    path = tmp_path / "checkpoint.json"
    dnurbs.write_checkpoint(path, checkpoint)
    for source in (checkpoint, path, str(path)):
        resumed = dnurbs.SceneSimulation(scene)
        resumed.restore(source)
        assert resumed.steps_done == 10 and resumed.time == first.time
        resumed.step(10)
        # The same doubles in the same order (Newmark's accelerations carried along).
        np.testing.assert_array_equal(resumed.coordinates, straight.coordinates)
        np.testing.assert_array_equal(resumed.velocities, straight.velocities)
    other = dnurbs.SceneSimulation(dnurbs.read_scene(SCENES / "curve_sculpting.json"))
    with pytest.raises(ValueError, match="checkpoint dict"):
        other.restore(checkpoint)
    with pytest.raises(ValueError, match="checkpoint has no \"time\""):
        other.restore({key: value for key, value in checkpoint.items() if key != "time"})


def test_simulation_parts_read_back():
    scene = dnurbs.read_scene(SCENES / "constraints.json")
    simulation = dnurbs.SceneSimulation(scene)
    simulation.step(3)
    system = simulation.system
    np.testing.assert_array_equal(system.coordinates, simulation.coordinates)
    system.set_time(99.0)
    assert simulation.time != 99.0  # a copy
    row = simulation.log_row()
    sample = simulation.sample()
    assert row.shape == (len(simulation.log_columns),)
    np.testing.assert_array_equal(row[:3], [sample["time"], sample["kinetic_energy"],
                                            sample["potential_energy"]])
    descriptions = simulation.constraint_descriptions
    assert len(descriptions) == len(sample["violations"]) > 0
    assert all(isinstance(text, str) and text for text in descriptions)
    assert simulation.max_violation() == pytest.approx(max(sample["violations"]), rel=1e-15)
    assert simulation.integrator_scheme == scene.scheme
    budget = simulation.energy_budget()
    assert set(budget) == {"initial_energy", "work", "energy_moved"}
    assert np.isfinite(budget["initial_energy"]) and np.isfinite(budget["work"])
