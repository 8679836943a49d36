// Tests of dynamics/swung/swung_parametric_surface.h: the domain's closures against the
// tensor-product twin's, the orientation rule on the prototypes (both signs, the flat fallback,
// an open trajectory) and the error for a surface without area.

#include "dnurbs/dynamics/swung/swung_parametric_surface.h"

#include <algorithm>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/nurbs/swung_shapes.h"
#include "tests/common/error_message.h"
#include "tests/nurbs/swung_sample_shapes.h"

namespace dnurbs {
namespace {

// The prototype with its profile run the other way (u -> 1 - u): S_u flips, so does the side.
SwungSurface reversed_profile(const SwungSurface& surface) {
  const NurbsCurve& p = surface.profile();
  std::vector<double> knots = p.knots().knots();
  std::reverse(knots.begin(), knots.end());
  for (double& t : knots) {
    t = 1.0 - t;
  }
  const NurbsCurve reversed(KnotVector(p.degree(), knots), p.control_points().colwise().reverse(),
                            p.weights().reverse());
  return SwungSurface(reversed, surface.trajectory(), surface.alpha());
}

TEST(SwungParametricSurface, DomainEqualsTheTwinsAndFindsPolesAndSeams) {
  for (const SwungSurface& surface :
       {swung_sphere(1.0), swung_torus(2.0, 0.5), swung_cone(1.0, 2.0), swung_cylinder(1.0, 2.0),
        testing::random_swung_surface(3, 2, 5, false)}) {
    const ParameterDomain domain = swung_parameter_domain(surface);
    const ParameterDomain twin = nurbs_parameter_domain(surface.to_nurbs_surface());
    EXPECT_EQ(domain.periodic_u, twin.periodic_u);
    EXPECT_EQ(domain.periodic_v, twin.periodic_v);
    EXPECT_EQ(domain.pole_u_min, twin.pole_u_min);
    EXPECT_EQ(domain.pole_u_max, twin.pole_u_max);
  }
  const ParameterDomain cone = swung_parameter_domain(swung_cone(1.0, 2.0));
  EXPECT_TRUE(!cone.pole_u_min && cone.pole_u_max && cone.periodic_v);  // the apex at u = 1
  const ParameterDomain open =
      swung_parameter_domain(testing::random_swung_surface(3, 2, 5, false));
  EXPECT_FALSE(open.periodic_v || open.periodic_u || open.pole_u_min || open.pole_u_max);
}

TEST(SwungParametricSurface, OrientationFollowsTheSideAwayFromTheAxis) {
  EXPECT_EQ(swung_normal_orientation(swung_sphere(1.0)), NormalOrientation::kSvCrossSu);
  EXPECT_EQ(swung_normal_orientation(reversed_profile(swung_sphere(1.0))),
            NormalOrientation::kSuCrossSv);
  EXPECT_EQ(swung_normal_orientation(swung_cylinder(1.0, 2.0)), NormalOrientation::kSvCrossSu);
  EXPECT_EQ(swung_normal_orientation(swung_cone(1.0, 2.0)), NormalOrientation::kSvCrossSu);
  EXPECT_EQ(swung_normal_orientation(swung_hat(1.5, 0.8, 1.0)), NormalOrientation::kSuCrossSv);
  // Flat profiles: up (+z) is outward; the disk from the rim inward turns it over.
  EXPECT_EQ(swung_normal_orientation(swung_open_profile(0.0, 0.0, 1.0, 0.0)),
            NormalOrientation::kSuCrossSv);
  EXPECT_EQ(swung_normal_orientation(swung_open_profile(1.0, 0.0, 0.0, 0.0)),
            NormalOrientation::kSvCrossSu);
  // alpha = -1 turns the sphere half a turn about z: the same side. A clockwise trajectory
  // (Y mirrored) flips S_v and with it the side.
  const SwungSurface sphere = swung_sphere(1.0);
  EXPECT_EQ(swung_normal_orientation(SwungSurface(sphere.profile(), sphere.trajectory(), -1.0)),
            NormalOrientation::kSvCrossSu);
  Eigen::MatrixX3d mirrored = sphere.trajectory().control_points();
  mirrored.col(1) *= -1.0;
  const NurbsCurve clockwise(sphere.trajectory().knots(), mirrored, sphere.trajectory().weights());
  EXPECT_EQ(swung_normal_orientation(SwungSurface(sphere.profile(), clockwise)),
            NormalOrientation::kSuCrossSv);
}

TEST(SwungParametricSurface, SurfaceWithoutAreaIsRejected) {
  const SwungSurface sphere = swung_sphere(1.0);
  Eigen::MatrixX3d axis = Eigen::MatrixX3d::Zero(5, 3);
  axis.col(2) = Eigen::VectorXd::LinSpaced(5, -1.0, 1.0);
  const SwungSurface line(NurbsCurve(sphere.profile().knots(), axis), sphere.trajectory());
  EXPECT_NE(testing::error_message([&] {
              (void)swung_normal_orientation(line);
            }).find("the surface has no area"),
            std::string::npos);
}

TEST(SwungParametricSurface, NormalIsTheSwungUnitNormalTurnedToTheOrientation) {
  const SwungSurface surface = testing::random_swung_surface(3, 2, 7, true);
  const ParameterDomain domain = swung_parameter_domain(surface);
  for (const NormalOrientation orientation :
       {NormalOrientation::kSuCrossSv, NormalOrientation::kSvCrossSu}) {
    const ParametricSurface parametric = swung_parametric_surface(surface, domain, orientation);
    const double sign = orientation == NormalOrientation::kSuCrossSv ? 1.0 : -1.0;
    for (const auto& [u, v] : {std::pair{0.2, 0.3}, std::pair{0.9, 0.45}}) {
      EXPECT_EQ(parametric.point(u, v), surface.point(u, v));
      // ParametricSurface normalizes the given normal again: the last bits may change.
      EXPECT_LT((parametric.unit_normal(u, v) - sign * surface.unit_normal(u, v)).norm(), 1e-15);
      // The difference normal of the same surface agrees: truncation O(1e-10).
      EXPECT_LT((parametric.difference_normal(u, v) - parametric.unit_normal(u, v)).norm(), 1e-7);
    }
  }
}

}  // namespace
}  // namespace dnurbs
