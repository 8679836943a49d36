#!/usr/bin/python3
"""Writes the example images and volumes of vision/ (T-snakes, T-surfaces, Kalman snakes).

Usage: /usr/bin/python3 scripts/generate_vision_data.py OUTPUT_FOLDER [--seed N]

Every shape is rendered by pixel (voxel) coverage on a 4 x 4 (x 4) sub-grid, intensity 1 inside
and 0 outside, so the intensity sum is the shape's area (volume) to the sub-sampling error:
  discs_merge.png      96 x 64: two discs of radius 16 whose centres are 28 px apart (they
                       overlap: grow one T-snake in each and they merge)
  dumbbell_discs.png   96 x 64: two discs of radius 12, 42 px apart (a dumbbell-shaped snake
                       around both pinches and splits)
  ring.png             80 x 80: an annulus of radii 12 and 26 (final contours: one outer
                       counter-clockwise, one hole clockwise)
  vessel_tree.png      128 x 128: a branching tree of tubes, widths 7 px down to 3 px, with
                       Gaussian noise (sigma 0.05) and a smooth background gradient
  torus.nrrd           48 x 48 x 24 uchar volume: a torus of radii 14 and 5 (genus 1)
  sphere.nrrd          33 x 33 x 33 uchar volume: a ball of radius 10 (genus 0)
  contour_sequence/frame_NNN.pgm and truth.csv: 20 frames 96 x 96 of an ellipse moving on a
                       circle and breathing (semi-axes 18 +- 3 and 12 +- 2), with Gaussian noise
                       of sigma 0.15, for a Kalman snake to track; truth.csv lists the centre,
                       semi-axes and rotation per frame.
PNG files are 8-bit greyscale (written here with zlib, no color conversion), PGM files binary
P5, NRRD files raw uchar with the data attached. Needs Debian's python3 and python3-numpy.
"""
import argparse
import os
import struct
import zlib

import numpy as np

SUB = 4  # coverage sub-samples per pixel side


def coverage_2d(width, height, inside):
    """Fraction of each pixel's unit square (centred on (x, y)) where inside(x, y) holds."""
    offsets = (np.arange(SUB) + 0.5) / SUB - 0.5
    y, x = np.mgrid[0:height, 0:width].astype(float)
    total = np.zeros((height, width))
    for dy in offsets:
        for dx in offsets:
            total += inside(x + dx, y + dy)
    return total / SUB**2


def coverage_3d(nx, ny, nz, inside):
    offsets = (np.arange(SUB) + 0.5) / SUB - 0.5
    z, y, x = np.mgrid[0:nz, 0:ny, 0:nx].astype(float)
    total = np.zeros((nz, ny, nx))
    for dz in offsets:
        for dy in offsets:
            for dx in offsets:
                total += inside(x + dx, y + dy, z + dz)
    return total / SUB**3


def quantize(image):
    return np.clip(np.rint(np.clip(image, 0.0, 1.0) * 255.0), 0, 255).astype(np.uint8)


def write_png(path, image):
    """8-bit greyscale PNG (color type 0), rows filtered with filter type 0."""
    data = quantize(image)
    height, width = data.shape
    raw = b"".join(b"\x00" + data[row].tobytes() for row in range(height))

    def chunk(kind, payload):
        body = kind + payload
        return struct.pack(">I", len(payload)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    with open(path, "wb") as out:
        out.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9))
                  + chunk(b"IEND", b""))


def write_pgm(path, image):
    data = quantize(image)
    with open(path, "wb") as out:
        out.write(b"P5\n%d %d\n255\n" % (data.shape[1], data.shape[0]))
        out.write(data.tobytes())


def write_nrrd(path, volume):
    """volume indexed [z, y, x]; NRRD's fastest axis is x."""
    data = quantize(volume)
    nz, ny, nx = data.shape
    with open(path, "wb") as out:
        out.write(("NRRD0004\n# dnurbs scripts/generate_vision_data.py\ntype: uchar\ndimension: 3\n"
                   "sizes: %d %d %d\nspacings: 1 1 1\nencoding: raw\n\n" % (nx, ny, nz)).encode())
        out.write(data.tobytes())


def disc(cx, cy, r):
    return lambda x, y: (x - cx) ** 2 + (y - cy) ** 2 <= r * r


def segment_distance(x, y, a, b):
    """Distance from (x, y) to the segment a-b."""
    ax, ay = a
    bx, by = b
    dx, dy = bx - ax, by - ay
    t = np.clip(((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0)
    return np.hypot(x - ax - t * dx, y - ay - t * dy)


def vessel_tree(rng):
    # Trunk, two branches, four twigs: (start, end, half-width) in pixels.
    tubes = [((64, 124), (64, 80), 3.5),
             ((64, 80), (36, 48), 2.8), ((64, 80), (94, 44), 2.8),
             ((36, 48), (20, 14), 2.0), ((36, 48), (50, 10), 1.8),
             ((94, 44), (84, 8), 1.8), ((94, 44), (118, 20), 1.5)]

    def inside(x, y):
        hit = np.zeros_like(x, dtype=bool)
        for a, b, half_width in tubes:
            hit |= segment_distance(x, y, a, b) <= half_width
        return hit

    image = 0.8 * coverage_2d(128, 128, inside)
    y, x = np.mgrid[0:128, 0:128].astype(float)
    image += 0.1 + 0.08 * x / 127.0  # uneven illumination
    return image + rng.normal(0.0, 0.05, image.shape)


def contour_sequence(folder, rng, frames=20):
    os.makedirs(folder, exist_ok=True)
    rows = ["frame,centre_x,centre_y,semi_axis_a,semi_axis_b,rotation"]
    for k in range(frames):
        phase = 2.0 * np.pi * k / frames
        cx, cy = 48.0 + 14.0 * np.cos(phase), 48.0 + 10.0 * np.sin(phase)
        a, b = 18.0 + 3.0 * np.sin(2 * phase), 12.0 + 2.0 * np.cos(2 * phase)
        rotation = 0.3 * phase
        c, s = np.cos(rotation), np.sin(rotation)

        def inside(x, y):
            u = c * (x - cx) + s * (y - cy)
            v = -s * (x - cx) + c * (y - cy)
            return (u / a) ** 2 + (v / b) ** 2 <= 1.0

        image = 0.2 + 0.6 * coverage_2d(96, 96, inside) + rng.normal(0.0, 0.15, (96, 96))
        write_pgm(os.path.join(folder, "frame_%03d.pgm" % k), image)
        rows.append("%d,%.6f,%.6f,%.6f,%.6f,%.6f" % (k, cx, cy, a, b, rotation))
    with open(os.path.join(folder, "truth.csv"), "w") as out:
        out.write("\n".join(rows) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder")
    parser.add_argument("--seed", type=int, default=1, help="noise seed (default 1)")
    arguments = parser.parse_args()
    folder = arguments.folder
    os.makedirs(folder, exist_ok=True)
    rng = np.random.default_rng(arguments.seed)

    left, right = disc(34, 32, 16), disc(62, 32, 16)
    write_png(os.path.join(folder, "discs_merge.png"),
              coverage_2d(96, 64, lambda x, y: left(x, y) | right(x, y)))
    left, right = disc(27, 32, 12), disc(69, 32, 12)
    write_png(os.path.join(folder, "dumbbell_discs.png"),
              coverage_2d(96, 64, lambda x, y: left(x, y) | right(x, y)))
    write_png(os.path.join(folder, "ring.png"), coverage_2d(
        80, 80, lambda x, y: (np.hypot(x - 40, y - 40) >= 12) & (np.hypot(x - 40, y - 40) <= 26)))
    write_png(os.path.join(folder, "vessel_tree.png"), vessel_tree(rng))

    def torus(x, y, z):
        rho = np.hypot(x - 24.0, y - 24.0) - 14.0
        return rho * rho + (z - 12.0) ** 2 <= 25.0

    write_nrrd(os.path.join(folder, "torus.nrrd"), coverage_3d(48, 48, 24, torus))
    write_nrrd(os.path.join(folder, "sphere.nrrd"), coverage_3d(
        33, 33, 33, lambda x, y, z: (x - 16.2) ** 2 + (y - 15.9) ** 2 + (z - 16.1) ** 2 <= 100.0))
    contour_sequence(os.path.join(folder, "contour_sequence"), rng)
    print("wrote the vision example data to", folder)


if __name__ == "__main__":
    main()
