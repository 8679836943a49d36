#include "dnurbs/vision/volume_edge_potential.h"

#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "../common/error_message.h"

namespace dnurbs {
namespace {

using testing::error_message;

Volume sampled_volume(int n, const std::function<double(const Eigen::Vector3d&)>& f) {
  Volume volume(n, n, n);
  for (int z = 0; z < n; ++z) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        volume(x, y, z) = f(Eigen::Vector3d(x, y, z));
      }
    }
  }
  return volume;
}

TEST(VolumeEdgePotential, GradientMatchesFiniteDifferencesOfTheInterpolant) {
  const Eigen::Vector3d center(8.3, 7.9, 8.1);
  const Volume volume = sampled_volume(
      17, [&](const Eigen::Vector3d& p) { return (p - center).norm() < 5.0 ? 1.0 : 0.0; });
  const VolumeEdgePotential potential(volume, 1.0, 2.0);
  const double h = 1e-6;
  double worst = 0.0;
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d p(1.3 + 0.137 * k, 1.7 + 0.131 * ((3 * k) % 100),
                            2.1 + 0.119 * ((7 * k) % 100));
    Eigen::Vector3d numeric;
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(axis);
      numeric[axis] = (potential.value(p + step) - potential.value(p - step)) / (2.0 * h);
    }
    worst = std::max(worst, (potential.gradient(p) - numeric).norm());
  }
  // Central differences of a piecewise tricubic: truncation ~1e-13, rounding ~1e-10.
  EXPECT_LT(worst, 1e-8);
}

TEST(VolumeEdgePotential, TricubicInterpolationReproducesQuadratics) {
  const auto q = [](const Eigen::Vector3d& p) {
    return 0.01 * p.x() * p.x() - 0.02 * p.y() * p.z() + 0.03 * p.z() * p.z() + 0.1 * p.x() - 0.2;
  };
  const VolumeEdgePotential potential(sampled_volume(10, q), 0.0, 1.0);
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector3d p(1.0 + 0.17 * k, 1.2 + 0.15 * k, 7.9 - 0.16 * k);
    // Catmull-Rom reproduces degree <= 2 per axis away from the border: rounding only.
    EXPECT_NEAR(potential.smoothed_intensity(p), q(p), 1e-12);
  }
}

TEST(VolumeEdgePotential, GaussianBlobPotentialMatchesTheAnalyticEdgeStrength) {
  // P = -c |grad(G_sigma * V)| of V = exp(-r^2 / 2s^2) is -c (s^2/t^2)^(3/2) r / t^2
  // exp(-r^2 / 2t^2), t^2 = s^2 + sigma^2.
  const double s = 4.0;
  const double sigma = 1.0;
  const double c = 2.0;
  const double t2 = s * s + sigma * sigma;
  const Eigen::Vector3d center(12.2, 11.8, 12.1);
  const VolumeEdgePotential potential(
      sampled_volume(25,
                     [&](const Eigen::Vector3d& p) {
                       return std::exp(-(p - center).squaredNorm() / (2.0 * s * s));
                     }),
      sigma, c);
  const double scale = c * std::pow(s * s / t2, 1.5);
  const double peak = scale / std::sqrt(t2) * std::exp(-0.5);
  double value_error = 0.0;
  double gradient_error = 0.0;
  for (int k = 0; k < 60; ++k) {
    const Eigen::Vector3d direction =
        Eigen::Vector3d(std::cos(0.7 * k), std::sin(0.7 * k), std::cos(1.3 * k)).normalized();
    const double r = 3.0 + 0.1 * k;  // away from the cone of |grad| at the centre
    const Eigen::Vector3d p = center + r * direction;
    const double e = std::exp(-r * r / (2.0 * t2));
    value_error = std::max(value_error, std::abs(potential.value(p) + scale * r / t2 * e) / peak);
    const Eigen::Vector3d exact_gradient = -scale / t2 * (1.0 - r * r / t2) * e * direction;
    gradient_error =
        std::max(gradient_error, (potential.gradient(p) - exact_gradient).norm() / (scale / t2));
  }
  std::printf("3-D blob potential relative errors: P %.2e, grad P %.2e\n", value_error,
              gradient_error);
  // The same tricubic errors as the bicubic 2-D case at one voxel per quarter blob width
  // (test_edge_potential: 1.4e-3 and 1.9e-2 there).
  EXPECT_LT(value_error, 5e-3);
  EXPECT_LT(gradient_error, 5e-2);
}

TEST(VolumeEdgePotential, BadInputIsNamed) {
  EXPECT_NE(
      error_message([] { VolumeEdgePotential(Volume(4, 1, 4), 1.0, 1.0); }).find("4 by 1 by 4"),
      std::string::npos);
  EXPECT_NE(
      error_message([] { VolumeEdgePotential(Volume(4, 4, 4), -0.5, 1.0); }).find("sigma = -0.5"),
      std::string::npos);
  const VolumeEdgePotential potential(Volume(4, 4, 4), 1.0, 1.0);
  EXPECT_NE(error_message([&] {
              potential.gradient(Eigen::Vector3d(0.0, INFINITY, 0.0));
            }).find("not finite"),
            std::string::npos);
}

}  // namespace
}  // namespace dnurbs
