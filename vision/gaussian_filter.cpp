#include "dnurbs/vision/gaussian_filter.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

void check_sigma(double sigma) {
  if (!(sigma >= 0.0 && sigma <= kMaxGaussianSigma)) {
    throw make_error("Gaussian width sigma = ", sigma, " is not in [0, ", kMaxGaussianSigma, "]");
  }
}

/// Convolves `data` (dimensions n, x fastest) with `kernel` along `axis`:
/// out(x) = sum_t in(clamp(x - t)) kernel(t), offsets t = -r..r.
void convolve_axis(std::vector<double>& data, const std::array<int, 3>& n, int axis,
                   const Eigen::VectorXd& kernel) {
  const int radius = static_cast<int>(kernel.size() / 2);
  if (radius == 0 && kernel(0) == 1.0) {
    return;
  }
  const long long stride = axis == 0 ? 1 : (axis == 1 ? n[0] : static_cast<long long>(n[0]) * n[1]);
  const int length = n[static_cast<std::size_t>(axis)];
  std::vector<double> line(static_cast<std::size_t>(length));
  const long long total = static_cast<long long>(n[0]) * n[1] * n[2];
  for (long long start = 0; start < total; ++start) {
    // A line starts where the coordinate along `axis` is 0.
    if ((start / stride) % length != 0) {
      continue;
    }
    for (int i = 0; i < length; ++i) {
      line[static_cast<std::size_t>(i)] = data[static_cast<std::size_t>(start + i * stride)];
    }
    for (int i = 0; i < length; ++i) {
      double sum = 0.0;
      for (int k = 0; k <= 2 * radius; ++k) {
        const int source = std::clamp(i - (k - radius), 0, length - 1);
        sum += line[static_cast<std::size_t>(source)] * kernel(k);
      }
      data[static_cast<std::size_t>(start + i * stride)] = sum;
    }
  }
}

/// Applies per-axis kernels (derivative_axis gets the derivative kernel, -1 for none).
std::vector<double> filter(const std::vector<double>& values, const std::array<int, 3>& n,
                           int dimension, double sigma, int derivative_axis) {
  std::vector<double> out = values;
  const Eigen::VectorXd smoothing = gaussian_kernel(sigma);
  const Eigen::VectorXd derivative = gaussian_derivative_kernel(sigma);
  for (int axis = 0; axis < dimension; ++axis) {
    convolve_axis(out, n, axis, axis == derivative_axis ? derivative : smoothing);
  }
  return out;
}

std::vector<double> image_samples(const Image& image) {
  return {image.values.data(), image.values.data() + image.values.size()};
}

Image image_from_samples(const std::vector<double>& samples, int width, int height) {
  Image image(width, height);
  std::copy(samples.begin(), samples.end(), image.values.data());
  return image;
}

}  // namespace

Eigen::VectorXd gaussian_kernel(double sigma) {
  check_sigma(sigma);
  if (sigma == 0.0) {
    return Eigen::VectorXd::Ones(1);
  }
  const int radius = static_cast<int>(std::ceil(5.0 * sigma));
  Eigen::VectorXd kernel(2 * radius + 1);
  for (int k = 0; k <= 2 * radius; ++k) {
    const double t = k - radius;
    kernel(k) = std::exp(-t * t / (2.0 * sigma * sigma));
  }
  return kernel / kernel.sum();
}

Eigen::VectorXd gaussian_derivative_kernel(double sigma) {
  check_sigma(sigma);
  if (sigma == 0.0) {
    return Eigen::Vector3d(0.5, 0.0, -0.5);
  }
  const Eigen::VectorXd gaussian = gaussian_kernel(sigma);
  const int radius = static_cast<int>(gaussian.size() / 2);
  Eigen::VectorXd kernel(gaussian.size());
  double moment = 0.0;  // sum of -t d(t), 1 for the exact derivative of a Gaussian
  for (int k = 0; k <= 2 * radius; ++k) {
    const double t = k - radius;
    kernel(k) = -t / (sigma * sigma) * gaussian(k);
    moment -= t * kernel(k);
  }
  return kernel / moment;
}

Image gaussian_smooth(const Image& image, double sigma) {
  const std::array<int, 3> n{image.width(), image.height(), 1};
  return image_from_samples(filter(image_samples(image), n, 2, sigma, -1), n[0], n[1]);
}

std::array<Image, 2> smoothed_gradient(const Image& image, double sigma) {
  const std::array<int, 3> n{image.width(), image.height(), 1};
  const std::vector<double> samples = image_samples(image);
  return {image_from_samples(filter(samples, n, 2, sigma, 0), n[0], n[1]),
          image_from_samples(filter(samples, n, 2, sigma, 1), n[0], n[1])};
}

Volume gaussian_smooth(const Volume& volume, double sigma) {
  Volume out = volume;
  out.values = filter(volume.values, volume.size, 3, sigma, -1);
  return out;
}

std::array<Volume, 3> smoothed_gradient(const Volume& volume, double sigma) {
  std::array<Volume, 3> out{volume, volume, volume};
  for (int axis = 0; axis < 3; ++axis) {
    out[static_cast<std::size_t>(axis)].values = filter(volume.values, volume.size, 3, sigma, axis);
  }
  return out;
}

}  // namespace dnurbs
