"""The cost of stepping from Python: a Python loop that steps a 20 x 20 D-NURBS sheet 1,000 times
against the same 1,000 steps looped in C++ (Integrator.step(system, dt, count=1000)), on two
copies of one system; prints both times and their ratio (target: at most 1.2) and checks that
both end in the same coordinates bit for bit.

    PYTHONPATH=build/python python3 bench/python/step_overhead.py [--steps 1000] [--repeats 5]
"""

import argparse
import copy
import time

import numpy as np

import dnurbs


def sheet_system(count=20):
    knots = dnurbs.KnotVector.clamped_uniform(3, count)
    u, v = np.meshgrid(np.linspace(0, 1, count), np.linspace(0, 1, count), indexing="ij")
    net = np.stack([u, v, np.zeros_like(u)], axis=-1).reshape(-1, 3)
    model = dnurbs.DNurbsSurface(dnurbs.NurbsSurface(knots, knots, net), damping_density=2.0,
                                 a10=1.0, a01=1.0, b20=0.01, b11=0.01, b02=0.01)
    model.fix_border()
    system = dnurbs.System()
    system.add_model(model)
    system.add_gravity(0, [0, 0, -1.0])
    system.add_spring(0, [0.5, 0.5], [0.5, 0.5, 0.3], 20.0)
    return system


def measure(steps, dt=0.01):
    python_system = sheet_system()
    cpp_system = copy.copy(python_system)
    python_integrator = dnurbs.Integrator("newmark")
    cpp_integrator = dnurbs.Integrator("newmark")
    # One step each first: the constant blocks are factored there, not in the timed loops.
    python_integrator.step(python_system, dt)
    cpp_integrator.step(cpp_system, dt)
    start = time.perf_counter()
    step = python_integrator.step
    for _ in range(steps):
        step(python_system, dt)
    python_seconds = time.perf_counter() - start
    start = time.perf_counter()
    cpp_integrator.step(cpp_system, dt, count=steps)
    cpp_seconds = time.perf_counter() - start
    if not np.array_equal(python_system.coordinates, cpp_system.coordinates):
        raise SystemExit("step_overhead: the two loops end in different coordinates")
    return python_seconds, cpp_seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=1000)
    parser.add_argument("--repeats", type=int, default=5)
    arguments = parser.parse_args()
    ratios = []
    for _ in range(arguments.repeats):
        python_seconds, cpp_seconds = measure(arguments.steps)
        ratios.append(python_seconds / cpp_seconds)
        print(f"python loop {python_seconds * 1e3:8.2f} ms   C++ loop {cpp_seconds * 1e3:8.2f} ms"
              f"   ratio {ratios[-1]:.3f}")
    print(f"median ratio {np.median(ratios):.3f} (target <= 1.2)")


if __name__ == "__main__":
    main()
