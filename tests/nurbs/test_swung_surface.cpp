// Tests of nurbs/swung_surface.h: the swung surface against its exact tensor-product twin, its
// derivatives against finite differences, closed trajectories without a seam, normals (including
// the collapsed poles of a sphere) and the validation of its input.

#include "dnurbs/nurbs/swung_surface.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/swung_shapes.h"
#include "swung_sample_shapes.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

struct SwungCase {
  const char* name;
  SwungSurface surface;
};

std::vector<SwungCase> swung_cases() {
  return {
      {"cubic profile, open quadratic trajectory", testing::random_swung_surface(3, 2, 11, false)},
      {"quadratic profile, periodic cubic trajectory",
       testing::random_swung_surface(2, 3, 21, true)},
      {"quartic profile, periodic quadratic trajectory",
       testing::random_swung_surface(4, 2, 31, true)},
      {"non-rational cubic profile and periodic trajectory",
       testing::random_swung_surface(3, 3, 41, true, false)},
      {"torus (periodic profile and trajectory)", swung_torus(3.0, 1.0)}};
}

TEST(SwungSurface, EqualsItsTensorProductTwinAtRandomParameters) {
  std::mt19937 generator(5);
  std::uniform_real_distribution<double> parameter(0.0, 1.0);
  for (const SwungCase& test_case : swung_cases()) {
    const SwungSurface& swung = test_case.surface;
    const NurbsSurface twin = swung.to_nurbs_surface();
    EXPECT_EQ(twin.knots_u(), swung.profile().knots());
    EXPECT_EQ(twin.knots_v(), swung.trajectory().knots());
    double point_error = 0.0;
    double derivative_error = 0.0;
    for (int sample = 0; sample < 300; ++sample) {
      const double u = parameter(generator);
      const double v = parameter(generator);
      const SurfaceDerivatives a = swung.derivatives(u, v, 2);
      const SurfaceDerivatives b = twin.derivatives(u, v, 2);
      EXPECT_LT((swung.point(u, v) - a(0, 0)).norm(), 1e-15);  // the same products
      point_error = std::max(point_error, (a(0, 0) - b(0, 0)).norm() / (1.0 + b(0, 0).norm()));
      for (int k = 0; k <= 2; ++k) {
        for (int l = 0; k + l <= 2; ++l) {
          derivative_error =
              std::max(derivative_error, (a(k, l) - b(k, l)).norm() / (1.0 + b(k, l).norm()));
        }
      }
    }
    // Exact identity; the two evaluations differ only by rounding (quotients of sums of a few
    // dozen products with weights 0.5..2.5).
    EXPECT_LT(point_error, 1e-13) << test_case.name;
    // The quotient rule of the twin's second derivatives divides by W(u) W(v) and subtracts
    // terms of size |S^(k,l)| times weight derivatives, so rounding grows by about 10.
    EXPECT_LT(derivative_error, 2e-13) << test_case.name;  // measured up to 3e-14
  }
}

TEST(SwungSurface, DerivativesMatchFiniteDifferences) {
  for (const SwungCase& test_case : swung_cases()) {
    const SwungSurface& swung = test_case.surface;
    const double h = 1e-5;
    for (const auto& [u, v] :
         {std::pair{0.13, 0.71}, std::pair{0.52, 0.08}, std::pair{0.88, 0.4}}) {
      const SurfaceDerivatives d = swung.derivatives(u, v, 3);
      const SurfaceDerivatives up = swung.derivatives(u + h, v, 2);
      const SurfaceDerivatives um = swung.derivatives(u - h, v, 2);
      const SurfaceDerivatives vp = swung.derivatives(u, v + h, 2);
      const SurfaceDerivatives vm = swung.derivatives(u, v - h, 2);
      for (int k = 0; k <= 2; ++k) {
        for (int l = 0; k + l <= 2; ++l) {
          const Eigen::Vector3d du = (up(k, l) - um(k, l)) / (2 * h);
          const Eigen::Vector3d dv = (vp(k, l) - vm(k, l)) / (2 * h);
          // Central differences: O(h^2 |S^(4)|) truncation ~1e-8 + O(1e-16 |S| / h) round-off.
          EXPECT_LT((du - d(k + 1, l)).norm(), 1e-6 * (1.0 + d(k + 1, l).norm()))
              << test_case.name << " d/du of S^(" << k << "," << l << ")";
          EXPECT_LT((dv - d(k, l + 1)).norm(), 1e-6 * (1.0 + d(k, l + 1).norm()))
              << test_case.name << " d/dv of S^(" << k << "," << l << ")";
        }
      }
    }
  }
}

TEST(SwungSurface, ClosedTrajectoryHasNoSeam) {
  const SwungSurface swung = testing::random_swung_surface(3, 3, 51, true);
  for (const double u : {0.0, 0.3, 0.77, 1.0}) {
    const SurfaceDerivatives start = swung.derivatives(u, 0.0, 2);
    const SurfaceDerivatives end = swung.derivatives(u, 1.0 - 1e-15, 2);
    for (int k = 0; k <= 2; ++k) {
      for (int l = 0; k + l <= 2; ++l) {
        // A periodic cubic trajectory is C^2 across the wrap; the end is 1e-15 before it.
        EXPECT_LT((start(k, l) - end(k, l)).norm(), 1e-11 * (1.0 + start(k, l).norm()))
            << "u " << u << " S^(" << k << "," << l << ")";
      }
    }
  }
}

TEST(SwungSurface, NormalMatchesTheTensorProductTwin) {
  for (const SwungCase& test_case : swung_cases()) {
    const NurbsSurface twin = test_case.surface.to_nurbs_surface();
    for (int i = 0; i < 7; ++i) {
      for (int j = 0; j < 7; ++j) {
        const double u = (i + 0.4) / 7.0;
        const double v = (j + 0.7) / 7.0;
        // Both are (S_u x S_v)/|S_u x S_v| of the same surface, up to rounding.
        EXPECT_LT((test_case.surface.unit_normal(u, v) - twin.unit_normal(u, v)).norm(), 1e-11)
            << test_case.name << " at " << u << ", " << v;
      }
    }
  }
}

TEST(SwungSphere, NormalsAreRadialIncludingThePoles) {
  const SwungSurface sphere = swung_sphere(1.7);
  for (int i = 0; i <= 40; ++i) {
    for (int j = 0; j <= 40; ++j) {
      const double u = i / 40.0;
      const double v = j / 40.0;
      const Eigen::Vector3d x = sphere.point(u, v);
      // u runs from the south to the north pole and v counter-clockwise: S_u x S_v points
      // inward, and at the poles (u = 0, 1) the limit is -x/|x| too.
      EXPECT_NEAR(sphere.unit_normal(u, v).dot(-x.normalized()), 1.0, 1e-13) << u << " " << v;
    }
  }
}

TEST(SwungSurface, RejectsCurvesOutsideTheirPlanesAndBadAlpha) {
  const NurbsCurve profile = testing::random_profile(2, 3);
  const NurbsCurve trajectory = testing::random_trajectory(2, 4, true);
  Eigen::MatrixX3d lifted = trajectory.control_points();
  lifted(3, 2) = 1e-300;
  const NurbsCurve off_plane(trajectory.knots(), lifted, trajectory.weights());
  EXPECT_NE(testing::error_message([&] {
              SwungSurface(profile, off_plane);
            }).find("trajectory control point 3 has z = 1e-300"),
            std::string::npos);
  Eigen::MatrixX3d bent = profile.control_points();
  bent(1, 1) = -0.5;
  const NurbsCurve bent_profile(profile.knots(), bent, profile.weights());
  EXPECT_NE(testing::error_message([&] {
              SwungSurface(bent_profile, trajectory);
            }).find("profile control point 1 has y = -0.5"),
            std::string::npos);
  EXPECT_NE(
      testing::error_message([&] { SwungSurface(profile, trajectory, 0.0); }).find("alpha is 0"),
      std::string::npos);
  EXPECT_NE(testing::error_message([&] {
              SwungSurface(profile, trajectory, std::nan(""));
            }).find("alpha is nan"),
            std::string::npos);
  EXPECT_THROW(SwungSurface(profile, trajectory).derivatives(0.5, 0.5, kMaxDerivativeOrder + 1),
               Error);
  // Outside the open profile's domain.
  EXPECT_THROW(SwungSurface(profile, trajectory).point(1.5, 0.5), Error);
}

TEST(SwungSurface, NormalAtADegenerateAxisPointThrows) {
  // A profile that touches the axis with a vanishing tangent there (two equal control points on
  // the axis): S_u and S_v both vanish, and no limit normal exists.
  Eigen::MatrixX3d points(4, 3);
  points << 0, 0, 0, 0, 0, 0, 1, 0, 1, 2, 0, 1;
  const NurbsCurve profile(KnotVector::clamped_uniform(3, 4), points);
  const SwungSurface surface(profile, unit_circle_trajectory());
  EXPECT_NE(testing::error_message([&] {
              (void)surface.unit_normal(0.0, 0.3);
            }).find("normal is undefined at (u, v) = (0, 0.3)"),
            std::string::npos);
}

}  // namespace
}  // namespace dnurbs
