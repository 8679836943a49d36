#pragma once
// The potential that attracts deformable contours and surfaces to edges,
//   P(x) = -c |grad(G_sigma * I)(x)|
// (Terzopoulos, Deformable Models: Classic, Topology-Adaptive and Generalized Formulations, below
// eq. 1.3), of a 2-D image (ImageEdgePotential, here: the external force -grad P of the snake
// equations, eqs. 1.4, 1.5) or of a 3-D volume (VolumeEdgePotential,
// vision/volume_edge_potential.h: the volume setting of section 3.2), sampled at the pixels
// (voxels) and interpolated with its gradient by the tensor product of Catmull-Rom cubic
// convolution along each axis.

#include <type_traits>

#include <Eigen/Core>

#include "dnurbs/vision/image.h"

namespace dnurbs {

struct Volume;

/// P = -c |grad(G_sigma * I)| of one image (Dimension 2) or volume (Dimension 3), with the
/// smoothed data G_sigma * I.
///
/// Sampled at every pixel or voxel (the gradient by derivative-of-Gaussian kernels,
/// gaussian_filter.h) and interpolated between them by the tensor product of Catmull-Rom cubic
/// convolution along each axis (cubic_interpolation.h; 4 samples per axis): the interpolant passes
/// through the samples and is C1; its error is O(h^3) in values and O(h^2) in the gradient for
/// smooth data. gradient() is the exact gradient of the interpolant.
/// Points are in pixel (voxel) units, sample (x, y[, z]) at integer coordinates; a point outside
/// the data is first clamped to [0, #samples - 1] along each axis (so the gradient is that of
/// the clamped point).
template <int Dimension>
class EdgePotential {
 public:
  static_assert(Dimension == 2 || Dimension == 3, "edge potentials of images and volumes");
  /// The sampled data: Image (Dimension 2) or Volume (Dimension 3).
  using Samples = std::conditional_t<Dimension == 2, Image, Volume>;
  /// A point, or a gradient: Dimension coordinates.
  using Point = Eigen::Matrix<double, Dimension, 1>;

  /// Throws Error naming the value for sigma outside [0, kMaxGaussianSigma], c not finite, data
  /// with fewer than 2 samples along an axis, or a sample that is not finite.
  EdgePotential(const Samples& data, double sigma, double c);

  /// P at `point`.
  double value(const Point& point) const;
  /// grad P at `point`; the external force on a snake or T-surface node is -gradient.
  Point gradient(const Point& point) const;
  /// (G_sigma * I) at `point`, interpolated like P: the intensity that inflation forces test.
  double smoothed_intensity(const Point& point) const;

  /// P sampled at the pixels (voxels), the size of the data.
  const Samples& samples() const { return potential_; }
  /// G_sigma * I sampled at the pixels (voxels), the size of the data.
  const Samples& smoothed() const { return smoothed_; }

 private:
  /// Value and gradient of the cubic interpolant of `samples` at `point`.
  static double interpolate(const Samples& samples, const Point& point, Point* gradient);

  Samples potential_;
  Samples smoothed_;
};

/// The edge potential of an image: the external potential of snakes (TSnake). Points and
/// gradients are Eigen::Vector2d; samples() and smoothed() are width by height images.
using ImageEdgePotential = EdgePotential<2>;

extern template class EdgePotential<2>;

}  // namespace dnurbs
