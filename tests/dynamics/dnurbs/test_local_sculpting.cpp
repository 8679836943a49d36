// Local sculpting: which control points a sculpted region keeps, and the error that freezing the
// others introduces against the full static solve.

#include "dnurbs/dynamics/dnurbs/local_sculpting.h"

#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/static_equilibrium.h"
#include "dnurbs/nurbs/knot_vector.h"
#include "tests/common/dynamics_test_helpers.h"

namespace dnurbs {
namespace {

using test::flat_patch;
using test::straight_curve;

TEST(LocalSculpting, KeepsTheSpanOfEachParameterGrownByTheMargin) {
  // Cubic 8 x 8 spans: 11 x 11 control points; (0.3, 0.4) lies in span u [0.25, 0.375) (first
  // driven index 2) and v [0.375, 0.5) (first driven index 3)
  const NurbsSurface surface = flat_patch(3, 3, 8, 8);
  const SculptedRegion region{{Eigen::Vector2d(0.3, 0.4)}, {}};
  const std::vector<int> kept = sculpted_control_points(surface, region, 0);
  ASSERT_EQ(kept.size(), 16u);
  for (int i = 2; i <= 5; ++i) {
    for (int j = 3; j <= 6; ++j) {
      EXPECT_TRUE(std::binary_search(kept.begin(), kept.end(), surface.control_point_index(i, j)));
    }
  }
  EXPECT_EQ(sculpted_control_points(surface, region, 1).size(), 36u);    // 6 x 6
  EXPECT_EQ(sculpted_control_points(surface, region, 3).size(), 90u);    // rows 0..8, columns 0..9
  EXPECT_EQ(sculpted_control_points(surface, region, 20).size(), 121u);  // clipped to the net
  // A control point alone, at a corner: itself and its ring, clipped
  const SculptedRegion corner{{}, {0}};
  EXPECT_EQ(sculpted_control_points(surface, corner, 0), std::vector<int>{0});
  EXPECT_EQ(sculpted_control_points(surface, corner, 1), (std::vector<int>{0, 1, 11, 12}));
}

TEST(LocalSculpting, PeriodicCurvesWrapTheRing) {
  // Periodic cubic with 8 control points: the ring of control point 0 wraps to 7 and 1
  const KnotVector knots = KnotVector::periodic_uniform(3, 8);
  Eigen::MatrixX3d points(8, 3);
  for (int i = 0; i < 8; ++i) {
    points.row(i) << std::cos(i * M_PI / 4.0), std::sin(i * M_PI / 4.0), 0.0;
  }
  const NurbsCurve curve(knots, points);
  EXPECT_EQ(sculpted_control_points(curve, {{}, {0}}, 1), (std::vector<int>{0, 1, 7}));
  EXPECT_EQ(sculpted_control_points(curve, {{}, {0}}, 4).size(), 8u);
  // A parameter drives p + 1 = 4 distinct control points
  const double u = 0.5 * (knots.domain_start() + knots.domain_end());
  EXPECT_EQ(sculpted_control_points(curve, {{Eigen::Vector2d(u, 0.0)}, {}}, 0).size(), 4u);
}

TEST(LocalSculpting, BadInputIsRejected) {
  const NurbsSurface surface = flat_patch(2, 2, 3, 3);
  EXPECT_THROW(sculpted_control_points(surface, {{}, {0}}, -1), Error);
  EXPECT_THROW(sculpted_control_points(surface, {{}, {25}}, 0), Error);
  EXPECT_THROW(sculpted_control_points(surface, {{Eigen::Vector2d(1.5, 0.5)}, {}}, 0), Error);
  EXPECT_THROW(sculpted_control_points(surface, {{Eigen::Vector2d(NAN, 0.5)}, {}}, 0), Error);
  EXPECT_THROW(sculpted_control_points(straight_curve(2, 3), {{}, {-1}}, 0), Error);
}

// The static shape under a point force on a clamped sheet (K q = f), with the control points
// outside the region of the force (grown by `margin`; negative: nothing frozen) fixed.
struct SculptResult {
  System system;
  int frozen = 0;
};

SculptResult sculpt(int margin) {
  DNurbsSurfaceMaterial material;
  material.a10 = 1.0;
  material.a01 = 1.0;
  material.b20 = 0.01;
  material.b11 = 0.01;
  material.b02 = 0.01;
  DNurbsSurface model(flat_patch(3, 3, 16, 16), material);
  model.fix_border();
  const Eigen::Vector2d at(0.3, 0.4);
  int frozen = 0;
  if (margin >= 0) {
    frozen = freeze_outside_sculpted_region(model, {{at}, {}}, margin);
  }
  System system(model);
  system.add_force(0, point_force(at, Eigen::Vector3d(0.0, 0.0, 1.0)));
  solve_static_equilibrium(system);
  return {system, frozen};
}

TEST(LocalSculpting, FreezingOutsideTheRegionConvergesToTheFullSolveAsTheMarginGrows) {
  const SculptResult full = sculpt(-1);
  // Error on a 41 x 41 grid of surface points, relative to the largest displacement
  auto error_of = [&](const System& system) {
    double error = 0.0;
    double largest = 0.0;
    for (int a = 0; a <= 40; ++a) {
      for (int b = 0; b <= 40; ++b) {
        const Eigen::Vector2d uv(a / 40.0, b / 40.0);
        const Eigen::Vector3d reference = full.system.position(0, uv);
        error = std::max(error, (system.position(0, uv) - reference).norm());
        largest = std::max(largest, std::abs(reference.z()));
      }
    }
    return error / largest;
  };
  double previous = 1.0;
  const int control_points = 19 * 19;
  for (const int margin : {0, 1, 2, 4, 8}) {
    const SculptResult local = sculpt(margin);
    const double error = error_of(local.system);
    std::cout << "[ local    ] margin " << margin << ": " << control_points - local.frozen << " of "
              << control_points << " control points active, error " << error << "\n";
    EXPECT_LT(error, previous) << "margin " << margin;
    EXPECT_GT(local.frozen, 0);
    EXPECT_LT(
        local.system.velocity_count() - static_cast<int>(local.system.fixed_coordinates().size()),
        full.system.velocity_count() - static_cast<int>(full.system.fixed_coordinates().size()));
    previous = error;
  }
  EXPECT_LT(previous, 0.1);  // margin 8: within 10 % of the full solve's displacement
}

}  // namespace
}  // namespace dnurbs
