#!/usr/bin/env python3
# Regenerates the point sets of the scene "fit" tests (tests/io/test_scene_fit.cpp):
#   fit_surface_source.json  a bicubic clamped uniform B-spline surface (2 spans per direction)
#   fit_surface_points.xyz   12 x 12 points on it (parameters i / 11, j / 11, corners included)
#   fit_superquadric_points.xyz  16 x 24 points on a tapered superellipsoid, rotated and moved
# (sizes 1.2, 0.8, 0.6, squareness e1 0.7, e2 1.3, taper t1 0.2, t2 -0.1; rotation 0.5 rad
# about (1, 2, 3) / |(1, 2, 3)|; centre (0.3, -0.2, 0.5)). Run: python3 generate_fit_points.py
import json, math

KNOTS = [0, 0, 0, 0, 0.5, 1, 1, 1, 1]
DEGREE = 3
# Control points on the Greville grid (x = 2 u, y = 1.5 v exactly, by linear precision) with
# heights symmetric about the middle, so that the principal axes of the points are x, y, z and
# the fit's flat start projects every point to its own parameters.
GREVILLE = [0, 1 / 6, 0.5, 5 / 6, 1]
HEIGHT = [[0.0, 0.1, 0.3, 0.1, 0.0], [0.2, 0.4, 0.7, 0.4, 0.2], [0.1, 0.6, 0.9, 0.6, 0.1],
          [0.2, 0.4, 0.7, 0.4, 0.2], [0.0, 0.1, 0.3, 0.1, 0.0]]
CONTROL = [[[2 * GREVILLE[i], 1.5 * GREVILLE[j], HEIGHT[i][j]] for j in range(5)] for i in range(5)]

def basis(i, p, u):  # Cox-de Boor, the last span closed at u = 1
    if p == 0:
        last = KNOTS[i + 1] == KNOTS[-1] and KNOTS[i] < KNOTS[i + 1]
        return 1.0 if KNOTS[i] <= u < KNOTS[i + 1] or (last and u == KNOTS[-1]) else 0.0
    left = 0.0 if KNOTS[i + p] == KNOTS[i] else \
        (u - KNOTS[i]) / (KNOTS[i + p] - KNOTS[i]) * basis(i, p - 1, u)
    right = 0.0 if KNOTS[i + p + 1] == KNOTS[i + 1] else \
        (KNOTS[i + p + 1] - u) / (KNOTS[i + p + 1] - KNOTS[i + 1]) * basis(i + 1, p - 1, u)
    return left + right

def surface(u, v):
    return [sum(basis(i, DEGREE, u) * basis(j, DEGREE, v) * CONTROL[i][j][k]
                for i in range(5) for j in range(5)) for k in range(3)]

def signed_power(c, e):
    return math.copysign(abs(c) ** e, c)

def rotation(axis, angle):
    n = math.sqrt(sum(a * a for a in axis))
    x, y, z = (a / n for a in axis)
    c, s = math.cos(angle), math.sin(angle)
    return [[c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s],
            [y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s],
            [z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c)]]

def superquadric(u, v):
    a1, a2, a3, e1, e2, t1, t2 = 1.2, 0.8, 0.6, 0.7, 1.3, 0.2, -0.1
    cu, su = signed_power(math.cos(u), e1), signed_power(math.sin(u), e1)
    cv, sv = signed_power(math.cos(v), e2), signed_power(math.sin(v), e2)
    z = a3 * su
    p = [(t1 * z / a3 + 1) * a1 * cu * cv, (t2 * z / a3 + 1) * a2 * cu * sv, z]
    r = rotation([1, 2, 3], 0.5)
    centre = [0.3, -0.2, 0.5]
    return [centre[k] + sum(r[k][m] * p[m] for m in range(3)) for k in range(3)]

def write_points(name, points, header):
    with open(name, "w") as out:
        out.write("# " + header + " (generate_fit_points.py)\n")
        for p in points:
            out.write(" ".join(repr(float(x)) for x in p) + "\n")

with open("fit_surface_source.json", "w") as out:
    json.dump({"type": "nurbs_surface", "degree_u": DEGREE, "degree_v": DEGREE, "knots_u": KNOTS,
               "knots_v": KNOTS, "control_points": CONTROL}, out, indent=1)
    out.write("\n")
write_points("fit_surface_points.xyz",
             [surface(i / 11, j / 11) for i in range(12) for j in range(12)],
             "points on fit_surface_source.json")
write_points("fit_superquadric_points.xyz",
             [superquadric(-math.pi / 2 + math.pi * (i + 0.5) / 16, 2 * math.pi * j / 24)
              for i in range(16) for j in range(24)],
             "points on a tapered superellipsoid")
