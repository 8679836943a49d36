#!/usr/bin/env python3
"""Render a shaded PNG preview of an OBJ mesh with matplotlib (Agg, no display needed).

Usage: preview_mesh.py MESH.obj OUT.png

Reads only `v`, `vn`, `f` and `o`/`g` lines (faces with more than three corners are fanned into
triangles; negative indices count from the end). Each object gets its own color; faces are
Lambert-shaded from one fixed light (two-sided), seen from a fixed camera that frames the whole
mesh with equal axis scales. The PNG is written to OUT.png whatever its extension.
"""

import sys


def read_obj(path):
    """Vertices, vertex normals and a list of (object name, triangles) from an OBJ file."""
    vertices, normals, objects = [], [], []
    current = ("mesh", [])
    with open(path, encoding="utf-8", errors="replace") as obj:
        for number, line in enumerate(obj, start=1):
            fields = line.split()
            if not fields:
                continue
            try:
                if fields[0] == "v":
                    vertices.append([float(x) for x in fields[1:4]])
                elif fields[0] == "vn":
                    normals.append([float(x) for x in fields[1:4]])
                elif fields[0] in ("o", "g"):
                    if current[1]:
                        objects.append(current)
                    current = (" ".join(fields[1:]) or "mesh", [])
                elif fields[0] == "f":
                    corners = []
                    for corner in fields[1:]:
                        index = int(corner.split("/")[0])
                        corners.append(index - 1 if index > 0 else len(vertices) + index)
                    for k in range(1, len(corners) - 1):
                        current[1].append((corners[0], corners[k], corners[k + 1]))
            except ValueError as error:
                raise SystemExit(f"{path}:{number}: cannot parse '{line.strip()}': {error}")
    if current[1]:
        objects.append(current)
    if not objects:
        raise SystemExit(f"{path}: no faces")
    return vertices, normals, objects


def main(argv):
    if len(argv) != 3 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) == 2 else 2
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import numpy as np
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    except ImportError as error:
        print(f"preview_mesh.py needs matplotlib and numpy (python3-matplotlib): {error}",
              file=sys.stderr)
        return 1

    vertices, _, objects = read_obj(argv[1])
    points = np.asarray(vertices, dtype=float)
    palette = np.array([[0.80, 0.52, 0.25], [0.30, 0.55, 0.80], [0.45, 0.70, 0.35],
                        [0.75, 0.35, 0.45], [0.60, 0.50, 0.75], [0.70, 0.70, 0.70]])
    elevation, azimuth = 28.0, -58.0
    # Light from the upper left of the camera, in world coordinates
    el, az = np.radians(elevation + 25.0), np.radians(azimuth - 40.0)
    light = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])

    polygons, colors = [], []
    for index, (_, triangles) in enumerate(objects):
        corners = points[np.asarray(triangles, dtype=int)]  # #F by 3 by 3
        normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        length = np.linalg.norm(normal, axis=1)
        keep = length > 0.0
        normal = normal[keep] / length[keep, None]
        lambert = np.abs(normal @ light)  # two-sided
        base = palette[index % len(palette)]
        shade = 0.25 + 0.75 * lambert
        rgb = np.clip(base[None, :] * shade[:, None] + 0.08 * lambert[:, None] ** 8, 0.0, 1.0)
        polygons.extend(corners[keep])
        colors.extend(rgb)

    figure = plt.figure(figsize=(8, 6), dpi=100)
    axes = figure.add_subplot(projection="3d")
    collection = Poly3DCollection(polygons, facecolors=colors, edgecolors="none",
                                  linewidths=0.0, antialiased=False)
    axes.add_collection3d(collection)
    # Frame the shape: its bounding box (padded), equal scales on the three axes
    low, high = points.min(axis=0), points.max(axis=0)
    centre = (low + high) / 2.0
    half = np.maximum((high - low) / 2.0, 0.02 * max((high - low).max(), 1e-9)) * 1.02
    axes.set_xlim(centre[0] - half[0], centre[0] + half[0])
    axes.set_ylim(centre[1] - half[1], centre[1] + half[1])
    axes.set_zlim(centre[2] - half[2], centre[2] + half[2])
    axes.set_box_aspect(tuple(half), zoom=1.15)
    axes.view_init(elev=elevation, azim=azimuth)
    axes.set_axis_off()
    figure.subplots_adjust(left=0.0, right=1.0, bottom=0.0, top=1.0)
    figure.savefig(argv[2], format="png", facecolor="white")
    plt.close(figure)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
