"""A Kalman snake tracks a moving, breathing, turning ellipse through the noisy frames that
scripts/generate_vision_data.py writes (contour_sequence/frame_NNN.pgm and truth.csv).

Kalman snakes (Terzopoulos & Szeliski, "Tracking with Kalman snakes", Active Vision, MIT Press
1992; Terzopoulos, "Deformable Models: Classic, Topology-Adaptive and Generalized Formulations",
2003, section 2.4): the snake's equations of motion are the system model of a Kalman filter, the
edges found along each node's normal in a frame its measurements. Every frame the filter
predicts, searches the edge potential of the frame along the predicted normals and updates; its
covariance is the uncertainty of the tracked shape.

Writes kalman_tracking.png (five frames with the tracked contour, the true ellipse and each
node's 2-sigma position ellipse, magnified 4 times) and returns the largest distance of a node
from the true ellipse in every frame. examples/python/pictures/kalman_tracking.png is this
script's output.

    PYTHONPATH=build/python python3 examples/python/kalman_tracking.py --out kalman-out
"""

import argparse
import pathlib
import subprocess
import sys

import numpy as np

import dnurbs

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
GENERATOR = SOURCE_DIR / "scripts" / "generate_vision_data.py"


def ellipse_points(row, count):
    """`count` points of the ellipse of one truth.csv row (centre, semi-axes, rotation)."""
    _, cx, cy, a, b, rotation = row
    t = 2.0 * np.pi * np.arange(count) / count
    c, s = np.cos(rotation), np.sin(rotation)
    u, v = a * np.cos(t), b * np.sin(t)
    return np.column_stack([cx + c * u - s * v, cy + s * u + c * v])


def track(out_dir, nodes=40, picture=True):
    """Generates the sequence into out_dir, tracks it; returns a dict with the per-frame largest
    node distance from the true ellipse (px), the edges found per frame and the picture's path."""
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    subprocess.run([sys.executable, str(GENERATOR), str(out_dir)], check=True,
                   stdout=subprocess.DEVNULL)
    folder = out_dir / "contour_sequence"
    truth = np.loadtxt(folder / "truth.csv", delimiter=",", skiprows=1)
    # The snake starts at rest on the first frame's ellipse. Tension and rigidity keep the nodes
    # spaced (edges along the normals do not see a node sliding along the contour); white
    # acceleration noise of 1 px / frame^2 lets it follow the ellipse's turns.
    start = ellipse_points(truth[0], nodes)
    snake = dnurbs.KalmanSnake(start, tension=3e-3, rigidity=1e-6, acceleration_variance=1.0,
                               initial_velocity_variance=9.0)
    largest, edges, shown = [], [], []
    for k, row in enumerate(truth):
        frame = dnurbs.read_image(str(folder / ("frame_%03d.pgm" % k)))
        edges.append(snake.track(frame, width=frame.width, height=frame.height))
        dense = ellipse_points(row, 2000)
        distances = np.linalg.norm(snake.positions[:, None, :] - dense[None, :, :], axis=2)
        largest.append(distances.min(axis=1).max())
        if k in (0, 5, 10, 15, len(truth) - 1):
            shown.append((k, frame.pixels, snake.positions.copy(), dense,
                          [snake.node_covariance(i) for i in range(nodes)]))
    result = {"largest": np.array(largest), "edges": np.array(edges), "nodes": nodes}
    if picture:
        result["picture"] = draw(shown, out_dir / "kalman_tracking.png")
    return result


def draw(shown, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Ellipse

    figure, axes = plt.subplots(1, len(shown), figsize=(2.3 * len(shown), 2.6))
    for axis, (k, pixels, positions, dense, covariances) in zip(axes, shown):
        axis.imshow(pixels, cmap="gray", vmin=-0.5, vmax=1.5, interpolation="nearest")
        axis.plot(*np.vstack([dense, dense[:1]]).T, "--", color="deepskyblue", lw=1.2)
        axis.plot(*np.vstack([positions, positions[:1]]).T, "-", color="orange", lw=1.4)
        for position, covariance in zip(positions, covariances):
            values, vectors = np.linalg.eigh(covariance)
            angle = np.degrees(np.arctan2(vectors[1, 1], vectors[0, 1]))
            # 2-sigma ellipses magnified 4 times so that they show at this scale
            axis.add_patch(Ellipse(position, 2 * 2 * 4 * np.sqrt(values[1]),
                                   2 * 2 * 4 * np.sqrt(values[0]), angle=angle, fill=False,
                                   color="yellow", lw=0.6))
        low, high = dense.min(axis=0) - 6.0, dense.max(axis=0) + 6.0
        axis.set_xlim(low[0], high[0])
        axis.set_ylim(high[1], low[1])
        axis.set_title("frame %d" % k, fontsize=10)
        axis.set_axis_off()
    figure.suptitle("Kalman snake (orange) tracking the true ellipse (dashed); 2-sigma node "
                    "uncertainty x 4 (yellow)", fontsize=10)
    figure.tight_layout()
    figure.savefig(path, dpi=60)
    plt.close(figure)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="kalman-out")
    arguments = parser.parse_args()
    result = track(arguments.out)
    print("largest node distance from the true ellipse per frame (px):",
          np.array2string(result["largest"], precision=2))
    print("edges found per frame:", result["edges"])
    print("wrote", result["picture"])


if __name__ == "__main__":
    main()
