// Tests of nurbs/swung_refinement.h: knot insertion into both curves keeps the surface (to
// rounding), adds S k control points per curve (open and periodic), and rejects negative counts.

#include "dnurbs/nurbs/swung_refinement.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "dnurbs/nurbs/swung_shapes.h"
#include "tests/common/error_message.h"
#include "tests/nurbs/swung_sample_shapes.h"

namespace dnurbs {
namespace {

TEST(SwungRefinement, SurfaceIsUnchangedAndGainsControlPointsPerSpan) {
  for (const SwungSurface& surface :
       {swung_sphere(1.0), swung_torus(2.0, 0.5), testing::random_swung_surface(3, 2, 41, false)}) {
    const SwungSurface refined = refine_swung_surface(surface, 2, 1);
    const auto spans = [](const NurbsCurve& c) {
      return static_cast<int>(c.knots().non_empty_spans().size());
    };
    EXPECT_EQ(refined.profile().control_point_count(),
              surface.profile().control_point_count() + 2 * spans(surface.profile()));
    EXPECT_EQ(refined.trajectory().control_point_count(),
              surface.trajectory().control_point_count() + spans(surface.trajectory()));
    EXPECT_EQ(refined.profile().is_periodic(), surface.profile().is_periodic());
    EXPECT_EQ(refined.trajectory().is_periodic(), surface.trajectory().is_periodic());
    EXPECT_EQ(refined.alpha(), surface.alpha());
    double worst = 0.0;
    for (int i = 0; i <= 30; ++i) {
      for (int j = 0; j <= 30; ++j) {
        worst = std::max(
            worst, (refined.point(i / 30.0, j / 30.0) - surface.point(i / 30.0, j / 30.0)).norm());
      }
    }
    // Knot insertion is exact in exact arithmetic: rounding of the convex combinations.
    EXPECT_LT(worst, 1e-14);
  }
  const SwungSurface same = refine_swung_surface(swung_sphere(1.0), 0, 0);
  EXPECT_EQ(same.profile().control_points(), swung_sphere(1.0).profile().control_points());
  EXPECT_NE(testing::error_message([] {
              (void)refine_swung_surface(swung_sphere(1.0), 0, -1);
            }).find("trajectory knots per span is -1"),
            std::string::npos);
}

}  // namespace
}  // namespace dnurbs
