// The wind force of dynamics/core/forces.h: the viscous fluid force drag (n . (v - xdot)) n per
// unit area of Terzopoulos, Platt, Barr & Fleischer 1987, section 5.

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "tests/common/dynamics_test_helpers.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

// The sum of a generalized force over the points of a model with 3 coordinates per point: the
// total force when the basis functions sum to one (non-rational D-NURBS, grid nodes).
Eigen::Vector3d total(const Eigen::VectorXd& force) {
  return force.reshaped(3, force.size() / 3).rowwise().sum();
}

Eigen::VectorXd generalized_wind(const Model& model, const Force& force, const Eigen::VectorXd& qd,
                                 double time = 0.0) {
  const Eigen::VectorXd q = model.initial_coordinates();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(model.velocity_count());
  force(model, time, q, qd, f);
  return f;
}

// A flat bicubic D-NURBS sheet x(u, v) = origin + u a + v b on [0, 1]^2 (linear in u and v: its
// control points are those of flat_patch mapped by (u, v, 0) -> origin + u a + v b).
DNurbsSurface tilted_dnurbs_sheet(const Eigen::Vector3d& origin, const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b) {
  const NurbsSurface patch = test::flat_patch(3, 3, 3, 2);
  Eigen::MatrixX3d points = patch.control_points();
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const Eigen::Vector3d p = points.row(k).transpose();
    points.row(k) = (origin + p.x() * a + p.y() * b).transpose();
  }
  return DNurbsSurface(NurbsSurface(patch.knots_u(), patch.knots_v(), points));
}

// A flat Terzopoulos sheet of nu by nv nodes at spacing h along the unit axes a, b.
TerzopoulosSurface tilted_grid_sheet(int nu, int nv, double h, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& b, double eta = 1.0) {
  const Grid grid(nu, nv, h);
  TerzopoulosMaterial material;
  material.eta << eta, 0.0, 0.0, eta;
  return TerzopoulosSurface(grid, flat_grid_positions(grid, Eigen::Vector3d(0.3, -0.2, 0.7), a, b),
                            material);
}

const Eigen::Vector3d kWind(2.0, -1.5, 4.0);

TEST(Wind, FlatDNurbsSheetAtRestFeelsDragTimesAreaTimesNormalWind) {
  // A parallelogram of sides a and b: area |a x b|, normal (a x b) / |a x b|. The force density
  // is constant on it and the Gauss rule integrates the bicubic basis functions exactly; they
  // sum to one, so the control points' forces add up to drag * area * (n . v) n.
  const Eigen::Vector3d a(1.2, 0.3, -0.4);
  const Eigen::Vector3d b(-0.2, 0.9, 0.5);
  const DNurbsSurface sheet = tilted_dnurbs_sheet(Eigen::Vector3d(1, 2, 3), a, b);
  const double drag = 0.7;
  const Eigen::Vector3d n = a.cross(b).normalized();
  const double area = a.cross(b).norm();
  const Eigen::Vector3d expected = drag * area * n.dot(kWind) * n;
  const Eigen::VectorXd f =
      generalized_wind(sheet, wind(kWind, drag), Eigen::VectorXd::Zero(sheet.velocity_count()));
  // Round-off of the quadrature sums: a few ulps of the total
  EXPECT_LE((total(f) - expected).norm(), 1e-12 * expected.norm());
}

TEST(Wind, FlatGridSheetAtRestFeelsDragTimesNodeAreaTimesNormalWind) {
  // The grid's node-area rule gives each of the nu nv nodes the area h^2: the forces sum to
  // drag * (nu nv h^2) * (n . v) n, the area of nu nv cells, not that of the sheet,
  // (nu - 1)(nv - 1) h^2 (7 * 5 * 0.2^2 = 1.4 against 6 * 4 * 0.2^2 = 0.96 here).
  const Eigen::Vector3d a = Eigen::Vector3d(1.0, 2.0, 2.0) / 3.0;
  const Eigen::Vector3d b = Eigen::Vector3d(2.0, -2.0, 1.0) / 3.0;  // a . b = 0, unit
  const TerzopoulosSurface sheet = tilted_grid_sheet(7, 5, 0.2, a, b);
  const double drag = 1.3;
  const Eigen::Vector3d n = a.cross(b);
  const double node_area = 7 * 5 * 0.2 * 0.2;
  const Eigen::Vector3d expected = drag * node_area * n.dot(kWind) * n;
  const Eigen::VectorXd f =
      generalized_wind(sheet, wind(kWind, drag), Eigen::VectorXd::Zero(sheet.velocity_count()));
  EXPECT_LE((total(f) - expected).norm(), 1e-12 * expected.norm());
  // Every node gets its share drag h^2 (n . v) n: the border tangents of a flat sheet are exact
  const Eigen::Vector3d share = drag * 0.04 * n.dot(kWind) * n;
  for (Eigen::Index k = 0; k < f.size() / 3; ++k) {
    EXPECT_LE((f.segment<3>(3 * k) - share).norm(), 1e-12 * share.norm()) << "node " << k;
  }
}

TEST(Wind, SheetMovingWithTheWindOrParallelToItFeelsNothing) {
  const Eigen::Vector3d a(1.2, 0.3, -0.4);
  const Eigen::Vector3d b(-0.2, 0.9, 0.5);
  const DNurbsSurface dnurbs_sheet = tilted_dnurbs_sheet(Eigen::Vector3d(1, 2, 3), a, b);
  const TerzopoulosSurface grid_sheet =
      tilted_grid_sheet(6, 6, 0.25, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
  const double drag = 2.0;
  const double scale = drag * kWind.norm();  // the force per unit area a sheet at rest could feel
  for (const Model* model : std::vector<const Model*>{&dnurbs_sheet, &grid_sheet}) {
    // Every control point or node moves with v: xdot = sum N_i v = v (partition of unity)
    const Eigen::VectorXd with_wind = kWind.replicate(model->velocity_count() / 3, 1);
    const Eigen::VectorXd f = generalized_wind(*model, wind(kWind, drag), with_wind);
    // v - xdot is the round-off of sum N_i v: ulps of |v|
    EXPECT_LE(f.cwiseAbs().maxCoeff(), 1e-14 * scale);
  }
  // Wind in the plane of each sheet: n . v = 0 up to the round-off of the normal
  const Eigen::Vector3d in_plane = 3.0 * a - 2.0 * b;
  const Eigen::VectorXd at_rest = Eigen::VectorXd::Zero(dnurbs_sheet.velocity_count());
  const Eigen::VectorXd f = generalized_wind(dnurbs_sheet, wind(in_plane, drag), at_rest);
  EXPECT_LE(f.cwiseAbs().maxCoeff(), 1e-14 * drag * in_plane.norm());
  const Eigen::VectorXd g = generalized_wind(grid_sheet, wind(Eigen::Vector3d(3, -4, 0), drag),
                                             Eigen::VectorXd::Zero(grid_sheet.velocity_count()));
  EXPECT_EQ(g.cwiseAbs().maxCoeff(), 0.0);  // n = (0, 0, 1) exactly
}

TEST(Wind, GridForceIsTheNodeByNodeSumOfLTransposeDensity) {
  // A deformed, moving grid sheet: the force through add_distributed_force against the sum,
  // computed here point by point, of L(u_k)^T h^2 drag (N . (v - L(u_k) qd)) N / |N| with
  // N = x_u x x_v from the sample's tangents (the model's difference operators) and L from
  // position_jacobian at each node's parameter.
  const double h = 0.2;
  const TerzopoulosSurface sheet =
      tilted_grid_sheet(5, 4, h, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
  Eigen::VectorXd q = sheet.initial_coordinates();
  Eigen::VectorXd qd(q.size());
  for (Eigen::Index k = 0; k < q.size(); ++k) {
    q[k] += 0.05 * std::sin(1.7 * static_cast<double>(k));
    qd[k] = std::cos(0.9 * static_cast<double>(k));
  }
  const double drag = 0.8;
  const auto velocity = [](double t) { return Eigen::Vector3d(1.0 + t, -0.5, 2.0 * t); };
  Eigen::VectorXd f = Eigen::VectorXd::Zero(q.size());
  wind(velocity, drag)(sheet, 0.75, q, qd, f);

  std::vector<MaterialSample> samples;
  Eigen::VectorXd unused = Eigen::VectorXd::Zero(q.size());
  sheet.add_distributed_force(
      q,
      [&samples](const MaterialSample& sample) -> Eigen::Vector3d {
        samples.push_back(sample);
        return Eigen::Vector3d::Zero();
      },
      unused);
  ASSERT_EQ(samples.size(), 20U);
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(q.size());
  for (const MaterialSample& sample : samples) {
    const SparseMatrix jacobian = sheet.position_jacobian(q, sample.parameter);
    const Eigen::Vector3d xdot = jacobian * qd;
    const Eigen::Vector3d normal = sample.tangent_u.cross(sample.tangent_v);
    const Eigen::Vector3d density =
        drag * normal.dot(velocity(0.75) - xdot) / normal.norm() * normal;
    expected += jacobian.transpose() * (h * h * density);
  }
  EXPECT_LE((f - expected).cwiseAbs().maxCoeff(), 1e-14 * expected.cwiseAbs().maxCoeff());
  EXPECT_GT(expected.cwiseAbs().maxCoeff(), 0.1);
}

TEST(Wind, CurvesFeelNoWindAndBadDragIsRefused) {
  const DNurbsCurve rod(test::straight_curve(3, 4));
  Eigen::VectorXd qd = Eigen::VectorXd::Ones(rod.velocity_count());
  EXPECT_EQ(generalized_wind(rod, wind(kWind, 1.0), qd).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_NE(testing::error_message([] { wind(kWind, -0.5); }).find("-0.5"), std::string::npos);
  EXPECT_NE(testing::error_message([] {
              wind(kWind, std::numeric_limits<double>::quiet_NaN());
            }).find("nan"),
            std::string::npos);
  EXPECT_NE(testing::error_message([] {
              wind(Eigen::Vector3d(std::numeric_limits<double>::infinity(), 0, 0), 1.0);
            }).find("inf"),
            std::string::npos);
  EXPECT_THROW(wind(VectorOfTime(), 1.0), Error);
}

// A free flat sheet falling face-down under gravity g in still air with drag gamma: every node
// obeys mu h^2 vdot = -mu h^2 g - gamma h^2 v (the sheet stays flat and unstretched), so
// v(t) = -v_t (1 - exp(-gamma t / mu)) with v_t = mu g / gamma. Returns the largest error of
// the node velocities against v(t) over the run, and sets `terminal` to the final velocity.
double falling_sheet(IntegratorScheme scheme, double dt, double duration, double& terminal) {
  const double mu = 0.8;
  const double g = 9.81;
  const double gamma = 2.5;
  const Grid grid(6, 6, 0.2);
  TerzopoulosMaterial material;
  material.mass_density = mu;
  material.eta << 4.0, 0.0, 0.0, 4.0;  // stretching only (xi = 0), no material damping
  System system(
      TerzopoulosSurface(grid, flat_grid_positions(grid, Eigen::Vector3d(0, 0, 5)), material));
  system.add_force(0, gravity(Eigen::Vector3d(0, 0, -g)));
  system.add_force(0, wind(Eigen::Vector3d(0, 0, 0), gamma));
  IntegratorSettings settings;
  settings.scheme = scheme;
  Integrator integrator(settings);
  const double v_t = mu * g / gamma;
  double worst = 0.0;
  const int steps = static_cast<int>(std::lround(duration / dt));
  for (int s = 1; s <= steps; ++s) {
    integrator.step(system, dt);
    const double exact = -v_t * (1.0 - std::exp(-gamma * s * dt / mu));
    const Eigen::VectorXd& qd = system.velocities();
    for (Eigen::Index k = 0; k < qd.size(); ++k) {
      worst = std::max(worst, std::abs(qd[k] - (k % 3 == 2 ? exact : 0.0)));
    }
  }
  terminal = system.velocities().reshaped(3, system.velocity_count() / 3).row(2).mean();
  return worst / v_t;
}

TEST(Wind, FallingSheetReachesTerminalVelocityMuGOverGamma) {
  const double v_t = 0.8 * 9.81 / 2.5;
  for (const IntegratorScheme scheme :
       {IntegratorScheme::kNewmark, IntegratorScheme::kImplicitEuler}) {
    double terminal = 0.0;
    double terminal_fine = 0.0;
    // 7 s: exp(-gamma t / mu) = exp(-21.9) = 3e-10. Not much longer: a free sheet without
    // bending stiffness falling in drag is unstable to wrinkling, and the round-off seeds it
    // (measured spread of the node velocities: 1e-10 of v_t at 7 s, 1e-5 at 12 s)
    const double coarse = falling_sheet(scheme, 0.02, 7.0, terminal);
    const double fine = falling_sheet(scheme, 0.01, 7.0, terminal_fine);
    std::printf(
        "%s: terminal velocity %.17g (exact %.17g, relative error %.2e); largest "
        "relative error of v(t) %.3e at dt 0.02, %.3e at dt 0.01 (ratio %.3f)\n",
        std::string(to_string(scheme)).c_str(), -terminal, v_t, std::abs(-terminal - v_t) / v_t,
        coarse, fine, coarse / fine);
    // The steady state of the step is the exact balance mu g = gamma v_t (a = 0): only the
    // rest of the exponential (3e-10) and the wrinkling remain
    EXPECT_NEAR(-terminal, v_t, 1e-6 * v_t);
    EXPECT_NEAR(-terminal_fine, v_t, 1e-6 * v_t);
    if (scheme == IntegratorScheme::kNewmark) {
      // The Terzopoulos block is state-dependent, so Newmark starts its solve from the last
      // acceleration and evaluates the drag at a velocity within O(dt^2) of the end of the
      // step: second order, halving dt quarters the error (measured 5.98e-4 and 1.50e-4)
      EXPECT_LT(fine, 2e-4);
      EXPECT_GT(coarse / fine, 3.6);
      EXPECT_LT(coarse / fine, 4.4);
    } else {
      // Implicit Euler is first order: halving dt halves the error (1.18e-2 and 5.82e-3)
      EXPECT_LT(fine, 7e-3);
      EXPECT_GT(coarse / fine, 1.8);
      EXPECT_LT(coarse / fine, 2.2);
    }
  }
}

}  // namespace
}  // namespace dnurbs
