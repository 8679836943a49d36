#include "dnurbs/vision/gaussian_filter.h"

#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "../common/error_message.h"

namespace dnurbs {
namespace {

using testing::error_message;

/// exp(-r^2 / (2 s^2)) about `center`: a blob whose Gaussian smoothing is known in closed form.
double blob(const Eigen::Vector3d& p, const Eigen::Vector3d& center, double s) {
  return std::exp(-(p - center).squaredNorm() / (2.0 * s * s));
}

TEST(GaussianKernel, SumsToOneAndTheDerivativeHasUnitMoment) {
  for (const double sigma : {0.0, 0.5, 1.0, 2.5}) {
    const Eigen::VectorXd g = gaussian_kernel(sigma);
    const Eigen::VectorXd d = gaussian_derivative_kernel(sigma);
    ASSERT_EQ(g.size() % 2, 1);
    const int r = static_cast<int>(d.size() / 2);
    double moment = 0.0;
    for (int k = 0; k < d.size(); ++k) {
      moment -= (k - r) * d(k);
    }
    EXPECT_NEAR(g.sum(), 1.0, 1e-15);  // normalized: rounding only
    EXPECT_NEAR(d.sum(), 0.0, 1e-15);  // odd kernel
    EXPECT_NEAR(moment, 1.0, 1e-15);
    EXPECT_EQ(g.size(), sigma == 0.0 ? 1 : 2 * static_cast<int>(std::ceil(5.0 * sigma)) + 1);
  }
}

TEST(GaussianKernel, BadSigmaIsNamed) {
  EXPECT_NE(error_message([] { gaussian_kernel(-1.0); }).find("sigma = -1"), std::string::npos);
  EXPECT_NE(error_message([] { gaussian_kernel(std::nan("")); }).find("sigma = nan"),
            std::string::npos);
  EXPECT_NE(error_message([] { gaussian_derivative_kernel(1000.5); }).find("sigma = 1000.5"),
            std::string::npos);
}

TEST(GaussianSmoothing, LinearRampIsUnchangedAndItsGradientExact) {
  Image ramp(40, 30);
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      ramp(x, y) = 0.3 * x - 0.2 * y + 1.0;
    }
  }
  const double sigma = 1.5;  // kernel radius 8: pixels 8 or more from the border see no border
  const Image smooth = gaussian_smooth(ramp, sigma);
  const std::array<Image, 2> gradient = smoothed_gradient(ramp, sigma);
  for (int y = 8; y < 22; ++y) {
    for (int x = 8; x < 32; ++x) {
      // Symmetric kernels of sum 1 and derivative moment 1 are exact on linear data (rounding).
      EXPECT_NEAR(smooth(x, y), ramp(x, y), 1e-13);
      EXPECT_NEAR(gradient[0](x, y), 0.3, 1e-13);
      EXPECT_NEAR(gradient[1](x, y), -0.2, 1e-13);
    }
  }
}

TEST(GaussianSmoothing, GaussianBlobMatchesTheClosedFormConvolution) {
  // G_sigma * exp(-r^2 / 2s^2) = (s^2 / t^2)^(d/2) exp(-r^2 / 2t^2) with t^2 = s^2 + sigma^2 in d
  // dimensions, and its gradient -(p - c) / t^2 times that.
  const double s = 3.0;
  const double sigma = 1.5;
  const double t2 = s * s + sigma * sigma;
  const Eigen::Vector3d center(20.3, 19.6, 0.0);
  Image image(41, 41);
  for (int y = 0; y < 41; ++y) {
    for (int x = 0; x < 41; ++x) {
      image(x, y) = blob(Eigen::Vector3d(x, y, 0.0), center, s);
    }
  }
  const Image smooth = gaussian_smooth(image, sigma);
  const std::array<Image, 2> gradient = smoothed_gradient(image, sigma);
  double value_error = 0.0;
  double gradient_error = 0.0;
  for (int y = 5; y < 36; ++y) {
    for (int x = 5; x < 36; ++x) {
      const Eigen::Vector3d p(x, y, 0.0);
      const double exact = s * s / t2 * std::exp(-(p - center).squaredNorm() / (2.0 * t2));
      value_error = std::max(value_error, std::abs(smooth(x, y) - exact));
      const Eigen::Vector2d exact_gradient = -(p - center).head<2>() / t2 * exact;
      gradient_error =
          std::max(gradient_error,
                   (Eigen::Vector2d(gradient[0](x, y), gradient[1](x, y)) - exact_gradient).norm());
    }
  }
  // Sampling both Gaussians at unit spacing errs by ~exp(-2 pi^2 sigma^2) (Poisson summation,
  // 1e-19 here) and cutting the kernel at 5 sigma drops a tail mass of 6e-7 and ~1.5e-5 of the
  // derivative kernel's second moment, which the unit-moment scaling absorbs for this smooth
  // data: measured 1.3e-8 and 4.3e-8 of a peak of 0.8.
  EXPECT_LT(value_error, 1e-6);
  EXPECT_LT(gradient_error, 1e-6);
  std::printf("2-D blob smoothing errors: %.1e (values), %.1e (gradient)\n", value_error,
              gradient_error);
}

TEST(GaussianSmoothing, VolumeBlobMatchesTheClosedFormConvolution) {
  const double s = 2.5;
  const double sigma = 1.0;
  const double t2 = s * s + sigma * sigma;
  const Eigen::Vector3d center(10.2, 9.7, 10.4);
  Volume volume(21, 21, 21);
  for (int z = 0; z < 21; ++z) {
    for (int y = 0; y < 21; ++y) {
      for (int x = 0; x < 21; ++x) {
        volume(x, y, z) = blob(Eigen::Vector3d(x, y, z), center, s);
      }
    }
  }
  const Volume smooth = gaussian_smooth(volume, sigma);
  const std::array<Volume, 3> gradient = smoothed_gradient(volume, sigma);
  double value_error = 0.0;
  double gradient_error = 0.0;
  for (int z = 4; z < 17; ++z) {
    for (int y = 4; y < 17; ++y) {
      for (int x = 4; x < 17; ++x) {
        const Eigen::Vector3d p(x, y, z);
        const double exact =
            std::pow(s * s / t2, 1.5) * std::exp(-(p - center).squaredNorm() / (2.0 * t2));
        value_error = std::max(value_error, std::abs(smooth(x, y, z) - exact));
        const Eigen::Vector3d numeric(gradient[0](x, y, z), gradient[1](x, y, z),
                                      gradient[2](x, y, z));
        gradient_error = std::max(gradient_error, (numeric + (p - center) / t2 * exact).norm());
      }
    }
  }
  // As in 2-D: kernel sampling and the 5-sigma cut.
  EXPECT_LT(value_error, 1e-6);
  EXPECT_LT(gradient_error, 1e-6);
}

}  // namespace
}  // namespace dnurbs
