#!/usr/bin/env python3
"""Plot the energies of a dnurbs run over time as a PNG with matplotlib (Agg, no display needed).

Usage: plot_energy.py LOG.csv OUT.png

LOG.csv is the log of `dnurbs run` (columns step, time, kinetic_energy, potential_energy,
total_energy, ...). The kinetic, elastic (potential) and total energies are drawn against the
time, on a logarithmic axis when they span more than three decades. The PNG (800 x 500 pixels)
is written to OUT.png whatever its extension.
"""

import csv
import sys

COLUMNS = ("time", "kinetic_energy", "potential_energy", "total_energy")


def read_log(path):
    """The columns of COLUMNS as lists of floats; SystemExit naming the line of a bad value."""
    with open(path, encoding="utf-8", errors="replace", newline="") as log:
        rows = csv.reader(log)
        header = next(rows, None)
        if header is None:
            raise SystemExit(f"{path}: empty log")
        missing = [name for name in COLUMNS if name not in header]
        if missing:
            raise SystemExit(f"{path}:1: no column {', '.join(missing)} in the header")
        index = [header.index(name) for name in COLUMNS]
        values = {name: [] for name in COLUMNS}
        for number, row in enumerate(rows, start=2):
            try:
                for name, column in zip(COLUMNS, index):
                    values[name].append(float(row[column]))
            except (ValueError, IndexError) as error:
                raise SystemExit(f"{path}:{number}: cannot read the energies: {error}")
    if not values["time"]:
        raise SystemExit(f"{path}: no rows after the header")
    return values


def main(argv):
    if len(argv) != 3 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) == 2 else 2
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as error:
        print(f"plot_energy.py needs matplotlib (python3-matplotlib): {error}", file=sys.stderr)
        return 1

    values = read_log(argv[1])
    figure = plt.figure(figsize=(8, 5), dpi=100)
    axes = figure.add_subplot()
    labels = {"kinetic_energy": "kinetic", "potential_energy": "elastic", "total_energy": "total"}
    for name, label in labels.items():
        axes.plot(values["time"], values[name], label=label, linewidth=1.5)
    positive = [v for name in labels for v in values[name] if v > 0.0]
    if positive and max(positive) > 1e3 * min(positive):
        axes.set_yscale("log")
    axes.set_xlabel("time")
    axes.set_ylabel("energy")
    axes.set_title("energy over time")
    axes.grid(True, alpha=0.3)
    axes.legend()
    figure.tight_layout()
    figure.savefig(argv[2], format="png", facecolor="white")
    plt.close(figure)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
