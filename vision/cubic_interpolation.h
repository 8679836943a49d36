#pragma once
// Catmull-Rom cubic convolution weights (Keys, Cubic convolution interpolation for digital image
// processing, IEEE TASSP 29(6) 1981, a = -1/2): the 1-D factor of the bicubic and tricubic
// interpolation of sampled potentials. The interpolant passes through the samples, is C1, and
// reproduces quadratics, so its error is O(h^3) for values and O(h^2) for first derivatives.

#include <algorithm>
#include <array>
#include <cmath>

namespace dnurbs {

/// The four samples i-1..i+2 around a coordinate and their weights.
///
/// index       the four sample indices, clamped to [0, count - 1] (border samples repeat)
/// weight      the four interpolation weights at the coordinate (sum 1)
/// derivative  d weight / d coordinate (sum 0)
struct CubicStencil {
  std::array<int, 4> index{};
  std::array<double, 4> weight{};
  std::array<double, 4> derivative{};
};

/// The stencil at `coordinate` (in sample units, sample i at coordinate i) over `count`
/// samples; the caller has clamped the coordinate to [0, count - 1].
inline CubicStencil catmull_rom_stencil(double coordinate, int count) {
  const int base = std::clamp(static_cast<int>(std::floor(coordinate)), 0, std::max(count - 2, 0));
  const double t = coordinate - base;
  const double t2 = t * t;
  const double t3 = t2 * t;
  CubicStencil stencil;
  for (int k = 0; k < 4; ++k) {
    stencil.index[static_cast<std::size_t>(k)] = std::clamp(base - 1 + k, 0, count - 1);
  }
  stencil.weight = {0.5 * (-t3 + 2.0 * t2 - t), 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
                    0.5 * (-3.0 * t3 + 4.0 * t2 + t), 0.5 * (t3 - t2)};
  stencil.derivative = {0.5 * (-3.0 * t2 + 4.0 * t - 1.0), 0.5 * (9.0 * t2 - 10.0 * t),
                        0.5 * (-9.0 * t2 + 8.0 * t + 1.0), 0.5 * (3.0 * t2 - 2.0 * t)};
  return stencil;
}

}  // namespace dnurbs
