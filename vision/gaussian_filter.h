#pragma once
// Separable Gaussian smoothing G_sigma * I and the gradient grad(G_sigma * I) of images and
// volumes (Terzopoulos, Deformable Models: Classic, Topology-Adaptive and Generalized
// Formulations, the edge potential below eq. 1.3), by sampled Gaussian and derivative-of-Gaussian
// kernels applied one axis at a time.

#include <array>

#include <Eigen/Core>

#include "dnurbs/vision/image.h"
#include "dnurbs/vision/volume.h"

namespace dnurbs {

/// Largest smoothing width accepted (in pixels or voxels).
inline constexpr double kMaxGaussianSigma = 256.0;

/// The sampled, normalized Gaussian G_sigma on taps t = -r..r, r = ceil(5 sigma) (the cut tail
/// holds 6e-7 of the mass).
///
/// kernel  2r+1 weights summing to 1; kernel(k) is the weight of offset t = k - r.
/// sigma = 0 gives the identity kernel {1}. Throws Error naming sigma if it is negative, NaN or
/// over kMaxGaussianSigma.
Eigen::VectorXd gaussian_kernel(double sigma);

/// The sampled derivative of G_sigma, d(t) = -t / sigma^2 G_sigma(t) on t = -r..r, scaled so that
/// convolving f(x) = x gives exactly 1 (sum of -t d(t) = 1). sigma = 0 gives the central
/// difference {1/2, 0, -1/2}. Same errors as gaussian_kernel.
Eigen::VectorXd gaussian_derivative_kernel(double sigma);

/// G_sigma * I: the image convolved with gaussian_kernel along x, then along y; samples past the
/// border repeat the border sample.
Image gaussian_smooth(const Image& image, double sigma);

/// grad(G_sigma * I) at every pixel: {d/dx, d/dy}, each the image convolved with the derivative
/// kernel along its axis and the Gaussian along the other (borders as gaussian_smooth).
std::array<Image, 2> smoothed_gradient(const Image& image, double sigma);

/// G_sigma * V for a volume, along x, y and z (borders as for images).
Volume gaussian_smooth(const Volume& volume, double sigma);

/// grad(G_sigma * V) at every voxel: {d/dx, d/dy, d/dz}.
std::array<Volume, 3> smoothed_gradient(const Volume& volume, double sigma);

}  // namespace dnurbs
