#include "vision/edge_potential.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "vision/cubic_interpolation.h"
#include "vision/gaussian_filter.h"

namespace dnurbs {

ImageEdgePotential::ImageEdgePotential(const Image& image, double sigma, double c) {
  if (!std::isfinite(c)) {
    throw make_error("edge potential scale c = ", c, " is not finite");
  }
  if (image.width() < 2 || image.height() < 2) {
    throw make_error("edge potential image is ", image.width(), " by ", image.height(),
                     ", needs at least 2 by 2");
  }
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if (!std::isfinite(image(x, y))) {
        throw make_error("edge potential image pixel (", x, ", ", y, ") is ", image(x, y));
      }
    }
  }
  smoothed_ = gaussian_smooth(image, sigma);
  // P = -c |grad(G_sigma * I)| at every pixel (Terzopoulos, below eq. 1.3).
  const std::array<Image, 2> gradient = smoothed_gradient(image, sigma);
  potential_ = Image(image.width(), image.height());
  potential_.values = -c * (gradient[0].values.square() + gradient[1].values.square()).sqrt();
}

double ImageEdgePotential::interpolate(const Image& samples, const Eigen::Vector2d& point,
                                       Eigen::Vector2d* gradient) {
  if (!point.allFinite()) {
    throw make_error("edge potential point (", point.x(), ", ", point.y(), ") is not finite");
  }
  const double x = std::clamp(point.x(), 0.0, samples.width() - 1.0);
  const double y = std::clamp(point.y(), 0.0, samples.height() - 1.0);
  const CubicStencil sx = catmull_rom_stencil(x, samples.width());
  const CubicStencil sy = catmull_rom_stencil(y, samples.height());
  double value = 0.0;
  double d_x = 0.0;
  double d_y = 0.0;
  for (std::size_t j = 0; j < 4; ++j) {
    for (std::size_t i = 0; i < 4; ++i) {
      const double sample = samples(sx.index[i], sy.index[j]);
      value += sample * sx.weight[i] * sy.weight[j];
      d_x += sample * sx.derivative[i] * sy.weight[j];
      d_y += sample * sx.weight[i] * sy.derivative[j];
    }
  }
  if (gradient != nullptr) {
    *gradient = Eigen::Vector2d(d_x, d_y);
  }
  return value;
}

double ImageEdgePotential::value(const Eigen::Vector2d& point) const {
  return interpolate(potential_, point, nullptr);
}

Eigen::Vector2d ImageEdgePotential::gradient(const Eigen::Vector2d& point) const {
  Eigen::Vector2d result;
  interpolate(potential_, point, &result);
  return result;
}

double ImageEdgePotential::smoothed_intensity(const Eigen::Vector2d& point) const {
  return interpolate(smoothed_, point, nullptr);
}

}  // namespace dnurbs
