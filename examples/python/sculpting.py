"""Sculpting a D-NURBS sheet with springs that follow keyframed paths, then exporting the result
as OBJ and glTF.

A cubic tensor-product D-NURBS surface (Terzopoulos, Deformable Models: Classic,
Topology-Adaptive and Generalized Formulations, eq. 1.27, thin plate under tension eq. 1.20),
clamped at its border, is pulled by two implicit springs whose targets move along keyframed
paths (monotone cubics through the keyframes); halfway, one spring is moved to a new
material point, and at the end it is removed and the sheet settles.

    PYTHONPATH=build/python python3 examples/python/sculpting.py --out sculpt-out
"""

import argparse
import pathlib

import numpy as np

import dnurbs


def flat_sheet(count):
    """A flat cubic sheet of count x count control points over [0, 1]^2."""
    knots = dnurbs.KnotVector.clamped_uniform(3, count)
    u, v = np.meshgrid(np.linspace(0, 1, count), np.linspace(0, 1, count), indexing="ij")
    net = np.stack([u, v, np.zeros_like(u)], axis=-1).reshape(-1, 3)
    return dnurbs.NurbsSurface(knots, knots, net)


def sculpt(out_dir, count=10, steps=300, dt=0.01):
    """Runs the sculpting session; writes sheet.obj and sheet.gltf into out_dir and returns a
    dict with the final heights of the two handles, the energies and the exported paths."""
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    model = dnurbs.DNurbsSurface(flat_sheet(count), mass_density=1.0, damping_density=3.0,
                                 a10=1.0, a01=1.0, b20=0.05, b11=0.05, b02=0.05)
    model.fix_border()
    system = dnurbs.System()
    system.add_model(model)
    duration = steps * dt
    # Two handles: one rises and stays, one rises, dips and rises again.
    rise = dnurbs.TargetTrajectory.keyframes(
        [0.0, 0.5 * duration, duration], [[0.35, 0.35, 0.0], [0.35, 0.35, 0.4], [0.35, 0.35, 0.4]])
    wave = dnurbs.TargetTrajectory.keyframes(
        [0.0, 0.3 * duration, 0.6 * duration, duration],
        [[0.7, 0.65, 0.0], [0.7, 0.65, 0.3], [0.7, 0.65, 0.1], [0.7, 0.65, 0.25]])
    handle = system.add_spring(0, [0.35, 0.35], rise, 40.0)
    second = system.add_spring(0, [0.7, 0.65], wave, 40.0)
    integrator = dnurbs.Integrator("implicit-euler")
    energies = []
    for step in range(steps):
        if step == steps // 2:
            # Move the first spring to a neighbouring material point (no refactorization).
            system.move_spring(handle, [0.4, 0.3], rise, 40.0)
        integrator.step(system, dt)
        energies.append((system.time, system.potential_energy(), system.spring_energy()))
    heights = (system.position(0, [0.4, 0.3])[2], system.position(0, [0.7, 0.65])[2])
    system.remove_spring(second)
    integrator.step(system, dt, count=steps // 4)
    sculpted = system.model(0)
    mesh = sculpted.tessellate(system.coordinates, segments_u=24, segments_v=24, name="sheet")
    paths = [out_dir / "sheet.obj", out_dir / "sheet.gltf"]
    for path in paths:
        dnurbs.export_meshes([mesh], path)
    return {"heights": heights, "energies": np.array(energies), "paths": paths,
            "surface": sculpted.exact_shape(system.coordinates), "mesh": mesh}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="sculpt-out", help="output folder")
    parser.add_argument("--steps", type=int, default=300)
    arguments = parser.parse_args()
    result = sculpt(arguments.out, steps=arguments.steps)
    print("handle heights at the end of the drag: %.4f %.4f" % result["heights"])
    print("wrote", ", ".join(str(path) for path in result["paths"]))


if __name__ == "__main__":
    main()
