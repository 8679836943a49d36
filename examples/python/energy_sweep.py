"""A parameter sweep: the same released D-NURBS curve (a plucked string) for several damping
densities, its kinetic and elastic energy against time, plotted with matplotlib into a PNG.

The curve is a cubic D-NURBS string with tension (Terzopoulos, Deformable Models, eq. 1.2 and
1.25), both ends fixed, released from a bump at rest; Newmark's average-acceleration scheme
conserves the energy of the undamped string, and damping gamma makes it decay.

    PYTHONPATH=build/python python3 examples/python/energy_sweep.py --out sweep.png
"""

import argparse

import numpy as np

import dnurbs

TENSION = 4.0
# The elastic energy (w1/2) integral |x_u|^2 du of the straight string from (0, 0, 0) to
# (1, 0, 0) with linear parametrization, the least the string can have: what vibrates is the
# energy above it.
STRAIGHT_ENERGY = TENSION / 2


def plucked_string(damping, count=12):
    knots = dnurbs.KnotVector.clamped_uniform(3, count)
    x = np.linspace(0, 1, count)
    points = np.stack([x, np.zeros(count), 0.1 * np.sin(np.pi * x)], axis=-1)
    model = dnurbs.DNurbsCurve(dnurbs.NurbsCurve(knots, points), mass_density=1.0,
                               damping_density=damping, tension=TENSION)
    model.fix_point(0)
    model.fix_point(count - 1)
    # The tension energy (w1/2) integral |x_u|^2 is least for the straight string between the
    # fixed ends: released from the bump, the string vibrates about it.
    return model


def energy_history(damping, steps=400, dt=0.005):
    """Returns (time (steps + 1,), kinetic (steps + 1,), elastic (steps + 1,))."""
    system = dnurbs.System()
    system.add_model(plucked_string(damping))
    integrator = dnurbs.Integrator("newmark")
    rows = [(system.time, system.kinetic_energy(), system.potential_energy())]
    for _ in range(steps):
        integrator.step(system, dt)
        rows.append((system.time, system.kinetic_energy(), system.potential_energy()))
    rows = np.array(rows)
    return rows[:, 0], rows[:, 1], rows[:, 2]


def sweep(dampings, plot_path=None, steps=400, dt=0.005):
    """The energy histories of every damping; writes the plot to plot_path if given."""
    histories = {gamma: energy_history(gamma, steps, dt) for gamma in dampings}
    if plot_path is not None:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        figure, axes = plt.subplots(figsize=(7, 4))
        for gamma, (time, kinetic, elastic) in histories.items():
            axes.plot(time, kinetic + elastic - STRAIGHT_ENERGY, label=f"gamma = {gamma:g}")
        axes.set_xlabel("time")
        axes.set_ylabel("vibration energy (kinetic + elastic - straight)")
        axes.set_yscale("log")
        axes.legend()
        figure.tight_layout()
        figure.savefig(plot_path, dpi=100)
        plt.close(figure)
    return histories


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="energy_sweep.png", help="the plot (PNG)")
    arguments = parser.parse_args()
    histories = sweep([0.0, 0.5, 2.0], arguments.out)
    for gamma, (_, kinetic, elastic) in histories.items():
        vibration = kinetic + elastic - STRAIGHT_ENERGY
        print(f"gamma {gamma:g}: vibration energy {vibration[0]:.6g} -> {vibration[-1]:.6g}")
    print("wrote", arguments.out)


if __name__ == "__main__":
    main()
