#include "dnurbs/design/superquadric_local_fitting.h"

#include <cmath>
#include <iostream>
#include <numbers>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/common/error_message.h"

#include "dnurbs/core/error.h"
#include "dnurbs/design/superquadric_fitting.h"

namespace dnurbs {
namespace {

constexpr double kPi = std::numbers::pi;

// A Gaussian bump of height H and angular width w on the unit sphere, centred on the x axis
// (u = 0, v = 0), sampled on a regular (u, v) grid of nu by nv cell centres: the points
// (1 + H exp(-angle^2 / 2 w^2)) n(u, v), angle = the great-circle angle from the x axis.
struct BumpedSphere {
  double height = 0.1;
  double width = 0.25;
  int nu = 96;
  int nv = 192;

  Eigen::MatrixX3d points() const {
    Eigen::MatrixX3d result(nu * nv, 3);
    for (int i = 0; i < nu; ++i) {
      for (int j = 0; j < nv; ++j) {
        const double u = -kPi / 2 + kPi * (i + 0.5) / nu;
        const double v = -kPi + 2.0 * kPi * (j + 0.5) / nv;
        const Eigen::Vector3d n(std::cos(u) * std::cos(v), std::cos(u) * std::sin(v), std::sin(u));
        const double angle = std::acos(std::clamp(n.x(), -1.0, 1.0));
        result.row(i * nv + j) =
            ((1.0 + height * std::exp(-angle * angle / (2.0 * width * width))) * n).transpose();
      }
    }
    return result;
  }
};

SuperquadricShapeParameters unit_sphere() {
  return DeformableSuperquadricShape().parameters();
}

// A mesh of cells_u by 2 cells_u cells: nodes on u = 0 and v = 0, one at the bump's centre.
SuperquadricLocalFitSettings bump_settings(int cells_u, double smoothness) {
  SuperquadricLocalFitSettings settings;
  settings.mesh_cells_u = cells_u;
  settings.mesh_cells_v = 2 * cells_u;
  settings.smoothness = smoothness;
  return settings;
}

// The fitted displacement at the node of the bump's centre (u = v = 0).
Eigen::Vector3d displacement_at_bump_centre(const BumpedSphere& bump,
                                            const SuperquadricLocalFitSettings& settings) {
  const SuperquadricLocalFitResult fit = fit_superquadric_local_displacements(
      bump.points(), unit_sphere(), Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), settings);
  const ParametricFeMesh mesh(settings.mesh_cells_u, settings.mesh_cells_v);
  const int centre = mesh.node_index(settings.mesh_cells_u / 2, settings.mesh_cells_v / 2);
  EXPECT_TRUE(mesh.node_parameter(centre).isZero(1e-15));
  return fit.displacements.segment<3>(3 * centre);
}

// On the true sphere the fitted displacement at the bump's centre is the bump's height H plus two
// biases, both to first order in the curvature b_uu = b_vv = -H / w^2 of the bump at its peak
// (u and v are arc lengths on the equator):
//  - regularization (header): (N lambda / rho)(b_uu + b_vv), rho = N / (2 pi^2) points per unit
//    (u, v) area: -4 pi^2 lambda H / w^2;
//  - bilinear cells of side h fitted by least squares to points at their quarter points (2 by 2
//    per cell): in 1-D, for b = x^2 / 2 the nodal values solve (h/32)(6 c_{i-1} + 20 c_i + 6
//    c_{i+1}) = h x_i^2 / 2 + 3 h^3 / 32, so c_i = b(x_i) - (3/32) h^2 b'': +2 (3/32) h^2 H / w^2
//    over u and v.
// The next order of each is smaller by (h / w)^2 (the fourth derivative of the Gaussian against
// the second).
TEST(SuperquadricLocalFitting, FitsAGaussianBumpOnTheTrueSphereUpToItsBiases) {
  const BumpedSphere bump;  // 96 x 192 points
  const SuperquadricLocalFitSettings settings = bump_settings(48, 1e-5);
  const Eigen::Vector3d peak = displacement_at_bump_centre(bump, settings);
  const double h = kPi / settings.mesh_cells_u;
  const double w2 = bump.width * bump.width;
  const double regularization_bias = -4.0 * kPi * kPi * settings.smoothness * bump.height / w2;
  const double cell_bias = 2.0 * (3.0 / 32.0) * h * h * bump.height / w2;
  const double predicted = bump.height + regularization_bias + cell_bias;
  const double next_order = h * h / w2 * (std::abs(regularization_bias) + std::abs(cell_bias));
  std::cout << "displacement at the bump's centre " << peak.transpose() << ": height "
            << bump.height << ", regularization bias " << regularization_bias << ", cell bias "
            << cell_bias << ", predicted " << predicted << " (next order " << next_order << ")\n";
  EXPECT_NEAR(peak.x(), predicted, next_order);
  // By symmetry about the x axis (the grid is symmetric in u and v about the bump) the
  // displacement there is radial: y and z vanish up to the solver's round-off.
  EXPECT_LT(peak.tail<2>().norm(), 1e-12);
}

// The regularization bias alone: tripling lambda lowers the peak by 2 (4 pi^2 lambda H / w^2).
TEST(SuperquadricLocalFitting, RegularizationBiasIsLinearInTheSmoothness) {
  const BumpedSphere bump;
  const double lambda = 1e-5;
  const double drop = displacement_at_bump_centre(bump, bump_settings(48, lambda)).x() -
                      displacement_at_bump_centre(bump, bump_settings(48, 3.0 * lambda)).x();
  const double w2 = bump.width * bump.width;
  const double predicted = 2.0 * 4.0 * kPi * kPi * lambda * bump.height / w2;
  std::cout << "peak drop from lambda to 3 lambda " << drop << ", predicted " << predicted << "\n";
  // Next order, relative: (h/w)^2 = 0.07 from the cells, and the second-order smoothing term
  // (c Laplacian)^2 b against c Laplacian b, c = 2 pi^2 (3 lambda), |Laplacian^2 b / Laplacian b|
  // = 8 / w^2 at the peak: 0.076.
  EXPECT_NEAR(drop, predicted, 0.15 * predicted);
}

// The full fit (global, then local) of the sphere with the bump: the displacements capture what
// the 17 global parameters cannot.
TEST(SuperquadricLocalFitting, ReducesTheResidualOfTheGlobalFit) {
  BumpedSphere bump;
  bump.nu = 48;
  bump.nv = 96;
  SuperquadricFitSettings settings;
  settings.local = bump_settings(24, 1e-5);
  const SuperquadricFitResult fit = fit_superquadric(bump.points(), settings);
  ASSERT_TRUE(fit.local.has_value());
  const SuperquadricLocalFitResult& local = *fit.local;
  std::cout << "global rms " << local.global_rms_error << " (radial " << fit.rms_error << "), max "
            << local.global_max_error << "; with local displacements rms " << local.rms_error
            << ", max " << local.max_error << "\n";
  // The global shape cannot follow the bump (max residual ~0.4 H); what the displacements leave
  // is the cell and smoothing bias (~5e-3 = 0.05 H at the peak with h = pi/24, test above) on
  // the ~5 % of the points the bump covers: at least a factor 10 in rms and 5 in max.
  EXPECT_LT(local.rms_error, local.global_rms_error / 10.0);
  EXPECT_LT(local.max_error, local.global_max_error / 5.0);
}

// Points exactly on a deformed superquadric leave nothing to the local stage.
TEST(SuperquadricLocalFitting, LeavesAnExactGlobalShapeUndisplaced) {
  SuperquadricShapeParameters shape;
  shape << 1.0, 1.1, 0.7, 1.6, 0.8, 1.3, 0.3, -0.2, 0.15, 0.2, 0.6, 0.7, 0.25, -0.15;
  const DeformableSuperquadricShape surface(shape);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -1, 2).normalized()).matrix();
  const Eigen::Vector3d centre(0.3, -0.2, 1.0);
  Eigen::MatrixX3d points(20 * 30, 3);
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 30; ++j) {
      const double u = -kPi / 2 + kPi * (i + 0.5) / 20;
      const double v = -kPi + 2.0 * kPi * (j + 0.5) / 30;
      points.row(i * 30 + j) = (centre + rotation * surface.point(u, v)).transpose();
    }
  }
  const SuperquadricLocalFitResult fit =
      fit_superquadric_local_displacements(points, shape, centre, rotation);
  // The offsets p_k - s(u_k) are round-off (~1e-16) and so is the solution.
  EXPECT_LT(fit.displacements.cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LT(fit.global_rms_error, 1e-14);
}

// The fit is the equilibrium K_d q_d = f_q: the energy (1/2N) sum |p_k - s_k - S_k q_d|^2 +
// (lambda/2) q_d^T K_d q_d is stationary at the fitted q_d in every direction.
TEST(SuperquadricLocalFitting, IsTheMinimumOfDataAndStiffnessEnergy) {
  BumpedSphere bump;
  bump.nu = 12;
  bump.nv = 20;
  SuperquadricLocalFitSettings settings;
  settings.stiffness = {1.0, 0.5, 0.2};
  settings.smoothness = 1e-3;
  const Eigen::MatrixX3d points = bump.points();
  const SuperquadricLocalFitResult fit = fit_superquadric_local_displacements(
      points, unit_sphere(), Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), settings);
  const ParametricFeMesh mesh(settings.mesh_cells_u, settings.mesh_cells_v);
  const Eigen::SparseMatrix<double> stiffness = mesh.stiffness_matrix(settings.stiffness);
  const DeformableSuperquadricShape sphere;
  const auto energy = [&](const Eigen::VectorXd& q) {
    double sum = 0.0;
    for (Eigen::Index k = 0; k < points.rows(); ++k) {
      const Eigen::Vector2d uv = fit.parameters.row(k).transpose();
      const Eigen::Vector3d d = mesh.displacement(q, mesh.shape_values(uv.x(), uv.y())).value;
      sum += (points.row(k).transpose() - sphere.point(uv.x(), uv.y()) - d).squaredNorm();
    }
    return 0.5 * sum / static_cast<double>(points.rows()) +
           0.5 * settings.smoothness * q.dot(stiffness * q);
  };
  std::mt19937 random(3);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double at_minimum = energy(fit.displacements);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd direction =
        Eigen::VectorXd::NullaryExpr(fit.displacements.size(), [&] { return gauss(random); });
    const double t = 1e-3;
    const double plus = energy(fit.displacements + t * direction);
    const double minus = energy(fit.displacements - t * direction);
    // A quadratic: the slope (plus - minus) / 2t is zero at the minimum up to round-off of
    // energies ~1e-4 (eps 1e-4 / t ~ 1e-16), the curvature term (plus + minus - 2 E) > 0.
    const double slope = (plus - minus) / (2.0 * t);
    const double curvature = (plus + minus - 2.0 * at_minimum) / (t * t);
    EXPECT_LT(std::abs(slope), 1e-9 * curvature);
    EXPECT_GT(curvature, 0.0);
  }
}

TEST(SuperquadricLocalFitting, BadSettingsThrowNamingTheValue) {
  using testing::error_message;
  const Eigen::MatrixX3d points = BumpedSphere{}.points();
  const auto fit = [&](const SuperquadricLocalFitSettings& settings) {
    fit_superquadric_local_displacements(points, unit_sphere(), Eigen::Vector3d::Zero(),
                                         Eigen::Matrix3d::Identity(), settings);
  };
  SuperquadricLocalFitSettings settings;
  settings.smoothness = -1e-3;
  EXPECT_THAT(error_message([&] { fit(settings); }), ::testing::HasSubstr("smoothness is -0.001"));
  settings = {};
  settings.smoothness = 0.0;
  EXPECT_THAT(error_message([&] { fit(settings); }), ::testing::HasSubstr("smoothness is 0"));
  settings = {};
  settings.stiffness.membrane_v = -2.0;
  EXPECT_THAT(error_message([&] { fit(settings); }), ::testing::HasSubstr("membrane_v -2"));
  settings = {};
  settings.mesh_cells_v = 2;
  EXPECT_THAT(error_message([&] { fit(settings); }), ::testing::HasSubstr("8 x 2"));
  Eigen::MatrixX3d bad = points;
  bad(7, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THAT(error_message([&] {
                fit_superquadric_local_displacements(bad, unit_sphere(), Eigen::Vector3d::Zero(),
                                                     Eigen::Matrix3d::Identity());
              }),
              ::testing::HasSubstr("inf"));
}

}  // namespace
}  // namespace dnurbs
