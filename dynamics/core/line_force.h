#pragma once
// A line of forces (Wu & de Melo, figures 10 and 11: "the same force along its upper line" opens a
// curtain): one force f(t) applied at each of several material points.

#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"

namespace dnurbs {

/// sum_k L(u_k)^T f(t): the same force at every point u_k (e.g. Grid::row_parameters(0), a
/// grid's first row). Throws Error if there are no points, a point is not finite or the force
/// function is empty.
Force line_force(std::vector<Eigen::Vector2d> points, VectorOfTime force);

}  // namespace dnurbs
