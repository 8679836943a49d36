#include "dnurbs/vision/edge_potential.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "../common/error_message.h"
#include "vision_test_images.h"

namespace dnurbs {
namespace {

using testing::coverage_image;
using testing::disc;
using testing::error_message;

Image gaussian_blob_image(int size, const Eigen::Vector2d& center, double s) {
  Image image(size, size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      image(x, y) = std::exp(-(Eigen::Vector2d(x, y) - center).squaredNorm() / (2.0 * s * s));
    }
  }
  return image;
}

TEST(ImageEdgePotential, GradientMatchesFiniteDifferencesOfTheInterpolant) {
  const Image image = coverage_image(48, 48, disc(Eigen::Vector2d(23.4, 24.1), 12.0));
  const ImageEdgePotential potential(image, 1.5, 2.0);
  const double h = 1e-6;
  double worst = 0.0;
  for (int k = 0; k < 200; ++k) {
    // Points spread over the image, avoiding exact integers (where the cubic pieces meet, the
    // interpolant is C1 but a one-sided difference could straddle two pieces).
    const Eigen::Vector2d p(1.3 + 0.2317 * k, 1.7 + 0.2113 * ((k * 7) % 200));
    const Eigen::Vector2d analytic = potential.gradient(p);
    const Eigen::Vector2d numeric(
        (potential.value(p + Eigen::Vector2d(h, 0)) - potential.value(p - Eigen::Vector2d(h, 0))) /
            (2 * h),
        (potential.value(p + Eigen::Vector2d(0, h)) - potential.value(p - Eigen::Vector2d(0, h))) /
            (2 * h));
    worst = std::max(worst, (analytic - numeric).norm());
  }
  // Central differences: truncation h^2 |P'''| / 6 ~ 1e-13, rounding 1e-16 |P| / h ~ 1e-10.
  EXPECT_LT(worst, 1e-8);
}

TEST(ImageEdgePotential, InterpolationPassesThroughSamplesAndReproducesQuadratics) {
  Image quadratic(24, 20);
  const auto q = [](double x, double y) {
    return 0.01 * x * x + 0.02 * x * y - 0.03 * y * y + 0.1 * x;
  };
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 24; ++x) {
      quadratic(x, y) = q(x, y);
    }
  }
  const ImageEdgePotential potential(quadratic, 0.0, 1.0);  // sigma 0: smoothed = image
  for (int k = 0; k < 50; ++k) {
    // Catmull-Rom cubic convolution reproduces polynomials of degree <= 2 away from the border.
    const Eigen::Vector2d p(1.0 + 0.41 * k, 1.0 + 0.33 * k);
    EXPECT_NEAR(potential.smoothed_intensity(p), q(p.x(), p.y()), 1e-12);
  }
  for (int y = 0; y < 20; y += 3) {
    for (int x = 0; x < 24; x += 5) {
      EXPECT_NEAR(potential.value(Eigen::Vector2d(x, y)), potential.samples()(x, y), 1e-14);
    }
  }
}

/// Largest errors of P and grad P against the closed form on a blob of width s = 4m smoothed with
/// sigma = m (the same blob seen at pixel size h = 1/m), relative to the peak |P| and |grad P|.
std::pair<double, double> blob_potential_errors(int m) {
  // P = -c |grad(G_sigma * I)| of I = exp(-r^2 / 2s^2) is -c (s^2/t^2) r / t^2 exp(-r^2 / 2t^2),
  // t^2 = s^2 + sigma^2; its gradient is radial with d/dr of that.
  const double s = 4.0 * m;
  const double sigma = m;
  const double c = 3.0;
  const double t2 = s * s + sigma * sigma;
  const Eigen::Vector2d center = m * Eigen::Vector2d(24.3, 23.8);
  const ImageEdgePotential potential(gaussian_blob_image(48 * m + 1, center, s), sigma, c);
  const double peak = c * s * s / t2 / std::sqrt(t2) * std::exp(-0.5);
  const double peak_slope = c * s * s / (t2 * t2);
  double value_error = 0.0;
  double gradient_error = 0.0;
  for (int k = 0; k < 100; ++k) {
    const double angle = 0.37 * k;
    // |grad| is a cone at the centre (not smooth there); the cubic error bound needs r >~ 2h.
    const double r = m * (3.0 + 0.1 * k);
    const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
    const Eigen::Vector2d p = center + r * direction;
    const double e = std::exp(-r * r / (2.0 * t2));
    const double exact = -c * s * s / t2 * r / t2 * e;
    const double exact_slope = -c * s * s / (t2 * t2) * (1.0 - r * r / t2) * e;
    value_error = std::max(value_error, std::abs(potential.value(p) - exact) / peak);
    gradient_error = std::max(
        gradient_error, (potential.gradient(p) - exact_slope * direction).norm() / peak_slope);
  }
  return {value_error, gradient_error};
}

TEST(ImageEdgePotential, GaussianBlobPotentialConvergesToTheAnalyticEdgeStrength) {
  const auto [value_1, gradient_1] = blob_potential_errors(1);
  const auto [value_2, gradient_2] = blob_potential_errors(2);
  const auto [value_4, gradient_4] = blob_potential_errors(4);
  std::printf(
      "blob potential relative errors at h = 1, 1/2, 1/4: P %.2e %.2e %.2e, grad P %.2e "
      "%.2e %.2e\n",
      value_1, value_2, value_4, gradient_1, gradient_2, gradient_4);
  // Bicubic (Catmull-Rom) interpolation: O(h^3) in values, O(h^2) in the gradient. Measured
  // value orders 4.0 (h = 1 -> 1/2) and 1.9 (1/2 -> 1/4), 3.0 over h = 1 -> 1/4; gradient orders
  // 2.3 and 2.0. (The Gaussian filter's own error, 1e-8 in test_gaussian_filter, is far below.)
  EXPECT_GT(std::log2(value_1 / value_4) / 2.0, 2.5);
  EXPECT_GT(std::log2(gradient_1 / gradient_2), 1.7);
  EXPECT_GT(std::log2(gradient_2 / gradient_4), 1.7);
  // At one pixel per quarter of the blob's width the errors are already small.
  EXPECT_LT(value_1, 5e-3);
  EXPECT_LT(gradient_1, 5e-2);
}

TEST(ImageEdgePotential, DiscEdgeIsTheMinimumOfThePotential) {
  const double radius = 15.0;
  const Eigen::Vector2d center(32.4, 31.8);
  const double sigma = 1.5;
  const ImageEdgePotential potential(coverage_image(64, 64, disc(center, radius)), sigma, 1.0);
  for (int k = 0; k < 16; ++k) {
    const double angle = 2.0 * M_PI * k / 16.0 + 0.1;
    const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
    double best_r = 0.0;
    double best = 0.0;
    for (double r = radius - 4.0; r <= radius + 4.0; r += 0.005) {
      const double value = potential.value(center + r * direction);
      if (value < best) {
        best = value;
        best_r = r;
      }
    }
    // The edge-strength maximum of a blurred disc sits sigma^2 / (2R) = 0.075 px inside the
    // circle; pixel-coverage sampling and bicubic interpolation add < 0.1 px.
    EXPECT_NEAR(best_r, radius - sigma * sigma / (2.0 * radius), 0.1) << "angle " << angle;
    // At the minimum the radial gradient vanishes (to the 0.005 px search step times |P''|).
    EXPECT_LT(std::abs(potential.gradient(center + best_r * direction).dot(direction)), 2e-3);
  }
}

TEST(ImageEdgePotential, BadInputIsNamed) {
  EXPECT_NE(error_message([] { ImageEdgePotential(Image(1, 5), 1.0, 1.0); }).find("1 by 5"),
            std::string::npos);
  EXPECT_NE(error_message([] { ImageEdgePotential(Image(5, 5), 1.0, INFINITY); }).find("c = inf"),
            std::string::npos);
  Image with_nan(5, 5);
  with_nan(3, 2) = NAN;
  EXPECT_NE(
      error_message([&] { ImageEdgePotential(with_nan, 1.0, 1.0); }).find("pixel (3, 2) is nan"),
      std::string::npos);
  const ImageEdgePotential potential(Image(5, 5), 1.0, 1.0);
  EXPECT_NE(error_message([&] { potential.value(Eigen::Vector2d(NAN, 1.0)); }).find("not finite"),
            std::string::npos);
}

}  // namespace
}  // namespace dnurbs
