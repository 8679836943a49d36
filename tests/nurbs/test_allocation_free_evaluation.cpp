// The D-NURBS hot path (points, derivatives and Jacobians at quadrature points) must not touch
// the heap. The counting global operator new of tests/common/allocation_counter.h checks it.
#include <cmath>
#include <new>

#include <gtest/gtest.h>

#include "dnurbs/nurbs/jacobian.h"
#include "dnurbs/nurbs/span_cached_surface_evaluator.h"
#include "sample_shapes.h"
#include "tests/common/allocation_counter.h"

namespace dnurbs {
namespace {

TEST(Evaluation, PointsDerivativesAndJacobiansDoNotAllocate) {
  // The counter sees allocations (so a zero below means something).
  testing::count_allocations = true;
  const long control_start = testing::allocations.load();
  ::operator delete(::operator new(16));  // a direct call, which the compiler may not elide
  ASSERT_EQ(testing::allocations.load() - control_start, 1);

  const NurbsCurve curve = testing::random_rational_curve(3, 61);
  const NurbsSurface surface = testing::random_rational_surface(3, 3, 62, false, true);
  CurveJacobian curve_result;
  SurfaceJacobian surface_result;
  CurveDerivatives curve_derivatives;
  SurfaceDerivatives surface_derivatives;
  const SpanCachedSurfaceEvaluator span_cached(surface);
  SurfaceDerivatives span_cached_derivatives;
  double checksum = 0.0;
  const long before = testing::allocations.load();
  for (int i = 0; i < 1000; ++i) {
    const double u = (i + 0.5) / 1000.0;
    curve_jacobian(curve, u, 2, WeightMode::kFree, curve_result);
    surface_jacobian(surface, u, 1.0 - u, 2, WeightMode::kFree, surface_result);
    curve.derivatives(u, 2, curve_derivatives);
    surface.derivatives(u, 1.0 - u, 2, surface_derivatives);
    span_cached.derivatives(u, 1.0 - u, 2, span_cached_derivatives);
    checksum += curve.point(u).x() + surface.point(u, u).y() + curve_result.basis(2, 1) +
                surface_result.weight_column[4](0, 3) + curve_derivatives(1, 0) +
                surface_derivatives(1, 1).z() + span_cached_derivatives(0, 2).x() +
                span_cached.point(u, u).z();
  }
  const long during = testing::allocations.load() - before;
  testing::count_allocations = false;
  EXPECT_EQ(during, 0);
  EXPECT_TRUE(std::isfinite(checksum));
}

}  // namespace
}  // namespace dnurbs
