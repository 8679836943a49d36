#include "dnurbs/design/superquadric_fitting.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/common/error_message.h"

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
  truth.shape[P::kTwist] = 0.2 + 0.4 * unit(random);
  truth.shape[P::kShearX] = -0.2 + 0.4 * unit(random);
  truth.shape[P::kShearY] = -0.2 + 0.4 * unit(random);
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

// Largest relative parameter error over sizes, exponents and the deformations (relative to
// max(|true|, 0.1) for the deformations, which may be near zero); b2 and b3 only if
// `bend_shape`.
double parameter_error(const Truth& truth, const SuperquadricFitResult& fit,
                       bool bend_shape = false) {
  double error = 0.0;
  for (int i = P::kAspect1; i <= P::kShearY; ++i) {
    if (!bend_shape && (i == P::kBendOffset || i == P::kBendFrequency)) {
      continue;
    }
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
      // Noise-free points: the radial distance vanishes at the truth. LBFGS ends with
      // Levenberg-Marquardt steps, which converge quadratically to the zero residual: what is
      // left is round-off of d_k (~1e-16) times the conditioning of the fit (measured <= 1e-14).
      // BOBYQA stops at its 1e-12 relative variable tolerance (measured 5e-13).
      EXPECT_LT(error, 1e-10);
      EXPECT_LT(centre_error, 1e-10);
      EXPECT_LT(rotation_error, 1e-10);
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
    Eigen::VectorXd x(kSuperquadricFitVariableCount);
    x.segment<3>(0) =
        truth.centre + 0.2 * Eigen::Vector3d(unit(random), unit(random), unit(random));
    const Eigen::AngleAxisd angle_axis(guess.rotation);
    x.segment<3>(3) = angle_axis.angle() * angle_axis.axis();
    x.segment<3>(6) = guess.shape.segment<3>(P::kAspect1);
    x[9] = guess.shape[P::kSquareness1];
    x[10] = guess.shape[P::kSquareness2];
    // The deformations (t1, t2, b1, b2, b3, tau, sx, sy), with b2 and b3 moved off their
    // defaults so that every partial derivative is exercised.
    x.tail<kGlobalDeformationParameterCount>() =
        guess.shape.tail<kGlobalDeformationParameterCount>();
    x[14] = 0.3 * unit(random);
    x[15] = 0.3 + 0.5 * unit(random);
    Eigen::VectorXd gradient;
    const double value = superquadric_fit_objective(points, settings, x, &gradient);
    EXPECT_DOUBLE_EQ(value, superquadric_fit_objective(points, settings, x, nullptr));
    Eigen::VectorXd difference(kSuperquadricFitVariableCount);
    for (int i = 0; i < kSuperquadricFitVariableCount; ++i) {
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
  }
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

// From a start near the truth only the polishing run is made: every global parameter comes back,
// the bend's offset b2 and frequency b3 too when they are fitted.
TEST(SuperquadricFitting, RecoversEveryGlobalParameterFromAPerturbedStart) {
  std::mt19937 random(23);
  Truth truth = random_superquadric(random, 0.7, 1.4);
  truth.shape[P::kBendOffset] = 0.3;
  truth.shape[P::kBendFrequency] = 0.7;
  const Eigen::MatrixX3d points = sample(truth, 16, 24);
  SuperquadricFitStart start;
  start.shape = truth.shape;
  start.shape.segment<3>(P::kAspect1) *= 1.05;
  start.shape[P::kSquareness1] += 0.05;
  start.shape[P::kSquareness2] -= 0.05;
  start.shape.tail<kGlobalDeformationParameterCount>().array() += 0.05;
  start.centre = truth.centre + Eigen::Vector3d(0.05, -0.03, 0.04);
  start.rotation =
      truth.rotation * Eigen::AngleAxisd(0.05, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  SuperquadricFitSettings settings;
  settings.fit_bend_shape = true;
  settings.start = start;
  const SuperquadricFitResult fit = fit_superquadric(points, settings);
  const double error = parameter_error(truth, fit, true);
  const double centre_error = (fit.centre - truth.centre).norm();
  const double rotation_error = (fit.rotation - truth.rotation).norm();
  std::cout << "tau " << truth.shape[P::kTwist] << ", sx " << truth.shape[P::kShearX] << ", sy "
            << truth.shape[P::kShearY] << ", b2 0.3, b3 0.7: parameter error " << error
            << ", centre " << centre_error << ", rotation " << rotation_error << ", rms "
            << fit.rms_error << ", " << fit.evaluations << " evaluations\n";
  // Noise-free points: the residual is zero at the truth with a regular Jacobian (the points
  // determine every parameter, b2 and b3 too since b1 != 0), and the Levenberg-Marquardt polish
  // converges quadratically to it: round-off of d_k (~1e-16) times the conditioning is left
  // (measured 4e-15). 1e-10 is far below the 1e-6 a fit tolerance would need.
  EXPECT_LT(error, 1e-10);
  EXPECT_LT(centre_error, 1e-10);
  EXPECT_LT(rotation_error, 1e-10);
  EXPECT_LT(fit.rms_error, 1e-13);
}

// Least squares: to first order the parameter error is linear in the noise, e(sigma n) =
// sigma A n. With the same normal draws n scaled by sigma and 4 sigma the errors differ by 4.
TEST(SuperquadricFitting, ParameterErrorIsLinearInTheNoise) {
  std::mt19937 random(29);
  const Truth truth = random_superquadric(random, 0.8, 1.2);
  const Eigen::MatrixX3d clean = sample(truth, 16, 24);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Eigen::MatrixX3d draws =
      Eigen::MatrixX3d::NullaryExpr(clean.rows(), 3, [&] { return gauss(random); });
  SuperquadricFitSettings settings;
  settings.start = SuperquadricFitStart{truth.shape, truth.centre, truth.rotation};
  Eigen::VectorXd errors[2];
  const double sigmas[2] = {1e-3, 4e-3};
  for (int level = 0; level < 2; ++level) {
    const SuperquadricFitResult fit = fit_superquadric(clean + sigmas[level] * draws, settings);
    Eigen::VectorXd error(3 + kSuperquadricShapeParameterCount);
    error << fit.centre - truth.centre, fit.shape - truth.shape;
    errors[level] = error;
    std::cout << "sigma " << sigmas[level] << ": |parameter error| " << error.norm() << ", rms "
              << fit.rms_error << "\n";
  }
  const double ratio = errors[1].norm() / errors[0].norm();
  const double nonlinearity = (errors[1] - 4.0 * errors[0]).norm() / errors[1].norm();
  std::cout << "ratio " << ratio << ", |e(4 sigma) - 4 e(sigma)| / |e(4 sigma)| " << nonlinearity
            << "\n";
  // e = sigma A n + sigma^2 B(n, n) + ...: e(4 sigma) - 4 e(sigma) = 12 sigma^2 B(n, n), relative
  // to e(4 sigma) 3 sigma |B| / |A|, with |B| / |A| of the order of the inverse of the shape's
  // smallest length (measured: 0.011, |B| / |A| ~ 4 per unit length for sizes 0.5 to 2). 0.05
  // allows |B| / |A| up to 17; the ratio of the norms then lies within 4 (1 +- 0.05).
  EXPECT_LT(nonlinearity, 0.05);
  EXPECT_NEAR(ratio, 4.0, 0.2);
  // The noise-free fit is exact (RecoversEveryGlobalParameterFromAPerturbedStart), so the
  // errors are the noise's: not zero.
  EXPECT_GT(errors[0].norm(), 1e-4);
}

TEST(SuperquadricFitting, BadInputThrowsNamingTheValue) {
  using testing::error_message;
  EXPECT_THAT(error_message([] { fit_superquadric(Eigen::MatrixX3d(0, 3)); }),
              ::testing::HasSubstr("empty"));
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Random(100, 3);
  points(3, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(error_message([&] { fit_superquadric(points); }), ::testing::HasSubstr("nan"));
  // 17 fitted parameters by default (b2, b3 held); 16 points are too few.
  EXPECT_THAT(error_message([] { fit_superquadric(Eigen::MatrixX3d::Random(16, 3)); }),
              ::testing::HasSubstr("17 parameters needs at least as many points (got 16)"));
  SuperquadricFitSettings settings;
  settings.fit_twist = false;
  settings.fit_shear = false;
  EXPECT_THAT(error_message([&] { fit_superquadric(Eigen::MatrixX3d::Random(13, 3), settings); }),
              ::testing::HasSubstr("14 parameters"));
  settings = {};
  settings.local = SuperquadricLocalFitSettings{};
  settings.local->smoothness = -0.5;
  EXPECT_THAT(error_message([&] { fit_superquadric(Eigen::MatrixX3d::Random(100, 3), settings); }),
              ::testing::HasSubstr("smoothness is -0.5"));
  settings = {};
  settings.maximum_shear = -1.0;
  EXPECT_THAT(error_message([&] { fit_superquadric(Eigen::MatrixX3d::Random(100, 3), settings); }),
              ::testing::HasSubstr("maximum_shear -1"));
  settings = {};
  settings.start = SuperquadricFitStart{DeformableSuperquadricShape().parameters(),
                                        Eigen::Vector3d::Zero(), 2.0 * Eigen::Matrix3d::Identity()};
  EXPECT_THAT(error_message([&] { fit_superquadric(Eigen::MatrixX3d::Random(100, 3), settings); }),
              ::testing::HasSubstr("det 8"));
  Eigen::MatrixX3d planar = Eigen::MatrixX3d::Random(100, 3);
  planar.col(2).setZero();
  EXPECT_THAT(error_message([&] { fit_superquadric(planar); }), ::testing::HasSubstr("plane"));
}

}  // namespace
}  // namespace dnurbs
