#pragma once
// The scaling gauge of swung coordinates (Qin & Terzopoulos, Dynamic NURBS swung surfaces for
// physics-based shape design, CAD 27(2) 1995): s = (alpha p_x t, p_z) does not change when the
// profile's x coordinates are scaled by c and the trajectory by 1/c, so the motion
//   g = d/dc (c x_i, z_i, 1/c T_j)|_{c=1} = (x_i, 0 | -X_j, -Y_j)
// moves nothing and M is singular along it. Fixing one coordinate with g_k != 0 removes it;
// fixing a second one (or a whole curve) turns that gauge coordinate into a real constraint.

#include <vector>

#include <Eigen/Core>

#include "dnurbs/nurbs/swung_jacobian.h"

namespace dnurbs {

/// The gauge direction g at q (layout's size): x_i on profile x coordinates, -X_j and -Y_j on
/// the trajectory's, 0 on profile z coordinates and weights. Throws Error if q has the wrong
/// size.
Eigen::VectorXd swung_scaling_gauge_direction(const SwungLayout& layout, const Eigen::VectorXd& q);

/// The coordinate fixed to remove the gauge: the profile x of largest magnitude, ties going to
/// the control point nearest the middle of the profile (a sphere's equator point). Throws Error
/// if every profile x is 0 (the surface is degenerate: no gauge coordinate).
int swung_scaling_gauge_coordinate(const SwungLayout& layout, const Eigen::VectorXd& q);

/// True if fixing `coordinates` already removes the gauge without the gauge coordinate
/// `gauge`: some listed coordinate other than `gauge` has g_k != 0 at q.
bool fixes_swung_scaling_gauge(const SwungLayout& layout, const Eigen::VectorXd& q, int gauge,
                               const std::vector<int>& coordinates);

}  // namespace dnurbs
