#include "dnurbs/design/dnurbs_fitting.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/design/point_set.h"
#include "dnurbs/io/mesh_import.h"
#include "tests/design/design_test_helpers.h"

namespace dnurbs {
namespace {

using test::graph_patch;

// Samples of `surface` on an n by n grid of parameters inside the domain.
Eigen::MatrixX3d surface_samples(const NurbsSurface& surface, int n) {
  Eigen::MatrixX3d points(n * n, 3);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u = (i + 0.5) / n;
      const double v = (j + 0.5) / n;
      points.row(i * n + j) = surface.point(u, v).transpose();
    }
  }
  return points;
}

TEST(DNurbsSurfaceFitting, ReproducesAKnownSurfaceOfTheSameDegreeAndKnots) {
  const KnotVector knots_u = KnotVector::clamped_uniform(3, 7);
  const KnotVector knots_v = KnotVector::clamped_uniform(3, 6);
  const NurbsSurface target = graph_patch(knots_u, knots_v, [](double u, double v) {
    return 0.3 * std::sin(3.0 * u) * std::cos(2.0 * v) + 0.2 * u * v;
  });
  const DNurbsSurface model(graph_patch(knots_u, knots_v, [](double, double) { return 0.0; }));
  const Eigen::MatrixX3d points = surface_samples(target, 12);

  const DNurbsFitResult result = fit_dnurbs_surface(model, points);
  const Eigen::MatrixX3d fitted = model.control_points(result.coordinates);
  const double error = (fitted - target.control_points()).lpNorm<Eigen::Infinity>();
  std::cout << "surface fit: " << result.iterations << " iterations, rms " << result.rms_error
            << ", max " << result.max_error << ", control point error " << error << "\n";
  // The points lie on a surface of the fitted space: least squares reproduces it up to the
  // round-off of the normal equations (condition ~1e3) and of the closest-point projections.
  EXPECT_LT(error, 1e-8);
  EXPECT_LT(result.max_error, 1e-8);
}

TEST(DNurbsSurfaceFitting, ParameterCorrectionRecoversACurvedParameterization) {
  // The target's (x, y) are not linear in (u, v): the first projection onto the plane gives
  // wrong parameters, which the re-projections correct.
  const KnotVector knots = KnotVector::clamped_uniform(3, 6);
  NurbsSurface target =
      graph_patch(knots, knots, [](double u, double v) { return 0.25 * std::sin(2.0 * u + v); });
  Eigen::MatrixX3d control = target.control_points();
  for (Eigen::Index i = 0; i < control.rows(); ++i) {
    control(i, 0) += 0.04 * std::sin(3.0 * control(i, 1));
  }
  target.set_control_points(control);
  const DNurbsSurface model(graph_patch(knots, knots, [](double, double) { return 0.0; }));
  DNurbsFitSettings settings;
  settings.max_iterations = 40;
  std::vector<std::pair<int, double>> reported;  // the progress callback's (iteration, rms)
  settings.on_iteration = [&reported](int iteration, double rms) {
    reported.emplace_back(iteration, rms);
  };
  const DNurbsFitResult result = fit_dnurbs_surface(model, surface_samples(target, 10), settings);
  std::cout << "curved parameterization: " << result.iterations << " iterations, rms "
            << result.rms_error << ", max " << result.max_error << "\n";
  // Parameter correction converges linearly; measured 1e-4 after 40 iterations.
  EXPECT_LT(result.max_error, 3e-4);
  // Every iteration is reported once, in order, the last with the result's rms distance
  ASSERT_EQ(reported.size(), static_cast<size_t>(result.iterations));
  for (size_t i = 0; i < reported.size(); ++i) {
    EXPECT_EQ(reported[i].first, static_cast<int>(i) + 1);
  }
  EXPECT_EQ(reported.back().second, result.rms_error);
  // and the re-projections lowered it (measured: 4.8e-6 after the first, 4.3e-6 after the 40th)
  EXPECT_LT(result.rms_error, 0.95 * reported.front().second);
}

TEST(DNurbsCurveFitting, ReproducesAKnownCurve) {
  const KnotVector knots = KnotVector::clamped_uniform(3, 8);
  const Eigen::VectorXd x = test::greville_abscissae(knots);
  Eigen::MatrixX3d flat = Eigen::MatrixX3d::Zero(x.size(), 3);
  flat.col(0) = x;
  Eigen::MatrixX3d control = flat;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    control(i, 1) = std::sin(4.0 * x[i]);
    control(i, 2) = 0.5 * x[i] * x[i];
  }
  const NurbsCurve target(knots, control);
  Eigen::MatrixX3d points(40, 3);
  for (int k = 0; k < 40; ++k) {
    points.row(k) = target.point((k + 0.5) / 40.0).transpose();
  }
  const DNurbsCurve model(NurbsCurve(knots, flat));
  const DNurbsFitResult result = fit_dnurbs_curve(model, points);
  const double error =
      (model.control_points(result.coordinates) - control).lpNorm<Eigen::Infinity>();
  std::cout << "curve fit: " << result.iterations << " iterations, control point error " << error
            << "\n";
  // As for the surface: round-off of the normal equations and projections.
  EXPECT_LT(error, 1e-8);
}

TEST(DNurbsCurveFitting, FreeWeightsFitACircularArcThatFixedWeightsCannot) {
  // A quarter circle is a rational quadratic: only free weights can represent it.
  const KnotVector knots = KnotVector::clamped_uniform(2, 3);
  Eigen::MatrixX3d start(3, 3);
  start << 1.0, 0.0, 0.0, 0.7, 0.7, 0.0, 0.0, 1.0, 0.0;
  Eigen::MatrixX3d points(30, 3);
  for (int k = 0; k < 30; ++k) {
    const double angle = 0.5 * std::numbers::pi * (k + 0.5) / 30.0;
    points.row(k) << std::cos(angle), std::sin(angle), 0.0;
  }
  DNurbsSettings free;
  free.weight_mode = WeightMode::kFree;
  free.minimum_weight = 0.1;
  DNurbsCurve rational(NurbsCurve(knots, start), {}, free);
  // Weights (1, c w, c^2) give the same arc with another parameterization: with weight 0 fixed
  // (the gauge) fixing weight 2 too leaves one exact answer, w = (1, sqrt(2)/2, 1).
  rational.fix_weight(2);
  const DNurbsCurve polynomial(NurbsCurve(knots, start));
  DNurbsFitSettings settings;
  settings.max_iterations = 100;
  const DNurbsFitResult fit = fit_dnurbs_curve(rational, points, settings);
  const DNurbsFitResult fixed = fit_dnurbs_curve(polynomial, points, settings);
  std::cout << "circular arc: free weights max error " << fit.max_error << " after "
            << fit.iterations << " iterations (weights "
            << rational.weights(fit.coordinates).transpose() << "), fixed weights "
            << fixed.max_error << "\n";
  EXPECT_GE(rational.weights(fit.coordinates).minCoeff(), free.minimum_weight);
  // A polynomial quadratic misses the circle by 7e-3. The rational fit is limited by parameter
  // correction, which converges linearly here: measured max error 3.5e-3, 1.8e-3 and 9e-5
  // after 1, 20 and 100 iterations (each an LBFGS solve at fixed parameters).
  EXPECT_GT(fixed.max_error, 5e-3);
  EXPECT_LT(fit.max_error, 2e-4);
}

TEST(DNurbsSurfaceFitting, SmoothnessPullsTowardsTheFlatShape) {
  const KnotVector knots = KnotVector::clamped_uniform(3, 6);
  const NurbsSurface target =
      graph_patch(knots, knots, [](double u, double v) { return std::sin(6.0 * u * v); });
  DNurbsSurfaceMaterial material = test::plate_material();
  const DNurbsSurface model(graph_patch(knots, knots, [](double, double) { return 0.0; }),
                            material);
  const Eigen::MatrixX3d points = surface_samples(target, 10);
  DNurbsFitSettings smooth;
  smooth.smoothness = 1.0;
  const DNurbsFitResult plain = fit_dnurbs_surface(model, points);
  const DNurbsFitResult smoothed = fit_dnurbs_surface(model, points, smooth);
  EXPECT_GT(smoothed.rms_error, plain.rms_error);
  EXPECT_LT(model.potential_energy(smoothed.coordinates),
            model.potential_energy(plain.coordinates));
}

TEST(FittingBadData, EmptyAndNonFinitePointsAreRejected) {
  const KnotVector knots = KnotVector::clamped_uniform(2, 4);
  const DNurbsSurface model(graph_patch(knots, knots, [](double, double) { return 0.0; }));
  EXPECT_THROW(fit_dnurbs_surface(model, Eigen::MatrixX3d(0, 3)), Error);
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Random(50, 3);
  points(7, 1) = std::nan("");
  try {
    fit_dnurbs_surface(model, points);
    FAIL() << "NaN accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("point 7"), std::string::npos) << error.what();
  }
  // Too few points for 16 control points and no smoothness: a singular normal matrix.
  EXPECT_THROW(fit_dnurbs_surface(model, Eigen::MatrixX3d::Random(3, 3)), Error);
}

TEST(FittingBadData, MissingOrUnreadableFilesGiveClearErrors) {
  const std::filesystem::path missing = "/nonexistent/dnurbs/points.obj";
  EXPECT_THROW(load_points(missing), Error);
  EXPECT_THROW(mesh_vertices(import_meshes(missing)), Error);
  const std::filesystem::path directory =
      std::filesystem::path(DNURBS_BINARY_DIR) / "tests" / "design_data";
  std::filesystem::create_directories(directory);
  const auto garbage = directory / "garbage.obj";
  std::ofstream(garbage) << "this is not a mesh\x01\x02\n";
  EXPECT_THROW(mesh_vertices(import_meshes(garbage)), Error);
  const auto bad_points = directory / "bad_points.xyz";
  std::ofstream(bad_points) << "# x y z\n0 0 0\n1 nan 2\n";
  try {
    load_points(bad_points);
    FAIL() << "NaN accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("line 3"), std::string::npos) << error.what();
  }
  const auto short_line = directory / "short_line.xyz";
  std::ofstream(short_line) << "0, 0, 0\n1, 2\n";
  EXPECT_THROW(load_points(short_line), Error);
  const auto good = directory / "good.xyz";
  std::ofstream(good) << "# points\n0, 0, 0\n\n1 2 3\n";
  EXPECT_EQ(load_points(good).rows(), 2);
  EXPECT_THROW(mesh_vertices({}), Error);
}

}  // namespace
}  // namespace dnurbs
