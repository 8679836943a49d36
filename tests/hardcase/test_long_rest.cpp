// Hard cases, long runs at rest: 10^6 steps with no force must not drift.

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/surface/grid.h"
#include "hardcase_helpers.h"

namespace dnurbs {
namespace {

using hardcase::record_result;

TEST(LongRest, MillionNewmarkStepsOfACurveAtRestDoNotDrift) {
  // A clamped straight cubic of 6 control points (3 spans, w1 = 1, w2 = 0.1, mu = 1) at its rest
  // shape x(u) = (u, 0, 0): K q_rest is zero up to the round-off of the quadrature sums
  // (~1e-16), so newmark (undamped, energy-conserving) may only oscillate about a static offset
  // K^-1 f_roundoff ~ 1e-16 / lambda_min(K). Stable, in numbers: max |q - q_rest| over 10^6
  // steps of dt = 1/60 stays below 1e-10.
  DNurbsCurveMaterial material;
  material.tension = 1.0;
  material.rigidity = 0.1;
  DNurbsCurve curve(hardcase::straight_cubic(3), material);
  curve.fix_control_point(0);
  curve.fix_control_point(curve.control_point_count() - 1);
  System system(curve);
  const Eigen::VectorXd rest = system.coordinates();
  Integrator integrator;  // newmark
  double drift = 0.0;
  for (int k = 0; k < 1000000; ++k) {
    integrator.step(system, 1.0 / 60.0);
    if (k % 1000 == 999) {
      drift = std::max(drift, (system.coordinates() - rest).cwiseAbs().maxCoeff());
    }
  }
  drift = std::max(drift, (system.coordinates() - rest).cwiseAbs().maxCoeff());
  std::printf("curve at rest: max |q - q_rest| over 1e6 newmark steps %.3e\n", drift);
  EXPECT_LE(drift, 1e-10);
  EXPECT_EQ(integrator.factorization_count(), 1);
  record_result("max |q - q_rest| over 1e6 newmark steps, 6-point cubic at rest", drift,
                "<= 1e-10");
}

TEST(LongRest, TerzopoulosSheetAtRestDoesNotDriftUnderNewmark) {
  // A 5 by 5 Terzopoulos sheet (border clamped, eta_ii = 1, xi = 0.1) at its rest shape: the
  // internal force is -K(q) q with alpha = eta (G - G0) = 0 and beta = xi (B - B0) = 0 at rest,
  // so it vanishes exactly. Stable, in numbers: max |q - q_rest| over 10^4 newmark steps
  // (the matrices are re-assembled every step, so 10^4 keeps the test fast) stays below 1e-10.
  const Grid grid(5, 5, 0.25);
  TerzopoulosMaterial material;
  material.eta << 1.0, 0.0, 0.0, 1.0;
  material.xi << 0.1, 0.1, 0.1, 0.1;
  TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()), material);
  sheet.fix_border();
  System system(sheet);
  const Eigen::VectorXd rest = system.coordinates();
  Integrator integrator;
  double drift = 0.0;
  for (int k = 0; k < 10000; ++k) {
    integrator.step(system, 1.0 / 60.0);
    drift = std::max(drift, (system.coordinates() - rest).cwiseAbs().maxCoeff());
  }
  std::printf("terzopoulos sheet at rest: max |q - q_rest| over 1e4 newmark steps %.3e\n", drift);
  EXPECT_LE(drift, 1e-10);
  record_result("max |q - q_rest| over 1e4 newmark steps, 5x5 Terzopoulos sheet at rest", drift,
                "<= 1e-10");
}

}  // namespace
}  // namespace dnurbs
