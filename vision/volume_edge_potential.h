#pragma once
// The 3-D edge potential P(x) = -c |grad(G_sigma * V)(x)| of a volume image (Terzopoulos,
// Deformable Models: Classic, Topology-Adaptive and Generalized Formulations, below eq. 1.3, in
// the volume setting of section 3.2), sampled at the voxels and interpolated tricubically.

#include <Eigen/Core>

#include "vision/volume.h"

namespace dnurbs {

/// P = -c |grad(G_sigma * V)| of one volume, with the smoothed volume G_sigma * V.
///
/// Sampled at every voxel and interpolated by the tensor product of Catmull-Rom cubic convolution
/// along x, y, z (64 samples; O(h^3) error in values, O(h^2) in the gradient for smooth data);
/// gradient() is the exact gradient of the interpolant. Points are in voxel units and are clamped
/// to the volume's box before interpolation.
class VolumeEdgePotential {
 public:
  /// Throws Error naming the value for sigma outside [0, kMaxGaussianSigma], c not finite or a
  /// volume with a side below 2.
  VolumeEdgePotential(const Volume& volume, double sigma, double c);

  /// P at `point` (3 coordinates).
  double value(const Eigen::Vector3d& point) const;
  /// grad P at `point` (3 components); the external force on a surface node is -gradient.
  Eigen::Vector3d gradient(const Eigen::Vector3d& point) const;
  /// (G_sigma * V) at `point`, interpolated like P.
  double smoothed_intensity(const Eigen::Vector3d& point) const;

  /// P sampled at the voxels.
  const Volume& samples() const { return potential_; }
  /// G_sigma * V sampled at the voxels.
  const Volume& smoothed() const { return smoothed_; }

 private:
  static double interpolate(const Volume& samples, const Eigen::Vector3d& point,
                            Eigen::Vector3d* gradient);

  Volume potential_;
  Volume smoothed_;
};

}  // namespace dnurbs
