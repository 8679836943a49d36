#pragma once
// The shapes of the default demo, built in code.

#include <Eigen/Core>

#include "nurbs/nurbs_surface.h"

namespace dnurbs::tools {

/// A bicubic 7 x 7 "hat" over [-1.2, 1.2]^2: a flat brim curling up at the rim and a crown raised
/// at the centre, whose nine middle control points carry weight 2.5 (a rational crown).
NurbsSurface hat_surface();

/// The rational quadratic torus about the z axis through `centre`, periodic in both directions:
/// 8 x 8 distinct control points, period knots {0, 1/4, 1/4, 1/2, 1/2, 3/4, 3/4, 1, 1} in u
/// (around z) and v (around the tube), weights products of 1 and sqrt(2)/2. It is closed and
/// exact: every point lies at distance minor_radius from the tube's centre circle.
NurbsSurface periodic_torus(double major_radius, double minor_radius,
                            const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());

}  // namespace dnurbs::tools
