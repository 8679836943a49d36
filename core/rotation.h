#pragma once
// Rotations of rigid parts: the cross-product matrix, the exponential map of a body-frame
// rotation vector and the Cayley map, all as unit quaternions where they give a rotation
// (orientations are advanced by these maps, never by adding to quaternion components).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace dnurbs {

/// [p]_x, the 3 x 3 matrix with [p]_x v = p x v.
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& p);

/// The unit quaternion of coordinates (w, x, y, z) (a 4-vector), divided by its norm; throws
/// Error naming the norm if it is zero or not finite.
Eigen::Quaterniond unit_quaternion(const Eigen::Ref<const Eigen::Vector4d>& coordinates);

/// exp([w]_x) as a unit quaternion: (cos(|w|/2), sin(|w|/2) w / |w|), accurate for small |w|.
Eigen::Quaterniond quaternion_exp(const Eigen::Vector3d& w);

/// The Cayley map cay([hw]_x) = (I - [hw]_x / 2)^-1 (I + [hw]_x / 2) as a unit quaternion,
/// proportional to (1, hw / 2): a second-order approximation of exp used by midpoint rules.
Eigen::Quaterniond cayley(const Eigen::Vector3d& hw);

}  // namespace dnurbs
