// Tests of dynamics/swung/swung_quadrature.h: the Gauss rule over the span products of a swung
// surface, the cached bases against fresh evaluations, and the checked material values.

#include "dnurbs/dynamics/swung/swung_quadrature.h"

#include <cmath>

#include <gtest/gtest.h>

#include "dnurbs/nurbs/swung_shapes.h"
#include "tests/common/error_message.h"
#include "tests/nurbs/swung_sample_shapes.h"

namespace dnurbs {
namespace {

TEST(SwungQuadrature, WeightsIntegratePolynomialsOfTheRuleDegreeExactly) {
  const SwungSurface surface = testing::random_swung_surface(3, 2, 91, true);
  const SwungQuadrature quadrature(surface, 4, 3, {});
  // 4 points per span of the profile's 4 spans, 3 per span of the trajectory's 6 (periodic).
  EXPECT_EQ(quadrature.profile_point_count(), 16);
  EXPECT_EQ(quadrature.trajectory_point_count(), 18);
  double area = 0.0;
  double moment = 0.0;
  for (int i = 0; i < quadrature.profile_point_count(); ++i) {
    for (int j = 0; j < quadrature.trajectory_point_count(); ++j) {
      const Eigen::Vector2d u = quadrature.parameter(i, j);
      area += quadrature.weight(i, j);
      moment += quadrature.weight(i, j) * std::pow(u.x(), 7) * std::pow(u.y(), 5);
    }
  }
  // Exact for degree 7 in u (4 points) and 5 in v (3 points) on [0, 1]^2: round-off only.
  EXPECT_NEAR(area, 1.0, 1e-15);
  EXPECT_NEAR(moment, 1.0 / 48.0, 1e-15);
}

TEST(SwungQuadrature, CachedSamplesEqualFreshEvaluationsAtTheGaussPoints) {
  const SwungSurface surface = testing::random_swung_surface(3, 2, 92, true);
  const SwungQuadrature quadrature(surface, 4, 3, {});
  for (const WeightMode mode : {WeightMode::kFixed, WeightMode::kFree}) {
    const SwungLayout layout = swung_layout(surface, mode);
    const Eigen::VectorXd q = swung_coordinates(surface, mode);
    std::vector<PlanarCurveSample> profile;
    std::vector<PlanarCurveSample> trajectory;
    quadrature.sample(layout, q.data(), surface.profile().weights().data(),
                      surface.trajectory().weights().data(), profile, trajectory);
    ASSERT_EQ(profile.size(), 16U);
    ASSERT_EQ(trajectory.size(), 18U);
    for (int i = 0; i < 16; ++i) {
      const double u = quadrature.parameter(i, 0).x();
      const Eigen::Vector3d expected = surface.profile().point(u);
      const PlanarCurveSample& s = profile[static_cast<size_t>(i)];
      // The same basis values, a rational evaluation in another order: round-off.
      EXPECT_LT((s.point.col(0) - Eigen::Vector2d(expected.x(), expected.z())).norm(), 1e-14);
    }
    for (int j = 0; j < 18; ++j) {
      const double v = quadrature.parameter(0, j).y();
      const CurveDerivatives expected = surface.trajectory().derivatives(v, 2);
      const PlanarCurveSample& s = trajectory[static_cast<size_t>(j)];
      for (int d = 0; d < 3; ++d) {
        EXPECT_LT((s.point.col(d) - expected.row(d).head<2>().transpose()).norm(),
                  1e-12 * (1.0 + expected.row(d).norm()));
      }
    }
  }
}

TEST(SwungQuadrature, MaterialValuesAreCheckedAndTwistRigidityIsDoubled) {
  const SwungSurface sphere = swung_sphere(1.0);
  DNurbsSurfaceMaterial material;
  material.mass_density =
      MaterialFunction([](const Eigen::Vector2d& u) { return 1.0 + u.x() + 2.0 * u.y(); });
  material.b11 = 0.25;
  material.a01 = 0.5;
  const SwungQuadrature quadrature(sphere, 3, 3, material);
  EXPECT_FALSE(quadrature.has_damping());
  EXPECT_TRUE(quadrature.has_stiffness(2));
  EXPECT_FALSE(quadrature.has_stiffness(1));
  EXPECT_EQ(quadrature.stiffness_order(), 2);  // b11 weighs S_uv
  const double* m = quadrature.material(4, 7);
  const Eigen::Vector2d u = quadrature.parameter(4, 7);
  EXPECT_EQ(m[0], 1.0 + u.x() + 2.0 * u.y());
  EXPECT_EQ(m[1 + 2], 0.5);  // a01
  EXPECT_EQ(m[1 + 4], 0.5);  // 2 b11 (Terzopoulos, eq. 1.20)
  material.damping_density =
      MaterialFunction([](const Eigen::Vector2d& p) { return p.x() > 0.5 ? -1.0 : 0.0; });
  EXPECT_NE(testing::error_message([&] {
              SwungQuadrature(sphere, 3, 3, material);
            }).find("damping density is negative (-1)"),
            std::string::npos);
}

}  // namespace
}  // namespace dnurbs
