#pragma once
// The shapes of the default demo, built in code.

#include <Eigen/Core>

#include "nurbs/nurbs_surface.h"

namespace dnurbs::tools {

/// A bicubic 7 x 7 "hat" over [-1.2, 1.2]^2: a flat brim curling up at the rim and a crown raised
/// at the centre, whose nine middle control points carry weight 2.5 (a rational crown).
NurbsSurface hat_surface();

}  // namespace dnurbs::tools
