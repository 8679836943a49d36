"""Fitting a D-NURBS surface to a point cloud: a flat start over the cloud's principal plane,
then least squares plus a thin-plate smoothness energy with parameter correction
(design/dnurbs_fitting.h), the fitted surface exported as OBJ.

    PYTHONPATH=build/python python3 examples/python/fit_point_cloud.py --out fit.obj
"""

import argparse

import numpy as np

import dnurbs


def dome_points(count=30, seed=1, noise=0.0):
    """count^2 samples of the dome z = 0.3 (1 - x^2 - y^2) over [-1, 1]^2 (plus noise)."""
    rng = np.random.default_rng(seed)
    x, y = np.meshgrid(np.linspace(-1, 1, count), np.linspace(-1, 1, count), indexing="ij")
    z = 0.3 * (1 - x ** 2 - y ** 2) + noise * rng.standard_normal(x.shape)
    return np.stack([x, y, z], axis=-1).reshape(-1, 3)


def fit(points, degree=3, spans=4, smoothness=0.0):
    """Returns (fitted NurbsSurface, fit result dict)."""
    start = dnurbs.principal_plane_surface(points, degree, spans)
    model = dnurbs.DNurbsSurface(start, a10=1.0, a01=1.0, b20=1.0, b11=1.0, b02=1.0)
    result = dnurbs.fit_dnurbs_surface(model, points, smoothness=smoothness)
    return model.surface(result["coordinates"]), result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="fit.obj", help="the fitted surface's mesh")
    arguments = parser.parse_args()
    points = dome_points(noise=0.002)
    surface, result = fit(points, smoothness=1e-4)
    print(f"{result['iterations']} iterations, rms error {result['rms_error']:.3g}, "
          f"max error {result['max_error']:.3g}")
    u, v = np.meshgrid(np.linspace(0, 1, 25), np.linspace(0, 1, 25), indexing="ij")
    vertices = surface(u, v).reshape(-1, 3)
    index = np.arange(25 * 25).reshape(25, 25)
    quads = np.stack([index[:-1, :-1], index[1:, :-1], index[1:, 1:], index[:-1, 1:]], axis=-1)
    triangles = np.concatenate([quads[..., [0, 1, 2]].reshape(-1, 3),
                                quads[..., [0, 2, 3]].reshape(-1, 3)])
    dnurbs.export_meshes([dnurbs.TriangleMesh(vertices, triangles, name="fit")], arguments.out)
    print("wrote", arguments.out)


if __name__ == "__main__":
    main()
