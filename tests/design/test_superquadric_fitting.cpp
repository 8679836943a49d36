#include "dnurbs/design/superquadric_fitting.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/design/point_set.h"
#include "dnurbs/io/mesh_import.h"

namespace dnurbs {
namespace {

using P = SuperquadricShapeParameter;

struct Truth {
  SuperquadricShapeParameters shape;
  Eigen::Vector3d centre;
  Eigen::Matrix3d rotation;
};

Truth random_superquadric(std::mt19937& random, double e1, double e2) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Truth truth;
  truth.shape.setZero();
  truth.shape[P::kScale] = 1.0;
  truth.shape[P::kAspect1] = 0.8 + 0.6 * unit(random);
  truth.shape[P::kAspect2] = 0.5 + 0.4 * unit(random);
  truth.shape[P::kAspect3] = 1.5 + 0.5 * unit(random);
  truth.shape[P::kSquareness1] = e1;
  truth.shape[P::kSquareness2] = e2;
  truth.shape[P::kTaper1] = 0.1 + 0.3 * unit(random);  // canonical: t1 >= 0, b1 >= 0
  truth.shape[P::kTaper2] = -0.3 + 0.6 * unit(random);
  truth.shape[P::kBendAmplitude] = 0.1 + 0.2 * unit(random);
  truth.shape[P::kBendFrequency] = 0.5;
  truth.centre = Eigen::Vector3d(unit(random), unit(random), unit(random)) * 4.0 -
                 Eigen::Vector3d::Constant(2.0);
  truth.rotation = Eigen::Quaterniond(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5,
                                      unit(random) - 0.5)
                       .normalized()
                       .toRotationMatrix();
  return truth;
}

Eigen::MatrixX3d sample(const Truth& truth, int nu, int nv) {
  const DeformableSuperquadricShape shape(truth.shape);
  Eigen::MatrixX3d points(nu * nv, 3);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double u = -std::numbers::pi / 2 + std::numbers::pi * (i + 0.5) / nu;
      const double v = -std::numbers::pi + 2 * std::numbers::pi * (j + 0.3) / nv;
      points.row(i * nv + j) =
          (truth.centre + truth.rotation * shape.evaluate(u, v).point).transpose();
    }
  }
  return points;
}

// Largest relative parameter error over sizes, exponents, taper and bend (relative to
// max(|true|, 0.1) for the deformations, which may be near zero), and centre error.
double parameter_error(const Truth& truth, const SuperquadricFitResult& fit) {
  double error = 0.0;
  for (int i = P::kAspect1; i <= P::kBendAmplitude; ++i) {
    const double reference =
        i >= P::kTaper1 ? std::max(std::abs(truth.shape[i]), 0.1) : std::abs(truth.shape[i]);
    error = std::max(error, std::abs(fit.shape[i] - truth.shape[i]) / reference);
  }
  return error;
}

TEST(SuperquadricFitting, RecoversParametersFromNoiseFreePoints) {
  std::mt19937 random(7);
  const double exponents[][2] = {{0.3, 1.0}, {1.0, 0.3}, {2.0, 0.6}, {0.6, 2.0}, {1.0, 1.0}};
  for (const auto& e : exponents) {
    const Truth truth = random_superquadric(random, e[0], e[1]);
    const Eigen::MatrixX3d points = sample(truth, 12, 18);
    for (const auto algorithm :
         {SuperquadricFitAlgorithm::kLbfgs, SuperquadricFitAlgorithm::kBobyqa}) {
      // The derivative-free fallback needs ~7x the evaluations: checked on the first shape only.
      if (algorithm == SuperquadricFitAlgorithm::kBobyqa && &e != &exponents[0]) {
        continue;
      }
      SuperquadricFitSettings settings;
      settings.algorithm = algorithm;
      const SuperquadricFitResult fit = fit_superquadric(points, settings);
      const double error = parameter_error(truth, fit);
      const double centre_error = (fit.centre - truth.centre).norm();
      const double rotation_error = (fit.rotation - truth.rotation).norm();
      std::cout << (algorithm == SuperquadricFitAlgorithm::kLbfgs ? "LBFGS" : "BOBYQA") << " e = ("
                << e[0] << ", " << e[1] << "): parameter error " << error << ", centre "
                << centre_error << ", rotation " << rotation_error << ", rms " << fit.rms_error
                << ", " << fit.evaluations << " evaluations\n";
      // Noise-free points: the radial distance vanishes at the truth; both algorithms stop at
      // the 1e-12 variable tolerance (or round-off), well inside 1e-3.
      EXPECT_LT(error, 1e-3);
      EXPECT_LT(centre_error, 1e-3);
      EXPECT_LT(rotation_error, 1e-3);
    }
  }
}

// The progress callback sees every evaluation once, in order, with a best rms distance that never
// rises and ends at the result's (a noisy fit, whose minimum is not zero)
TEST(SuperquadricFitting, ReportsEveryEvaluationWithTheBestRmsSoFar) {
  std::mt19937 random(11);
  const Truth truth = random_superquadric(random, 0.8, 1.2);
  Eigen::MatrixX3d points = sample(truth, 10, 14);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (Eigen::Index i = 0; i < points.size(); ++i) {
    points.data()[i] += noise(random);
  }
  SuperquadricFitSettings settings;
  std::vector<std::pair<int, double>> reported;
  settings.on_evaluation = [&reported](int evaluations, double best_rms) {
    reported.emplace_back(evaluations, best_rms);
  };
  const SuperquadricFitResult fit = fit_superquadric(points, settings);
  ASSERT_EQ(reported.size(), static_cast<size_t>(fit.evaluations));
  for (size_t i = 0; i < reported.size(); ++i) {
    ASSERT_EQ(reported[i].first, static_cast<int>(i) + 1);
    if (i > 0) {
      ASSERT_LE(reported[i].second, reported[i - 1].second);
    }
  }
  EXPECT_GT(fit.rms_error, 1e-3);
  // The result's rms is evaluated again at the canonical pose: equal up to round-off
  EXPECT_NEAR(reported.back().second, fit.rms_error, 1e-12 * fit.rms_error + 1e-15);
  EXPECT_GT(reported.front().second, reported.back().second);
}

TEST(SuperquadricFitting, AnalyticGradientMatchesCentralDifferences) {
  std::mt19937 random(19);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const SuperquadricFitSettings settings;
  for (int trial = 0; trial < 5; ++trial) {
    // Points near a random superquadric, variables at another random one: d_k != 0.
    const Truth truth =
        random_superquadric(random, 0.3 + 1.7 * unit(random), 0.3 + 1.7 * unit(random));
    Eigen::MatrixX3d points = sample(truth, 8, 10);
    points +=
        0.05 * Eigen::MatrixX3d::NullaryExpr(points.rows(), 3, [&] { return unit(random) - 0.5; });
    const Truth guess =
        random_superquadric(random, 0.3 + 1.7 * unit(random), 0.3 + 1.7 * unit(random));
    Eigen::VectorXd x(14);
    x.segment<3>(0) =
        truth.centre + 0.2 * Eigen::Vector3d(unit(random), unit(random), unit(random));
    const Eigen::AngleAxisd angle_axis(guess.rotation);
    x.segment<3>(3) = angle_axis.angle() * angle_axis.axis();
    x.segment<3>(6) = guess.shape.segment<3>(P::kAspect1);
    x[9] = guess.shape[P::kSquareness1];
    x[10] = guess.shape[P::kSquareness2];
    x[11] = guess.shape[P::kTaper1];
    x[12] = guess.shape[P::kTaper2];
    x[13] = guess.shape[P::kBendAmplitude];
    Eigen::VectorXd gradient;
    const double value = superquadric_fit_objective(points, settings, x, &gradient);
    EXPECT_DOUBLE_EQ(value, superquadric_fit_objective(points, settings, x, nullptr));
    Eigen::VectorXd difference(14);
    for (int i = 0; i < 14; ++i) {
      // Central difference: O(h^2) truncation (~1e-10) plus O(eps J / h) round-off (~1e-11).
      const double h = 1e-5;
      Eigen::VectorXd plus = x;
      Eigen::VectorXd minus = x;
      plus[i] += h;
      minus[i] -= h;
      difference[i] = (superquadric_fit_objective(points, settings, plus, nullptr) -
                       superquadric_fit_objective(points, settings, minus, nullptr)) /
                      (2.0 * h);
    }
    const double relative = (gradient - difference).norm() / gradient.norm();
    std::cout << "trial " << trial << ": |gradient| " << gradient.norm()
              << ", relative difference to central differences " << relative << "\n";
    EXPECT_LT(relative, 1e-6);
  }
}

TEST(SuperquadricFitting, DegradesGracefullyWithNoise) {
  std::mt19937 random(11);
  const Truth truth = random_superquadric(random, 0.7, 1.3);
  const Eigen::MatrixX3d clean = sample(truth, 12, 18);
  std::normal_distribution<double> gauss(0.0, 1.0);
  double previous = 0.0;
  for (const double sigma : {0.0, 0.003, 0.01, 0.03}) {
    Eigen::MatrixX3d noisy = clean;
    for (Eigen::Index k = 0; k < noisy.rows(); ++k) {
      for (int c = 0; c < 3; ++c) {
        noisy(k, c) += sigma * gauss(random);
      }
    }
    const SuperquadricFitResult fit = fit_superquadric(noisy);
    const double error = parameter_error(truth, fit);
    std::cout << "noise " << sigma << ": parameter error " << error << ", rms " << fit.rms_error
              << ", max " << fit.max_error << "\n";
    // The error grows about linearly with the noise (least squares): a few sigma over the sizes
    // (~1) at most; and the rms distance follows sigma.
    EXPECT_LT(error, 1e-3 + 20.0 * sigma);
    EXPECT_LT(fit.rms_error, 1e-6 + 2.0 * sigma);
    previous = error;
  }
  (void)previous;
}

TEST(SuperquadricFitting, FitsTheVerticesOfAnImportedMesh) {
  std::mt19937 random(3);
  const Truth truth = random_superquadric(random, 0.8, 1.2);
  const int nu = 12;
  const int nv = 18;
  const Eigen::MatrixX3d points = sample(truth, nu, nv);
  // An OBJ of the sampled grid (rows of constant u, closed in v), triangulated.
  const std::filesystem::path directory =
      std::filesystem::path(DNURBS_BINARY_DIR) / "tests" / "design_data";
  std::filesystem::create_directories(directory);
  const auto path = directory / "superquadric.obj";
  {
    std::ofstream file(path);
    file.precision(17);
    for (Eigen::Index k = 0; k < points.rows(); ++k) {
      file << "v " << points(k, 0) << " " << points(k, 1) << " " << points(k, 2) << "\n";
    }
    for (int i = 0; i + 1 < nu; ++i) {
      for (int j = 0; j < nv; ++j) {
        const int a = i * nv + j + 1;
        const int b = i * nv + (j + 1) % nv + 1;
        file << "f " << a << " " << b << " " << b + nv << "\n";
        file << "f " << a << " " << b + nv << " " << a + nv << "\n";
      }
    }
  }
  const Eigen::MatrixX3d vertices = mesh_vertices(import_meshes(path));
  ASSERT_EQ(vertices.rows(), points.rows());
  const SuperquadricFitResult fit = fit_superquadric(vertices);
  // assimp reads the vertices as floats: 1e-7 relative round-off of the data.
  EXPECT_LT(parameter_error(truth, fit), 1e-4);
  EXPECT_LT(fit.rms_error, 1e-5);
}

TEST(SuperquadricFitting, BadPointsAreRejected) {
  EXPECT_THROW(fit_superquadric(Eigen::MatrixX3d(0, 3)), Error);
  EXPECT_THROW(fit_superquadric(Eigen::MatrixX3d::Random(5, 3)), Error);
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Random(100, 3);
  points(3, 2) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(fit_superquadric(points), Error);
  Eigen::MatrixX3d planar = Eigen::MatrixX3d::Random(100, 3);
  planar.col(2).setZero();
  EXPECT_THROW(fit_superquadric(planar), Error);
}

}  // namespace
}  // namespace dnurbs
