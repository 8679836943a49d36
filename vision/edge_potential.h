#pragma once
// The image potential that attracts snakes to edges, P(x, y) = -c |grad(G_sigma * I)(x, y)|
// (Terzopoulos, Deformable Models: Classic, Topology-Adaptive and Generalized Formulations, below
// eq. 1.3), sampled at the pixels and interpolated bicubically with its gradient, the external
// force -grad P of the snake equations (eqs. 1.4, 1.5).

#include <Eigen/Core>

#include "vision/image.h"

namespace dnurbs {

/// P = -c |grad(G_sigma * I)| of one image, with the smoothed image G_sigma * I.
///
/// Sampled at every pixel (the gradient by derivative-of-Gaussian kernels, gaussian_filter.h) and
/// interpolated between pixels by Catmull-Rom bicubic convolution (cubic_interpolation.h): the
/// interpolant passes through the samples and is C1; its error is O(h^3) in values and O(h^2) in
/// the gradient for smooth data. gradient() is the exact gradient of the interpolant.
/// Points are in pixel units (pixel (x, y) at integer x, y); points outside the image are first
/// clamped to [0, width - 1] by [0, height - 1] (so the gradient is that of the clamped point).
class ImageEdgePotential {
 public:
  /// Throws Error naming the value for sigma outside [0, kMaxGaussianSigma], c not finite or an
  /// image smaller than 2 by 2.
  ImageEdgePotential(const Image& image, double sigma, double c);

  /// P at `point` (2 coordinates).
  double value(const Eigen::Vector2d& point) const;
  /// grad P at `point` (2 components); the external force on a snake node is -gradient.
  Eigen::Vector2d gradient(const Eigen::Vector2d& point) const;
  /// (G_sigma * I) at `point`, interpolated like P: the intensity that inflation forces test.
  double smoothed_intensity(const Eigen::Vector2d& point) const;

  /// P sampled at the pixels (width by height).
  const Image& samples() const { return potential_; }
  /// G_sigma * I sampled at the pixels (width by height).
  const Image& smoothed() const { return smoothed_; }
  int width() const { return potential_.width(); }
  int height() const { return potential_.height(); }

 private:
  /// Value and gradient of the bicubic interpolant of `samples` at `point`.
  static double interpolate(const Image& samples, const Eigen::Vector2d& point,
                            Eigen::Vector2d* gradient);

  Image potential_;
  Image smoothed_;
};

}  // namespace dnurbs
