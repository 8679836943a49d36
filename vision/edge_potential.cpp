#include "dnurbs/vision/edge_potential.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "dnurbs/core/error.h"
#include "dnurbs/vision/cubic_interpolation.h"
#include "dnurbs/vision/gaussian_filter.h"
#include "dnurbs/vision/volume.h"
#include "dnurbs/vision/volume_edge_potential.h"

namespace dnurbs {
namespace {

// What error messages call the potential.
const char* potential_name(const Image& /*image*/) {
  return "edge potential";
}
const char* potential_name(const Volume& /*volume*/) {
  return "volume edge potential";
}

// The number of samples along each axis: (width, height) or (nx, ny, nz).
std::array<int, 2> sample_counts(const Image& image) {
  return {image.width(), image.height()};
}
const std::array<int, 3>& sample_counts(const Volume& volume) {
  return volume.size;
}

double sample_at(const Image& image, const std::array<int, 2>& index) {
  return image(index[0], index[1]);
}
double sample_at(const Volume& volume, const std::array<int, 3>& index) {
  return volume(index[0], index[1], index[2]);
}

// Throws Error unless the image is at least 2 by 2 with finite pixels.
void check_samples(const Image& image) {
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
}

// Throws Error unless the volume has at least 2 voxels per side, all finite.
void check_samples(const Volume& volume) {
  if (*std::min_element(volume.size.begin(), volume.size.end()) < 2) {
    throw make_error("volume edge potential volume is ", volume.size[0], " by ", volume.size[1],
                     " by ", volume.size[2], ", needs at least 2 per side");
  }
  for (std::size_t i = 0; i < volume.values.size(); ++i) {
    if (!std::isfinite(volume.values[i])) {
      throw make_error("volume edge potential voxel ", i, " (x fastest) is ", volume.values[i]);
    }
  }
}

// The samples of an image or volume as one array (x fastest).
template <typename Samples>
Eigen::Map<Eigen::ArrayXd> flat(Samples& samples) {
  return {samples.values.data(), static_cast<Eigen::Index>(samples.values.size())};
}
template <typename Samples>
Eigen::Map<const Eigen::ArrayXd> flat(const Samples& samples) {
  return {samples.values.data(), static_cast<Eigen::Index>(samples.values.size())};
}

}  // namespace

template <int Dimension>
EdgePotential<Dimension>::EdgePotential(const Samples& data, double sigma, double c) {
  if (!std::isfinite(c)) {
    throw make_error(potential_name(data), " scale c = ", c, " is not finite");
  }
  check_samples(data);
  smoothed_ = gaussian_smooth(data, sigma);
  // P = -c |grad(G_sigma * I)| at every sample (Terzopoulos, below eq. 1.3).
  const std::array<Samples, Dimension> gradient = smoothed_gradient(data, sigma);
  Eigen::ArrayXd squared_norm = flat(gradient[0]).square();
  for (std::size_t axis = 1; axis < Dimension; ++axis) {
    squared_norm += flat(gradient[axis]).square();
  }
  potential_ = data;
  flat(potential_) = -c * squared_norm.sqrt();
}

template <int Dimension>
double EdgePotential<Dimension>::interpolate(const Samples& samples, const Point& point,
                                             Point* gradient) {
  if (!point.allFinite()) {
    if constexpr (Dimension == 2) {
      throw make_error(potential_name(samples), " point (", point.x(), ", ", point.y(),
                       ") is not finite");
    } else {
      throw make_error(potential_name(samples), " point (", point.x(), ", ", point.y(), ", ",
                       point.z(), ") is not finite");
    }
  }
  const std::array<int, Dimension> counts = sample_counts(samples);
  std::array<CubicStencil, Dimension> stencil;
  for (std::size_t axis = 0; axis < Dimension; ++axis) {
    const double coordinate = point[static_cast<Eigen::Index>(axis)];
    stencil[axis] =
        catmull_rom_stencil(std::clamp(coordinate, 0.0, counts[axis] - 1.0), counts[axis]);
  }
  // Tensor product of the stencils over the 4^Dimension samples around the point, x fastest:
  // value = sum_s sample_s prod_axis weight, and d/dx_a replaces the weight of axis a by its
  // derivative.
  double value = 0.0;
  Point d = Point::Zero();
  constexpr int kSampleCount = 1 << (2 * Dimension);
  for (int s = 0; s < kSampleCount; ++s) {
    std::array<std::size_t, Dimension> offset{};
    std::array<int, Dimension> index{};
    for (std::size_t axis = 0; axis < Dimension; ++axis) {
      offset[axis] = static_cast<std::size_t>((s >> (2 * axis)) & 3);
      index[axis] = stencil[axis].index[offset[axis]];
    }
    const double sample = sample_at(samples, index);
    double term = sample;
    for (std::size_t axis = 0; axis < Dimension; ++axis) {
      term *= stencil[axis].weight[offset[axis]];
    }
    value += term;
    for (std::size_t derivative = 0; derivative < Dimension; ++derivative) {
      double slope = sample;
      for (std::size_t axis = 0; axis < Dimension; ++axis) {
        slope *= axis == derivative ? stencil[axis].derivative[offset[axis]]
                                    : stencil[axis].weight[offset[axis]];
      }
      d[static_cast<Eigen::Index>(derivative)] += slope;
    }
  }
  if (gradient != nullptr) {
    *gradient = d;
  }
  return value;
}

template <int Dimension>
double EdgePotential<Dimension>::value(const Point& point) const {
  return interpolate(potential_, point, nullptr);
}

template <int Dimension>
typename EdgePotential<Dimension>::Point EdgePotential<Dimension>::gradient(
    const Point& point) const {
  Point result;
  interpolate(potential_, point, &result);
  return result;
}

template <int Dimension>
double EdgePotential<Dimension>::smoothed_intensity(const Point& point) const {
  return interpolate(smoothed_, point, nullptr);
}

template class EdgePotential<2>;
template class EdgePotential<3>;

}  // namespace dnurbs
