#pragma once
// Quadrature over the deformable superquadric's (u, v) cells (file comment of
// dynamics/superquadric/deformable_superquadric_model.h): tensor Gauss-Legendre points per cell,
// graded toward the points where the signed powers |cos w|^e of the superellipsoid
// (Terzopoulos, "Deformable Models", eqs. 1.29-1.30) make the area element singular for e < 1.

#include <vector>

#include "dnurbs/surface/deformable_superquadric_shape.h"
#include "dnurbs/surface/parametric_fe_mesh.h"

namespace dnurbs {

/// The quadrature points (u, v, weight du dv, cell) of `mesh`'s cells, `points_per_direction`
/// Gauss-Legendre points per cell and direction. With `graded` and a squareness e1 (e2) below 1,
/// a cell ending at u (v) = k pi/2 maps its rule through w = w_s + (w_e - w_s) tau^(1/e) toward
/// that end (both ends: tau^p / (tau^p + (1 - tau)^p)), which makes |cos w|^e smooth in tau.
std::vector<ParameterQuadraturePoint> superquadric_quadrature_points(
    const ParametricFeMesh& mesh, const SuperquadricShapeParameters& shape,
    int points_per_direction, bool graded);

}  // namespace dnurbs
