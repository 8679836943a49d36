#!/usr/bin/python3
"""Writes the hand-crafted base mesh of the face in (u, v) (Goldenstein et al. 2005, figure 2a).

Usage: /usr/bin/python3 scripts/generate_face_base.py OUTPUT.obj

Section 5.1 of the paper builds its base mesh by choosing points in (u, v) by hand, denser around
the features, and triangulating them (with Shewchuk's triangle); its figure 2a has 113 vertices
and 195 triangles. This script places 113 points the same way on the canonical layout of
FaceLayout (surface/deformable_face.h): 29 on an ellipse around the face (0.47 by 0.48 about
(1/2, 1/2)), rings around the eyes, the mouth and the nose tip, points on the brows and the chin,
and fills the rest by farthest-point sampling of a fine grid inside the ellipse (so the fill is
even and thins out near the features' rings). Their Delaunay triangulation (scipy) has
2 * 113 - 2 - 29 = 195 triangles, as the paper's. Needs Debian's python3 with python3-numpy and python3-scipy.

Output: an OBJ of the (u, v) plane: "v u v 0" lines and "f a b c" lines (1-based,
counter-clockwise in (u, v)).
"""
import argparse
import os
import sys

import numpy as np
from scipy.spatial import Delaunay

# The canonical layout (FaceLayout in surface/deformable_face.h), from the faces' script
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from generate_face import (BROW_INNER, BROW_OUTER, BROW_V, CHIN_V,  # noqa: E402
                           EYE_OFFSET, EYE_V, MIDLINE, MOUTH_HALF_WIDTH, MOUTH_V, NOSE_TIP_V)

VERTICES = 113
OUTLINE = 29
OUTLINE_RADII = (0.47, 0.48)


def ring(centre, radii, count, phase=0.0):
    angles = phase + 2.0 * np.pi * np.arange(count) / count
    return np.column_stack([centre[0] + radii[0] * np.cos(angles),
                            centre[1] + radii[1] * np.sin(angles)])


def feature_points():
    points = [ring((MIDLINE, 0.5), OUTLINE_RADII, OUTLINE, phase=-np.pi / 2)]
    for side in (-1.0, 1.0):
        eye = (MIDLINE + side * EYE_OFFSET, EYE_V)
        points.append(np.array([eye]))
        points.append(ring(eye, (0.075, 0.045), 8))
        brow_u = MIDLINE + side * np.linspace(BROW_INNER, BROW_OUTER, 3)
        points.append(np.column_stack([brow_u, np.full(3, BROW_V)]))
    points.append(np.array([[MIDLINE, MOUTH_V]]))
    points.append(ring((MIDLINE, MOUTH_V), (MOUTH_HALF_WIDTH + 0.025, 0.045), 10))
    points.append(np.array([[MIDLINE, NOSE_TIP_V]]))
    points.append(ring((MIDLINE, NOSE_TIP_V), (0.05, 0.04), 4, phase=np.pi / 4))
    points.append(np.array([[MIDLINE, CHIN_V]]))
    return np.vstack(points)


def fill(points, count):
    """Adds `count` points of a 201 x 201 grid inside 0.88 of the outline ellipse, each the one
    farthest from the points so far."""
    axis = np.linspace(0.0, 1.0, 201)
    grid = np.array([(u, v) for u in axis for v in axis])
    inside = (((grid[:, 0] - 0.5) / (0.88 * OUTLINE_RADII[0])) ** 2 +
              ((grid[:, 1] - 0.5) / (0.88 * OUTLINE_RADII[1])) ** 2) < 1.0
    candidates = grid[inside]
    distance = np.min(np.linalg.norm(candidates[:, None, :] - points[None, :, :], axis=2), axis=1)
    added = []
    for _ in range(count):
        best = int(np.argmax(distance))
        added.append(candidates[best])
        distance = np.minimum(distance, np.linalg.norm(candidates - candidates[best], axis=1))
    return np.vstack([points, np.array(added)])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("output", help="OBJ file to write")
    args = parser.parse_args()
    features = feature_points()
    points = fill(features, VERTICES - len(features))
    triangulation = Delaunay(points)
    triangles = triangulation.simplices
    hull = len(np.unique(triangulation.convex_hull))
    assert hull == OUTLINE, f"convex hull has {hull} vertices, not the {OUTLINE} of the outline"
    # Counter-clockwise in (u, v)
    a, b, c = (points[triangles[:, k]] for k in range(3))
    area = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    triangles[area < 0] = triangles[area < 0][:, [0, 2, 1]]
    with open(args.output, "w") as stream:
        stream.write("# The hand-crafted base mesh of the face in (u, v) (Goldenstein et al. 2005, "
                     "figure 2a)\n# written by scripts/generate_face_base.py: "
                     f"{len(points)} vertices, {len(triangles)} triangles\n")
        for u, v in points:
            stream.write(f"v {u:.6f} {v:.6f} 0\n")
        for t in triangles:
            stream.write(f"f {t[0] + 1} {t[1] + 1} {t[2] + 1}\n")
    print(f"{args.output}: {len(points)} vertices, {len(triangles)} triangles")


if __name__ == "__main__":
    main()
