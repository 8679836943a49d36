#include "dnurbs/core/rotation.h"

#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& p) {
  Eigen::Matrix3d m;
  m << 0.0, -p.z(), p.y(), p.z(), 0.0, -p.x(), -p.y(), p.x(), 0.0;
  return m;
}

Eigen::Quaterniond unit_quaternion(const Eigen::Ref<const Eigen::Vector4d>& coordinates) {
  const double norm = coordinates.norm();
  if (!(norm > 0.0) || !std::isfinite(norm)) {
    throw make_error("quaternion (", coordinates[0], ", ", coordinates[1], ", ", coordinates[2],
                     ", ", coordinates[3], ") has norm ", norm,
                     " (expected a finite non-zero norm)");
  }
  return Eigen::Quaterniond(coordinates[0] / norm, coordinates[1] / norm, coordinates[2] / norm,
                            coordinates[3] / norm);
}

Eigen::Quaterniond quaternion_exp(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  const double half = 0.5 * angle;
  // sin(half)/angle, by its Taylor series where the quotient loses digits.
  const double sinc = angle < 1e-4 ? 0.5 - angle * angle / 48.0 : std::sin(half) / angle;
  return Eigen::Quaterniond(std::cos(half), sinc * w.x(), sinc * w.y(), sinc * w.z());
}

Eigen::Quaterniond cayley(const Eigen::Vector3d& hw) {
  return Eigen::Quaterniond(1.0, 0.5 * hw.x(), 0.5 * hw.y(), 0.5 * hw.z()).normalized();
}

}  // namespace dnurbs
