#pragma once
// The scenes dnurbs-bench times and measures (set-ups as in tests/dynamics, tests/superquadric,
// tests/grid): clamped D-NURBS strings and membranes, a spinning rigid superquadric, a pushed
// Terzopoulos sheet and a PDE surface with a deformation region.

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/grid/pde_surface.h"
#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"

namespace dnurbs::bench {

/// A cubic D-NURBS string on [0, 1] (x axis, Greville abscissae: a linear parametrization),
/// tension 1, rigidity `rigidity`, unit mass density, both end control points fixed.
DNurbsCurve clamped_string(int control_points, WeightMode mode, double rigidity = 1e-3,
                           int quadrature_points = 0);

/// A bicubic D-NURBS membrane on [0, 1]^2 (plane z = 0), a10 = a01 = 1, b20 = b02 = 1e-3,
/// damping `damping`, the border of the control net fixed.
DNurbsSurface clamped_membrane(int per_side, WeightMode mode, double damping = 0.0,
                               int quadrature_points = 0);

/// An asymmetric bent superellipsoid spinning and drifting freely (tests/superquadric), with
/// the given parts (rigid: 6 velocities).
System spinning_superquadric(const DeformableSuperquadricParts& parts);

/// Load factor of a force switched on smoothly over `ramp_time`: (1 - cos(pi t / ramp_time)) / 2
/// up to ramp_time, then 1 (a step load for ramp_time = 0). A smooth load keeps the grid's stiff
/// modes unexcited, so that time-step convergence is in its asymptotic range.
double smooth_ramp(double time, double ramp_time);

/// A 9 by 9 Terzopoulos sheet (unit square, border clamped, eta_ii = 0.1, xi = 1e-3, gamma =
/// 0.5) pushed down by 0.01 on its centre node, the force ramped over `ramp_time`.
System pushed_terzopoulos_sheet(double ramp_time = 0.0);

/// A biharmonic PDE surface on an n by n unit-square grid, damping 20, pushed by 1 on the
/// nodes within 0.08 of (0.5, 0.5) (ramped over `ramp_time`); with a deformation region of radius
/// 0.25 around it or (region = false) the whole grid simulated.
System pushed_pde_surface(int nodes_per_side, bool region, double ramp_time = 0.0);

}  // namespace dnurbs::bench
