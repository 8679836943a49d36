#!/usr/bin/python3
"""Writes geometry images of procedural faces for surface/deformable_face.h (DeformableFace).

Usage: /usr/bin/python3 scripts/generate_face.py OUTPUT_FOLDER [--nodes N]

Goldenstein et al. 2005 (sections 3 and 6) describe a face over a (u, v) space that is
normalized across individuals: a feature (an eye's corner, the nose tip) sits at the same (u, v)
on every face while its 3-D position differs. The faces here are built that way: every feature
is placed at the canonical (u, v) of FaceLayout in surface/deformable_face.h (the nose tip at
(1/2, 27/64), the lips meeting at v = 18/64, the eyes at (1/2 +- 0.16, 0.6), the brows at
v = 0.7, the chin at (1/2, 0.16)), and a few parameters per individual, drawn from a seeded
generator, set the head's width, height and depth, the vertical spacing of the features, and
the size of the forehead, brow ridges, eye sockets, nose, cheeks, lips and chin.

Frame and units (as DeformableFace): millimetres, x to the face's own left, y up, z out of the
face; u from the face's right (0) to its left (1), v from under the chin (0) to the top of the
forehead (1). The head is an elliptic cylinder in u (the sides curve back, +-72 degrees) that
narrows toward the jaw, curves back under the chin (v < 0.1) and over the forehead (v > 0.8),
with the features added as Gaussian bumps of z (the nose also along its ridge).

Each file face_<name>.gim (format in surface/deformable_face.h):
  dnurbs-geometry-image 1
  individual <name>
  nodes <count_u> <count_v>
  x y z        one line per node (i, j) at (i / (count_u - 1), j / (count_v - 1)), u outer
The values are written with 4 decimals (0.1 micrometre), which also makes the files the same on
every machine whatever the last bit of numpy's exp and sin. 65 x 65 nodes by default: 64 cells,
so that the node parameters i / 64 are exact in binary and the surface reproduces its samples
bitwise. Needs Debian's python3 and python3-numpy.
"""
import argparse
import os

import numpy as np

# The canonical layout (FaceLayout in surface/deformable_face.h)
MIDLINE = 0.5
MOUTH_V = 18.0 / 64
MOUTH_HALF_WIDTH = 0.085
NOSE_TIP_V = 27.0 / 64
EYE_V = 0.60
EYE_OFFSET = 0.16
BROW_V = 0.70
BROW_INNER = 0.08
BROW_OUTER = 0.26
CHIN_V = 0.16

# (name, seed) of the individuals
INDIVIDUALS = [("ada", 7), ("ben", 1999), ("cleo", 314159)]


def uniform_draws(seed, count):
    """count numbers in [0, 1) from splitmix64 (integer arithmetic: the same on every machine
    and every numpy version, unlike numpy's generators' streams)."""
    mask = (1 << 64) - 1
    state = seed & mask
    draws = []
    for _ in range(count):
        state = (state + 0x9E3779B97F4A7C15) & mask
        z = state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & mask
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & mask
        z ^= z >> 31
        draws.append((z >> 11) / float(1 << 53))
    return draws


def individual_parameters(seed):
    """The shape parameters of one individual: each a range's point at one seeded draw."""
    ranges = {
        "half_width": (68.0, 80.0),      # mm, the head's half width at the cheeks
        "height": (175.0, 200.0),        # mm, from under the chin to the top of the forehead
        "depth_ratio": (0.75, 0.95),     # the head's depth over its half width
        "spacing_warp": (-0.25, 0.25),   # moves the features up or down in y, not in (u, v)
        "jaw_taper": (0.12, 0.28),       # how much narrower the jaw is than the cheeks
        "forehead_slope": (20.0, 40.0),  # mm the top of the forehead lies back
        "brow_ridge": (3.0, 7.0),        # mm
        "eye_socket": (7.0, 12.0),       # mm
        "nose_height": (18.0, 28.0),     # mm, the nose tip above the face
        "nose_width": (0.030, 0.045),    # in u
        "cheek": (4.0, 9.0),             # mm
        "lips": (3.0, 6.0),              # mm
        "chin": (4.0, 9.0),              # mm
    }
    draws = uniform_draws(seed, len(ranges))
    return {key: low + (high - low) * draw
            for (key, (low, high)), draw in zip(ranges.items(), draws)}


def gaussian(u, v, centre_u, centre_v, sigma_u, sigma_v):
    return np.exp(-0.5 * (((u - centre_u) / sigma_u) ** 2 + ((v - centre_v) / sigma_v) ** 2))


def mirrored_pair(u, v, offset, centre_v, sigma_u, sigma_v):
    """A bump at MIDLINE - offset and its mirror image at MIDLINE + offset."""
    return (gaussian(u, v, MIDLINE - offset, centre_v, sigma_u, sigma_v) +
            gaussian(u, v, MIDLINE + offset, centre_v, sigma_u, sigma_v))


def face_points(parameters, nodes):
    """The nodes x nodes by 3 array of points: node (i, j) at u = i / (nodes - 1),
    v = j / (nodes - 1)."""
    p = parameters
    grid = np.arange(nodes) / (nodes - 1)
    u, v = np.meshgrid(grid, grid, indexing="ij")
    # The head: an elliptic cylinder narrowing toward the jaw
    theta = (u - MIDLINE) * 2.0 * 1.25
    taper = 1.0 - p["jaw_taper"] * (1.0 - np.clip((v - 0.05) / 0.45, 0.0, 1.0)) ** 2
    radius = p["half_width"] * taper
    x = radius * np.sin(theta)
    z = p["depth_ratio"] * radius * (np.cos(theta) - 1.0)
    # y rises monotonically with v (slope between 1 - 0.25 and 1 + 0.25 times the height): the
    # warp moves the features up or down on the head without moving them in (u, v)
    y = p["height"] * (v - 0.5 + p["spacing_warp"] * np.sin(2.0 * np.pi * v) / (2.0 * np.pi))
    # Under the chin and over the forehead the surface curves back
    z -= 45.0 * np.clip((0.1 - v) / 0.1, 0.0, 1.0) ** 2
    z -= p["forehead_slope"] * np.clip((v - 0.8) / 0.2, 0.0, 1.0) ** 2
    # Brow ridges along the brows, eye sockets with the eyeballs in them
    brow_u = np.clip(np.abs(u - MIDLINE), BROW_INNER, BROW_OUTER)
    z += p["brow_ridge"] * np.exp(-0.5 * (((np.abs(u - MIDLINE) - brow_u) / 0.04) ** 2 +
                                          ((v - BROW_V) / 0.03) ** 2))
    z -= p["eye_socket"] * mirrored_pair(u, v, EYE_OFFSET, EYE_V, 0.06, 0.045)
    z += 0.5 * p["eye_socket"] * mirrored_pair(u, v, EYE_OFFSET, EYE_V, 0.035, 0.022)
    # The nose: a ridge from between the eyes to the tip, the tip, the nostril wings
    # (the ridge's height rises from 0.35 of the nose's between the eyes to 0.9 at the tip, and
    # fades within about 0.03 above the eyes and below the tip)
    bridge_v = 0.62
    ridge = np.clip((bridge_v - v) / (bridge_v - NOSE_TIP_V), 0.0, 1.0)
    along = np.where(v >= NOSE_TIP_V, 0.35 + 0.55 * ridge,
                     0.9 * np.exp(-0.5 * ((v - NOSE_TIP_V) / 0.02) ** 2))
    along = np.where(v > bridge_v, 0.35 * np.exp(-0.5 * ((v - bridge_v) / 0.03) ** 2), along)
    z += p["nose_height"] * along * np.exp(-0.5 * ((u - MIDLINE) / (0.5 * p["nose_width"])) ** 2)
    z += 0.1 * p["nose_height"] * gaussian(u, v, MIDLINE, NOSE_TIP_V, p["nose_width"], 0.025)
    z += 0.2 * p["nose_height"] * mirrored_pair(u, v, 0.045, NOSE_TIP_V - 0.01, 0.02, 0.02)
    # Cheeks, lips (meeting at MOUTH_V, a groove between them) and chin
    z += p["cheek"] * mirrored_pair(u, v, 0.2, 0.44, 0.08, 0.07)
    z += p["lips"] * gaussian(u, v, MIDLINE, MOUTH_V + 0.02, MOUTH_HALF_WIDTH * 0.75, 0.018)
    z += p["lips"] * gaussian(u, v, MIDLINE, MOUTH_V - 0.025, MOUTH_HALF_WIDTH * 0.7, 0.02)
    z -= 0.5 * p["lips"] * gaussian(u, v, MIDLINE, MOUTH_V, MOUTH_HALF_WIDTH, 0.008)
    z += p["chin"] * gaussian(u, v, MIDLINE, CHIN_V, 0.08, 0.05)
    return np.stack([x, y, z], axis=-1)


def write_geometry_image(path, name, points):
    nodes_u, nodes_v, _ = points.shape
    with open(path, "w", encoding="ascii", newline="\n") as out:
        out.write("dnurbs-geometry-image 1\n")
        out.write("# written by scripts/generate_face.py: mm, x to the face's left, y up, "
                  "z out of the face\n")
        out.write("individual %s\nnodes %d %d\n" % (name, nodes_u, nodes_v))
        for row in points.reshape(-1, 3):
            # round to 4 decimals first, then + 0.0 turns a rounded -0.0 into 0.0
            out.write("%.4f %.4f %.4f\n" % tuple(round(float(value), 4) + 0.0 for value in row))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output", help="folder for face_<name>.gim")
    parser.add_argument("--nodes", type=int, default=65, help="nodes per direction (>= 2)")
    arguments = parser.parse_args()
    if arguments.nodes < 2:
        parser.error("--nodes must be at least 2, got %d" % arguments.nodes)
    os.makedirs(arguments.output, exist_ok=True)
    for name, seed in INDIVIDUALS:
        points = face_points(individual_parameters(seed), arguments.nodes)
        path = os.path.join(arguments.output, "face_%s.gim" % name)
        write_geometry_image(path, name, points)
        print("%s: %d x %d nodes, nose tip at z = %.2f mm" %
              (path, arguments.nodes, arguments.nodes, points[..., 2].max()))


if __name__ == "__main__":
    main()
