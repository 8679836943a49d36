#include "vision/volume_edge_potential.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "vision/cubic_interpolation.h"
#include "vision/gaussian_filter.h"

namespace dnurbs {

VolumeEdgePotential::VolumeEdgePotential(const Volume& volume, double sigma, double c) {
  if (!std::isfinite(c)) {
    throw make_error("volume edge potential scale c = ", c, " is not finite");
  }
  if (*std::min_element(volume.size.begin(), volume.size.end()) < 2) {
    throw make_error("volume edge potential volume is ", volume.size[0], " by ", volume.size[1],
                     " by ", volume.size[2], ", needs at least 2 per side");
  }
  for (std::size_t i = 0; i < volume.values.size(); ++i) {
    if (!std::isfinite(volume.values[i])) {
      throw make_error("volume edge potential voxel ", i, " (x fastest) is ", volume.values[i]);
    }
  }
  smoothed_ = gaussian_smooth(volume, sigma);
  // P = -c |grad(G_sigma * V)| at every voxel (Terzopoulos, below eq. 1.3).
  const std::array<Volume, 3> gradient = smoothed_gradient(volume, sigma);
  potential_ = volume;
  for (std::size_t i = 0; i < potential_.values.size(); ++i) {
    potential_.values[i] = -c * std::sqrt(gradient[0].values[i] * gradient[0].values[i] +
                                          gradient[1].values[i] * gradient[1].values[i] +
                                          gradient[2].values[i] * gradient[2].values[i]);
  }
}

double VolumeEdgePotential::interpolate(const Volume& samples, const Eigen::Vector3d& point,
                                        Eigen::Vector3d* gradient) {
  if (!point.allFinite()) {
    throw make_error("volume edge potential point (", point.x(), ", ", point.y(), ", ", point.z(),
                     ") is not finite");
  }
  std::array<CubicStencil, 3> stencil;
  for (int axis = 0; axis < 3; ++axis) {
    const int count = samples.size[static_cast<std::size_t>(axis)];
    stencil[static_cast<std::size_t>(axis)] =
        catmull_rom_stencil(std::clamp(point[axis], 0.0, count - 1.0), count);
  }
  const auto& [sx, sy, sz] = stencil;
  double value = 0.0;
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::size_t j = 0; j < 4; ++j) {
      for (std::size_t i = 0; i < 4; ++i) {
        const double sample = samples(sx.index[i], sy.index[j], sz.index[k]);
        value += sample * sx.weight[i] * sy.weight[j] * sz.weight[k];
        d.x() += sample * sx.derivative[i] * sy.weight[j] * sz.weight[k];
        d.y() += sample * sx.weight[i] * sy.derivative[j] * sz.weight[k];
        d.z() += sample * sx.weight[i] * sy.weight[j] * sz.derivative[k];
      }
    }
  }
  if (gradient != nullptr) {
    *gradient = d;
  }
  return value;
}

double VolumeEdgePotential::value(const Eigen::Vector3d& point) const {
  return interpolate(potential_, point, nullptr);
}

Eigen::Vector3d VolumeEdgePotential::gradient(const Eigen::Vector3d& point) const {
  Eigen::Vector3d result;
  interpolate(potential_, point, &result);
  return result;
}

double VolumeEdgePotential::smoothed_intensity(const Eigen::Vector3d& point) const {
  return interpolate(smoothed_, point, nullptr);
}

}  // namespace dnurbs
