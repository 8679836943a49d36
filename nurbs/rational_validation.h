#pragma once
// Checks shared by curves and surfaces on their control points and weights.

#include <Eigen/Core>

namespace dnurbs {

/// Throws Error unless `control_points` has `expected_count` rows of finite values.
void check_control_points(const Eigen::MatrixX3d& control_points, int expected_count);
/// Throws Error unless `weights` has `expected_count` finite, positive entries.
void check_weights(const Eigen::VectorXd& weights, int expected_count);

}  // namespace dnurbs
