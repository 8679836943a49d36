#!/usr/bin/python3
"""Renders the README picture of example 213: three individuals (columns) smiling, raising the
left brow and opening the jaw (rows), from the OBJ files the example writes.

Usage: /usr/bin/python3 examples/213_deformable_face/render_faces.py OBJ_FOLDER OUT.png

The faces are in the example's frame (mm, y up, looking along +z) and are shown turned to
matplotlib's z-up frame, Lambert-shaded from one light. Needs python3-matplotlib.
"""
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402 (after choosing the backend)
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

EXPRESSIONS = ["smile", "left_brow_raise", "jaw_open"]
INDIVIDUALS = ["ada", "ben", "cleo"]


def read_obj(path):
    """Vertices (#V by 3) and triangles (#F by 3, 0-based) of an OBJ file."""
    vertices, triangles = [], []
    with open(path, encoding="ascii") as obj:
        for line in obj:
            words = line.split()
            if words and words[0] == "v":
                vertices.append([float(word) for word in words[1:4]])
            elif words and words[0] == "f":
                triangles.append([int(corner.split("/")[0]) - 1 for corner in words[1:4]])
    return np.array(vertices), np.array(triangles)


def main(folder, out):
    figure = plt.figure(figsize=(7.5, 8.4), dpi=80)
    elevation, azimuth = 12.0, -68.0
    light_elevation, light_azimuth = np.radians(elevation + 30.0), np.radians(azimuth - 35.0)
    light = np.array([np.cos(light_elevation) * np.cos(light_azimuth),
                      np.cos(light_elevation) * np.sin(light_azimuth), np.sin(light_elevation)])
    skin = np.array([0.86, 0.66, 0.52])
    for row, expression in enumerate(EXPRESSIONS):
        for column, individual in enumerate(INDIVIDUALS):
            vertices, triangles = read_obj(f"{folder}/{individual}_{expression}.obj")
            # y up, face along +z -> z up, face along -y (toward the camera)
            points = np.stack([vertices[:, 0], -vertices[:, 2], vertices[:, 1]], axis=1)
            corners = points[triangles]
            normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
            normal /= np.maximum(np.linalg.norm(normal, axis=1)[:, None], 1e-12)
            lambert = np.abs(normal @ light)
            colors = np.clip(skin[None] * (0.22 + 0.78 * lambert[:, None]) +
                             0.06 * lambert[:, None] ** 8, 0.0, 1.0)
            axes = figure.add_subplot(3, 3, row * 3 + column + 1, projection="3d")
            axes.add_collection3d(Poly3DCollection(corners, facecolors=colors, edgecolors="none",
                                                   linewidths=0.0, antialiased=False))
            axes.set_xlim(-80, 80)
            axes.set_ylim(-80, 80)
            axes.set_zlim(-100, 100)
            axes.set_box_aspect((160, 160, 200), zoom=1.55)
            axes.view_init(elev=elevation, azim=azimuth)
            axes.set_axis_off()
            axes.set_title(f"{individual}: {expression.replace('_', ' ')}", fontsize=9, y=0.93)
    figure.subplots_adjust(left=0.0, right=1.0, bottom=0.0, top=1.0, wspace=0.0, hspace=0.0)
    figure.savefig(out, format="png", facecolor="white")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
