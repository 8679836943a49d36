#!/usr/bin/python3
"""Compares a scene's log.csv with its recorded log: same header, same rows, and every number
equal to the recorded one within a relative tolerance of its column's scale.

Usage: compare_scene_log.py RECORDED.csv NEW.csv [--tolerance 1e-8]

Why a tolerance and not the bytes: OpenBLAS picks its kernels for the CPU it runs on (AVX2,
AVX-512, ...), so CHOLMOD's supernodal factorization (used above the solver threshold) rounds
differently on another machine; measured between two machines: up to 5.7e-11 relative after 75
steps of a triangular D-NURBS scene, round-off amplified by the steps. A change of behaviour is
far above 1e-8. Prints the first differing value and exits 1 if the logs differ.

The scale of a column is shared by its group: the components of one point or vector (name_x,
name_y, name_z) and numbered columns (name_0, name_1, ...) take the largest magnitude of the
group. A component that is zero by symmetry (the x of a point on the axis) holds only rounding
of the point's size, 1e-17 against 1e-16 of a column scale of its own; any change of the
rounding then failed the check.
"""
import argparse
import csv
import math
import re
import sys


def group(name):
    """The group of a column: its name without a trailing _x, _y, _z or _<number>."""
    return re.sub(r"_(x|y|z|[0-9]+)$", "", name)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("recorded")
    parser.add_argument("new")
    parser.add_argument("--tolerance", type=float, default=1e-8)
    args = parser.parse_args()
    with open(args.recorded, newline="") as file:
        recorded = list(csv.reader(file))
    with open(args.new, newline="") as file:
        new = list(csv.reader(file))
    if not recorded or not new or recorded[0] != new[0]:
        print(f"header differs: {new[0] if new else []} against {recorded[0] if recorded else []}")
        return 1
    if len(recorded) != len(new):
        print(f"{len(new) - 1} rows against {len(recorded) - 1} recorded")
        return 1
    columns = len(recorded[0])
    scale = [0.0] * columns
    for row in recorded[1:]:
        for k, text in enumerate(row):
            value = float(text)
            if math.isfinite(value):
                scale[k] = max(scale[k], abs(value))
    group_scale = {}
    for k, name in enumerate(recorded[0]):
        group_scale[group(name)] = max(group_scale.get(group(name), 0.0), scale[k])
    scale = [group_scale[group(name)] for name in recorded[0]]
    for line, (old_row, new_row) in enumerate(zip(recorded[1:], new[1:]), start=2):
        if len(old_row) != columns or len(new_row) != columns:
            print(f"line {line}: {len(new_row)} values against {len(old_row)} recorded")
            return 1
        for k, (old_text, new_text) in enumerate(zip(old_row, new_row)):
            old, value = float(old_text), float(new_text)
            if math.isnan(old) and math.isnan(value):
                continue
            if not abs(value - old) <= args.tolerance * max(scale[k], 1e-300):
                print(f"line {line}, column {recorded[0][k]}: {new_text} against {old_text} "
                      f"recorded (column scale {scale[k]:.3g})")
                return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
