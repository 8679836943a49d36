#pragma once
// Where a shape is sculpted (local sculpting, Model::freeze_outside): the material points that
// forces, springs and constraints act on, and the control points they act on directly.

#include <vector>

#include <Eigen/Core>

namespace dnurbs {

/// The parameters of the material points that forces, springs and constraints act on ((u, v);
/// v is ignored for curves), and the control points (or nodes) that forces or constraints act on
/// directly (indices).
struct SculptedRegion {
  std::vector<Eigen::Vector2d> parameters;
  std::vector<int> control_points;
};

}  // namespace dnurbs
