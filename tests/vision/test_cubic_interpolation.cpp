#include "dnurbs/vision/cubic_interpolation.h"

#include <gtest/gtest.h>

namespace dnurbs {
namespace {

TEST(CatmullRomStencil, WeightsInterpolateAndReproduceQuadratics) {
  for (int k = 0; k <= 20; ++k) {
    const double x = 3.0 + 0.05 * k;  // t from 0 to 1 over the span [3, 4]
    const CubicStencil stencil = catmull_rom_stencil(x, 10);
    double sum = 0.0;
    double derivative_sum = 0.0;
    double quadratic = 0.0;
    double quadratic_slope = 0.0;
    for (std::size_t i = 0; i < 4; ++i) {
      const double node = stencil.index[i];
      sum += stencil.weight[i];
      derivative_sum += stencil.derivative[i];
      quadratic += stencil.weight[i] * (node * node - 2.0 * node);
      quadratic_slope += stencil.derivative[i] * (node * node - 2.0 * node);
    }
    EXPECT_NEAR(sum, 1.0, 1e-15);
    EXPECT_NEAR(derivative_sum, 0.0, 1e-15);
    EXPECT_NEAR(quadratic, x * x - 2.0 * x, 1e-13);  // exact for degree <= 2 (Keys, a = -1/2)
    EXPECT_NEAR(quadratic_slope, 2.0 * x - 2.0, 1e-13);
  }
  const CubicStencil at_node = catmull_rom_stencil(5.0, 10);
  EXPECT_EQ(at_node.weight[1], 1.0);  // passes through the samples
  EXPECT_EQ(at_node.weight[0], 0.0);
}

TEST(CatmullRomStencil, DerivativeWeightsMatchFiniteDifferences) {
  const double h = 1e-7;
  for (int k = 1; k < 20; ++k) {
    const double x = 2.0 + 0.05 * k;
    const CubicStencil stencil = catmull_rom_stencil(x, 10);
    const CubicStencil plus = catmull_rom_stencil(x + h, 10);
    const CubicStencil minus = catmull_rom_stencil(x - h, 10);
    for (std::size_t i = 0; i < 4; ++i) {
      // Cubic weights: central differences exact to h^2 w''' / 6 ~ 1e-14, rounding ~1e-9.
      EXPECT_NEAR(stencil.derivative[i], (plus.weight[i] - minus.weight[i]) / (2.0 * h), 1e-8);
    }
  }
}

TEST(CatmullRomStencil, BorderSamplesRepeat) {
  const CubicStencil first = catmull_rom_stencil(0.25, 5);
  EXPECT_EQ(first.index, (std::array<int, 4>{0, 0, 1, 2}));
  const CubicStencil last = catmull_rom_stencil(4.0, 5);
  EXPECT_EQ(last.index, (std::array<int, 4>{2, 3, 4, 4}));
  EXPECT_NEAR(last.weight[2], 1.0, 1e-15);  // the end sample at t = 1 of the last span
}

}  // namespace
}  // namespace dnurbs
