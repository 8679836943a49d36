// The curve-on-surface constraint whose samples follow their nearest surface points
// (Terzopoulos 2003, eqs. 1.39-1.40): its rows against finite differences, and a sculpting run
// in which the curve's largest distance from the surface, measured between the samples, is held
// to the bound of Baumgarte's residual plus the interpolation error of the sample spacing.

#include "dnurbs/constraints/curve_on_surface_constraint.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/constraints/constraint_solver.h"
#include "dnurbs/constraints/surface_constraints.h"
#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "tests/common/constraint_test_scenes.h"

namespace dnurbs {
namespace {

ConstraintSolver::Evaluation evaluate_at(const ConstraintSolver& solver, const System& system,
                                         const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  ConstraintSolver::Evaluation evaluation;
  solver.evaluate(system, q, qd, 0.0, evaluation);
  return evaluation;
}

class FollowingCurveOnSurface : public ::testing::TestWithParam<WeightMode> {};

TEST_P(FollowingCurveOnSurface, RowsMatchFiniteDifferences) {
  // The curve runs across the patch up to 0.08 from it, so the foot points' motion matters: C_q is
  // exact off the surface too (dn.r = 0), which these differences of the re-projected C check.
  const System system = testing::surface_and_curve(GetParam());
  ConstraintSolver solver;
  solver.add(system, evenly_sampled_curve_on_surface(system, 1, 0, 5));
  ASSERT_EQ(solver.row_count(), 5);
  const int n = system.velocity_count();
  const Eigen::VectorXd q = system.coordinates();
  Eigen::VectorXd qd(n);
  for (int i = 0; i < n; ++i) {
    qd[i] = 0.3 * std::sin(1.7 * i + 0.4);
  }
  const ConstraintSolver::Evaluation at = evaluate_at(solver, system, q, qd);
  EXPECT_GT(at.value.cwiseAbs().maxCoeff(), 0.02);  // the samples are off the surface
  const Eigen::MatrixXd jacobian = Eigen::MatrixXd(at.jacobian);
  const auto value = [&](const Eigen::VectorXd& coordinates) {
    return Eigen::VectorXd(evaluate_at(solver, system, coordinates, qd).value);
  };
  // Central differences D(h) = C_q + h^2 C''' / 6 + O(h^4). With h = 1e-3 the h^2 term (~1e-7)
  // is far above the rounding eps |C| / h ~ 1e-13 (the projection is exact to round-off and C is
  // stationary in the foot point), so: the error falls by 4 when h halves (a wrong C_q would
  // leave a constant error), and Richardson's (4 D(h/2) - D(h)) / 3 agrees with C_q to
  // O(h^4 C^(5)) + 4 eps |C| / h ~ 1e-12, asserted at 1e-9 (a margin of 1e3 for C^(5)).
  const double h = 1e-3;
  const auto differences = [&](double step) {
    Eigen::MatrixXd numeric(solver.row_count(), n);
    for (int k = 0; k < n; ++k) {
      Eigen::VectorXd plus = q;
      Eigen::VectorXd minus = q;
      plus[k] += step;
      minus[k] -= step;
      numeric.col(k) = (value(plus) - value(minus)) / (2.0 * step);
    }
    return numeric;
  };
  const Eigen::MatrixXd coarse = differences(h);
  const Eigen::MatrixXd fine = differences(0.5 * h);
  const double coarse_error = (coarse - jacobian).cwiseAbs().maxCoeff();
  const double fine_error = (fine - jacobian).cwiseAbs().maxCoeff();
  const double richardson_error = ((4.0 * fine - coarse) / 3.0 - jacobian).cwiseAbs().maxCoeff();
  std::cout << "C_q: central difference error " << coarse_error << " (h), " << fine_error
            << " (h/2), Richardson " << richardson_error << "\n";
  EXPECT_NEAR(coarse_error / fine_error, 4.0, 0.4);
  EXPECT_LT(richardson_error, 1e-9 * (1.0 + jacobian.cwiseAbs().maxCoeff()));

  // Along q(s) = q + s qd (qdd = 0): Cdot = dC/ds and -sigma = d^2C/ds^2. Central first and
  // second differences with Richardson extrapolation: O(s^4) truncation plus rounding
  // 4 eps |C| / s^2 ~ 1e-9 at s = 1e-3 (second differences), asserted at 1e-7.
  const auto along = [&](double step) {
    const Eigen::VectorXd forward = value(q + step * qd);
    const Eigen::VectorXd backward = value(q - step * qd);
    const Eigen::VectorXd middle = value(q);
    return std::pair<Eigen::VectorXd, Eigen::VectorXd>{
        (forward - backward) / (2.0 * step), (forward - 2.0 * middle + backward) / (step * step)};
  };
  const auto [rate_coarse, second_coarse] = along(h);
  const auto [rate_fine, second_fine] = along(0.5 * h);
  const Eigen::VectorXd rate = (4.0 * rate_fine - rate_coarse) / 3.0;
  const Eigen::VectorXd second = (4.0 * second_fine - second_coarse) / 3.0;
  std::cout << "Cdot error " << (at.rate - rate).cwiseAbs().maxCoeff() << ", sigma error "
            << (at.sigma + second).cwiseAbs().maxCoeff() << " (|sigma| "
            << at.sigma.cwiseAbs().maxCoeff() << ")\n";
  EXPECT_LT((at.rate - rate).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + rate.cwiseAbs().maxCoeff()));
  EXPECT_LT((at.sigma + second).cwiseAbs().maxCoeff(), 1e-7 * (1.0 + second.cwiseAbs().maxCoeff()));
}

INSTANTIATE_TEST_SUITE_P(FixedAndFreeWeights, FollowingCurveOnSurface,
                         ::testing::Values(WeightMode::kFixed, WeightMode::kFree),
                         [](const auto& info) {
                           return info.param == WeightMode::kFixed ? std::string("FixedWeights")
                                                                   : std::string("FreeWeights");
                         });

// A sculpting scene: a D-NURBS surface with its border clamped (model 0) and a D-NURBS curve
// laid across it (model 1; its control points on the function the surface's control net
// samples, so it starts within about 0.01 of the surface).
System sculpt_scene() {
  DNurbsSurfaceMaterial surface_material;
  surface_material.a10 = surface_material.a01 = 1.0;
  surface_material.b20 = surface_material.b02 = 0.1;
  surface_material.damping_density = 0.5;
  DNurbsSurface surface(testing::curved_patch(false), surface_material);
  surface.fix_border();
  NurbsCurve curve = testing::curve_over_patch(false);
  Eigen::MatrixX3d points = curve.control_points();
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    points(i, 2) = 0.2 * std::sin(3.0 * points(i, 0)) * std::cos(2.0 * points(i, 1));
  }
  curve.set_control_points(points);
  DNurbsCurveMaterial curve_material;
  curve_material.tension = 0.05;
  curve_material.rigidity = 0.01;
  curve_material.damping_density = 4.0;
  System system(surface);
  system.add_model(DNurbsCurve(curve, curve_material));
  return system;
}

struct SculptMeasurement {
  double gap = 0.0;                ///< largest |distance| at the dense parameters over the run
  double sample_residual = 0.0;    ///< largest |distance| at the samples over the run
  double bound = 0.0;              ///< largest residual + spacing^2 / 8 max |d''| over the run
  double worst_bound_ratio = 0.0;  ///< largest gap / bound at one instant
};

// Settles the curve onto the surface for 0.5 s, then pulls the surface at (0.5, 0.35) with a
// mouse spring moving up and sideways for 2 s, with the following (`follow`) or the frozen
// curve-on-surface constraint at `samples` samples. Every 4 steps of the pull, the signed
// distance d(t) of the curve from the surface is measured by projection at parameters 20 times
// denser than the samples.
SculptMeasurement sculpt(bool follow, int samples, double dt) {
  System system = sculpt_scene();
  ConstraintSolver solver;
  if (follow) {
    solver.add(system, evenly_sampled_curve_on_surface(system, 1, 0, samples));
  } else {
    for (auto& constraint : curve_on_surface_constraints(system, 1, 0, samples)) {
      solver.add(system, std::move(constraint));
    }
  }
  IntegratorSettings settings;
  settings.newton_iterations = 2;
  Integrator integrator(settings);
  const int steps_per_hundredth = static_cast<int>(std::lround(0.01 / dt));
  for (int k = 0; k < 50 * steps_per_hundredth; ++k) {
    solver.step(integrator, system, dt);
  }
  const Eigen::Vector2d grab(0.5, 0.35);
  const Eigen::Vector3d start = system.position(0, grab);
  const double t0 = system.time();
  system.add_force(0, spring_force(
                          grab,
                          [start, t0](double t) {
                            return Eigen::Vector3d(start + (t - t0) * Eigen::Vector3d(0.1, 0, 0.4));
                          },
                          20.0));
  constexpr int kDensity = 20;
  const int dense_count = (samples - 1) * kDensity + 1;
  std::vector<double> dense(static_cast<size_t>(dense_count));
  for (int j = 0; j < dense_count; ++j) {
    dense[static_cast<size_t>(j)] = static_cast<double>(j) / (dense_count - 1);
  }
  const double spacing = 1.0 / (samples - 1);
  const double step = spacing / kDensity;
  SculptMeasurement measurement;
  for (int k = 1; k <= 200 * steps_per_hundredth; ++k) {
    solver.step(integrator, system, dt);
    if (k % (4 * steps_per_hundredth) != 0) {
      continue;
    }
    const Eigen::VectorXd d = curve_to_surface_distances(system, 1, 0, dense);
    double residual = 0.0;
    for (int j = 0; j < dense_count; j += kDensity) {
      residual = std::max(residual, std::abs(d[j]));
    }
    double curvature = 0.0;  // max |d''| by second differences on the dense parameters
    for (int j = 1; j + 1 < dense_count; ++j) {
      curvature = std::max(curvature, std::abs(d[j + 1] - 2.0 * d[j] + d[j - 1]) / (step * step));
    }
    const double gap = d.cwiseAbs().maxCoeff();
    const double bound = residual + spacing * spacing / 8.0 * curvature;
    measurement.gap = std::max(measurement.gap, gap);
    measurement.sample_residual = std::max(measurement.sample_residual, residual);
    measurement.bound = std::max(measurement.bound, bound);
    measurement.worst_bound_ratio = std::max(measurement.worst_bound_ratio, gap / bound);
  }
  // The spring did sculpt the surface.
  EXPECT_GT((system.position(0, grab) - start).norm(), 0.05);
  return measurement;
}

TEST(FollowingCurveOnSurface, SculptedCurveStaysOnTheSurfaceBetweenSamples) {
  for (int samples : {8, 16}) {
    const SculptMeasurement follow = sculpt(true, samples, 0.01);
    const SculptMeasurement half_step = sculpt(true, samples, 0.005);
    const SculptMeasurement frozen = sculpt(false, samples, 0.01);
    std::cout << samples << " samples: following gap " << follow.gap << " (at the samples "
              << follow.sample_residual << ", " << half_step.sample_residual << " at dt / 2; bound "
              << follow.bound << "), frozen gap " << frozen.gap << " (at the samples "
              << frozen.sample_residual << ")\n";
    // Between the samples d(t) differs from its linear interpolant of the sample values by at
    // most spacing^2 / 8 max |d''|, so |d| <= residual + spacing^2 / 8 max |d''| at every
    // instant. max |d''| is taken on the dense parameters (20 per sample spacing); the gap is
    // measured on the same parameters, so the bound holds for the measured values exactly.
    EXPECT_LE(follow.worst_bound_ratio, 1.0) << samples << " samples";
    // The residual at the samples is the integrator's error on a constraint non-linear in q
    // (Baumgarte's rows hold C_q qdd, not C itself): Newmark is second order, so halving dt
    // divides it by about 4 (measured 4.6 and 4.5); a wrong C_q or sigma would leave an error
    // that does not fall with dt.
    EXPECT_GT(follow.sample_residual / half_step.sample_residual, 3.0) << samples << " samples";
    // Samples glued to surface points frozen at creation hold their points to rounding, yet the
    // curve between them leaves the surface farther than the following samples let it (measured
    // 4.30e-3 against 1.43e-3 with 8 samples, 1.63e-3 against 1.84e-4 with 16).
    EXPECT_LT(follow.gap, frozen.gap) << samples << " samples";
  }
}

TEST(FollowingCurveOnSurface, BadInputIsRejected) {
  const System system = testing::surface_and_curve(WeightMode::kFixed);
  EXPECT_THROW(evenly_sampled_curve_on_surface(system, 1, 0, 1), Error);
  EXPECT_THROW(evenly_sampled_curve_on_surface(system, 2, 0, 8), Error);
  EXPECT_THROW(evenly_sampled_curve_on_surface(system, 1, -1, 8), Error);
  EXPECT_THROW(evenly_sampled_curve_on_surface(system, 0, 1, 8), Error);  // models swapped
  EXPECT_THROW(evenly_sampled_curve_on_surface(system, 1, 1, 8), Error);  // the same model
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(CurveOnSurfaceConstraint(1, 0, {0.0, nan, 1.0}), Error);
  EXPECT_THROW(CurveOnSurfaceConstraint(1, 0, {0.5}), Error);
  EXPECT_THROW(CurveOnSurfaceConstraint(1, 0, {0.0, 0.5, 0.5}), Error);  // not increasing
  ConstraintSolver solver;
  EXPECT_THROW(solver.add(system, CurveOnSurfaceConstraint(1, 0, {0.0, 1.5})), Error);
  EXPECT_THROW(solver.add(system, CurveOnSurfaceConstraint(1, 5, {0.0, 1.0})), Error);
  EXPECT_EQ(solver.constraint_count(), 0);
  EXPECT_THROW(curve_to_surface_distances(system, 1, 3, {0.5}), Error);
  EXPECT_THROW(curve_to_surface_distances(system, 1, 0, {nan}), Error);
}

}  // namespace
}  // namespace dnurbs
