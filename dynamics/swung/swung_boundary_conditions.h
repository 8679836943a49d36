#pragma once
// Boundary conditions of swung D-NURBS surfaces in their own coordinates (Qin & Terzopoulos,
// Dynamic NURBS swung surfaces for physics-based shape design, CAD 27(2) 1995): which
// coordinates to fix to hold a point of the control polygons or the surface's border. A swung
// surface has no 3-D control points among its coordinates; its points are the profile's and the
// trajectory's planar control points.

#include <vector>

#include "dnurbs/nurbs/swung_jacobian.h"
#include "dnurbs/surface/parametric_surface.h"

namespace dnurbs {

/// The in-plane coordinates of point i of the swung model (Model::fix_point): profile control
/// point i (x_i, z_i) for 0 <= i < m, trajectory control point i - m (X, Y) for
/// m <= i < m + n (m, n the profile's and trajectory's control point counts). A free weight
/// stays free. Throws Error naming i and the range otherwise.
std::vector<int> swung_point_coordinates(const SwungLayout& layout, int i);

/// The coordinates that hold every border edge of the surface fixed (Model::fix_border). An edge
/// of `domain` is a border unless its direction is periodic or it is a pole. Since
/// s(u, v) = (alpha p_x(u) t(v), p_z(u)):
///   - an edge u = u_start (or u_end) is the trajectory scaled by p_x there, at height p_z: fixed
///     by the profile control points whose basis functions do not vanish there (the end point of
///     a clamped profile) and the whole trajectory;
///   - an edge v = v_start (or v_end) is the profile swung to t there: fixed by the whole profile
///     and the trajectory control points whose basis functions do not vanish there.
/// In-plane coordinates only (free weights stay free, as DNurbsSurface::fix_border leaves them).
/// Sorted and distinct; empty for a closed surface (sphere, torus).
std::vector<int> swung_border_coordinates(const SwungSurface& surface, const SwungLayout& layout,
                                          const ParameterDomain& domain);

}  // namespace dnurbs
