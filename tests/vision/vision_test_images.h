#pragma once
// Analytic test images and volumes for the vision tests: shapes rendered by pixel (voxel)
// coverage, so the intensity sum is the shape's area (volume) up to the coverage sampling.

#include <functional>

#include <Eigen/Core>

#include "dnurbs/vision/image.h"
#include "dnurbs/vision/volume.h"

namespace dnurbs::testing {

/// An image whose pixel (x, y) holds the fraction of the unit square about (x, y) inside
/// `shape`, estimated on a samples by samples sub-grid (error <= perimeter / samples^2 per pixel
/// on the boundary, in area).
inline Image coverage_image(int width, int height,
                            const std::function<bool(const Eigen::Vector2d&)>& shape,
                            int samples = 8) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      int count = 0;
      for (int b = 0; b < samples; ++b) {
        for (int a = 0; a < samples; ++a) {
          const Eigen::Vector2d p(x - 0.5 + (a + 0.5) / samples, y - 0.5 + (b + 0.5) / samples);
          count += shape(p) ? 1 : 0;
        }
      }
      image(x, y) = static_cast<double>(count) / (samples * samples);
    }
  }
  return image;
}

/// A volume whose voxel holds the fraction of its unit cube inside `shape` (samples^3 points).
inline Volume coverage_volume(int nx, int ny, int nz,
                              const std::function<bool(const Eigen::Vector3d&)>& shape,
                              int samples = 4) {
  Volume volume(nx, ny, nz);
  for (int z = 0; z < nz; ++z) {
    for (int y = 0; y < ny; ++y) {
      for (int x = 0; x < nx; ++x) {
        int count = 0;
        for (int c = 0; c < samples; ++c) {
          for (int b = 0; b < samples; ++b) {
            for (int a = 0; a < samples; ++a) {
              const Eigen::Vector3d p(x - 0.5 + (a + 0.5) / samples, y - 0.5 + (b + 0.5) / samples,
                                      z - 0.5 + (c + 0.5) / samples);
              count += shape(p) ? 1 : 0;
            }
          }
        }
        volume(x, y, z) = static_cast<double>(count) / (samples * samples * samples);
      }
    }
  }
  return volume;
}

/// A disc of `radius` about `center` as an inside predicate.
inline std::function<bool(const Eigen::Vector2d&)> disc(const Eigen::Vector2d& center,
                                                        double radius) {
  return [=](const Eigen::Vector2d& p) { return (p - center).squaredNorm() <= radius * radius; };
}

}  // namespace dnurbs::testing

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace dnurbs::testing {

/// A fresh file path in the temporary directory, named after the running test.
inline std::string scratch_file(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto folder = std::filesystem::temp_directory_path() / "dnurbs_vision_tests";
  std::filesystem::create_directories(folder);
  return (folder / (std::string(info->test_suite_name()) + "_" + info->name() + "_" + name))
      .string();
}

}  // namespace dnurbs::testing
