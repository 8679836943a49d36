"""scripts/generate_face.py regenerates the committed geometry images of examples/faces exactly."""

import subprocess
import sys

from conftest import SOURCE_DIR

INDIVIDUALS = ("ada", "ben", "cleo")


def test_regenerating_gives_the_committed_faces_byte_for_byte(tmp_path):
    subprocess.run([sys.executable, str(SOURCE_DIR / "scripts" / "generate_face.py"),
                    str(tmp_path)], check=True, capture_output=True)
    written = sorted(path.name for path in tmp_path.iterdir())
    assert written == [f"face_{name}.gim" for name in INDIVIDUALS]
    for name in INDIVIDUALS:
        committed = (SOURCE_DIR / "examples" / "faces" / f"face_{name}.gim").read_bytes()
        assert (tmp_path / f"face_{name}.gim").read_bytes() == committed, name


def test_the_faces_differ_but_share_their_layout(tmp_path):
    # 65 x 65 nodes after the four header lines; the nose tip (largest z) at node (32, 27) on
    # every face, while the faces' shapes differ
    rows = {}
    for name in INDIVIDUALS:
        lines = (SOURCE_DIR / "examples" / "faces" / f"face_{name}.gim").read_text().splitlines()
        assert lines[0] == "dnurbs-geometry-image 1"
        assert lines[2] == f"individual {name}" and lines[3] == "nodes 65 65"
        rows[name] = [tuple(float(word) for word in line.split()) for line in lines[4:]]
        assert len(rows[name]) == 65 * 65
        highest = max(range(65 * 65), key=lambda node: rows[name][node][2])
        assert divmod(highest, 65) == (32, 27), name
    assert rows["ada"] != rows["ben"] and rows["ben"] != rows["cleo"]


def test_a_node_count_below_two_is_refused(tmp_path):
    result = subprocess.run([sys.executable, str(SOURCE_DIR / "scripts" / "generate_face.py"),
                             str(tmp_path), "--nodes", "1"], capture_output=True, text=True)
    assert result.returncode != 0
    assert "--nodes must be at least 2, got 1" in result.stderr
