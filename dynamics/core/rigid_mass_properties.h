#pragma once
// Mass properties of a rigid body (body frame): what a rigid part's M and gyroscopic force come
// from, so that stepping it never integrates over its surface.

#include <Eigen/Core>

namespace dnurbs {

/// Mass, centre of mass and inertia tensors of a body, in its body frame.
struct RigidMassProperties {
  double mass = 0.0;                                               ///< m = integral mu dA
  Eigen::Vector3d centre_of_mass = Eigen::Vector3d::Zero();        ///< (1/m) integral mu p dA
  Eigen::Matrix3d inertia_about_origin = Eigen::Matrix3d::Zero();  ///< integral mu [p]_x^T [p]_x
  Eigen::Matrix3d inertia_about_centre = Eigen::Matrix3d::Zero();  ///< parallel-axis shifted
};

}  // namespace dnurbs
