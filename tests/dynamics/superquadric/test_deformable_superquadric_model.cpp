// Kinematics, matrices, forces and input checks of the deformable superquadric model
// (dynamics/superquadric/deformable_superquadric_model.h; Terzopoulos 2003, eqs. 1.28-1.38).

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"
#include "dnurbs/surface/signed_power.h"
#include "tests/common/superquadric_test_helpers.h"

namespace dnurbs {
namespace {

using test::deformed_shape;
using test::every_part;
using test::pattern_vector;
using test::Shape;
using test::some_rotation;
using test::superellipsoid;

constexpr double kPi = std::numbers::pi;
const std::vector<double> exponents = {0.1, 0.5, 1.0, 2.0, 4.0};
// Material points away from the seams and poles (where the signed powers are not smooth in u, v
// but x is still smooth in q).
const std::vector<Eigen::Vector2d> material_points = {
    {0.3, 0.7}, {-0.9, 2.5}, {1.2, -1.9}, {0.05, -3.0}, {-1.4, 0.2}};

/// The full model (every coordinate free) at a deformed state with local displacements.
struct FullState {
  DeformableSuperquadricModel model;
  Eigen::VectorXd q;
  Eigen::VectorXd qd;
};

FullState full_state(double exponent, double regularization = 1e-8) {
  DeformableSuperquadricSettings settings;
  settings.parts = every_part();
  settings.mesh_cells_u = 4;
  settings.mesh_cells_v = 6;
  settings.quadrature_points = 2;
  settings.regularization = regularization;
  settings.mass_density = 1.7;
  DeformableSuperquadricModel model(deformed_shape(exponent, exponent),
                                    Eigen::Vector3d(0.2, -0.3, 0.5), some_rotation(), settings);
  Eigen::VectorXd q = model.initial_coordinates();
  const int nd = model.mesh().coordinate_count();
  q.segment(model.local_coordinate_offset(), nd) = 0.05 * pattern_vector(nd, 1.0);
  Eigen::VectorXd qd = 0.7 * pattern_vector(model.velocity_count(), 2.0);
  return {model, q, qd};
}

/// q "+" dv through the model's exponential map.
Eigen::VectorXd advance(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& dv) {
  Eigen::VectorXd out(q.size());
  model.advance_coordinates(q, dv, out);
  return out;
}

// L against central differences of x(q "+" h e_j) for every velocity coordinate j -----------------

TEST(DeformableSuperquadricModel, JacobianMatchesFiniteDifferencesForEveryCoordinate) {
  for (const double exponent : exponents) {
    const FullState s = full_state(exponent);
    const int n = s.model.velocity_count();
    for (const Eigen::Vector2d& u : material_points) {
      const Eigen::MatrixXd jacobian = Eigen::MatrixXd(s.model.position_jacobian(s.q, u));
      ASSERT_EQ(jacobian.rows(), 3);
      ASSERT_EQ(jacobian.cols(), n);
      const double h = 1e-6;
      for (int j = 0; j < n; ++j) {
        const Eigen::VectorXd step = h * Eigen::VectorXd::Unit(n, j);
        const Eigen::Vector3d fd = (s.model.position(advance(s.model, s.q, step), u) -
                                    s.model.position(advance(s.model, s.q, -step), u)) /
                                   (2.0 * h);
        // Central differences: truncation h^2 |x'''| (up to ~1e-10 with the ln^3 factors of the
        // exponent derivatives) plus round-off 1e-16 |x| / h ~ 1e-10.
        EXPECT_LT((fd - jacobian.col(j)).norm(), 1e-7 * (1.0 + jacobian.col(j).norm()))
            << "exponent " << exponent << " u (" << u.transpose() << ") coordinate " << j;
      }
    }
  }
}

TEST(DeformableSuperquadricModel, JacobianRateMatchesSecondDifferenceAlongConstantVelocity) {
  // Along q(t) = q "+" t qd (constant body angular velocity and rates), qdd = 0 and
  // x'' = Ldot qd.
  for (const double exponent : exponents) {
    const FullState s = full_state(exponent);
    for (const Eigen::Vector2d& u : material_points) {
      const Eigen::Vector3d rate = s.model.jacobian_rate_times_velocity(s.q, s.qd, u);
      const double h = 1e-4;
      const Eigen::Vector3d fd =
          (s.model.position(advance(s.model, s.q, h * s.qd), u) - 2.0 * s.model.position(s.q, u) +
           s.model.position(advance(s.model, s.q, -h * s.qd), u)) /
          (h * h);
      // Second differences: truncation h^2 |x''''| / 12 ~ 1e-8 |x''''| plus round-off
      // 4e-16 |x| / h^2 ~ 1e-7.
      EXPECT_LT((fd - rate).norm(), 2e-5 * (1.0 + rate.norm()))
          << "exponent " << exponent << " u (" << u.transpose() << ")";
    }
  }
}

// M and g against sums over the quadrature points of the public L and Ldot qd -------------------

TEST(DeformableSuperquadricModel, MassMatrixIsTheQuadratureSumOfMuLTransposeL) {
  const FullState s = full_state(0.5, 0.0);
  ModelMatrices matrices;
  s.model.assemble_matrices(s.q, matrices);
  const int n = s.model.velocity_count();
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(n, n);
  const auto& points = s.model.quadrature_points();
  for (size_t k = 0; k < points.size(); ++k) {
    const Eigen::MatrixXd l =
        Eigen::MatrixXd(s.model.position_jacobian(s.q, Eigen::Vector2d(points[k].u, points[k].v)));
    expected += s.model.quadrature_masses()[k] * l.transpose() * l;
  }
  const Eigen::MatrixXd mass = Eigen::MatrixXd(matrices.mass);
  // The same sum in a different order: round-off only.
  EXPECT_LT((mass - expected).norm(), 1e-12 * expected.norm());
  EXPECT_LT((mass - mass.transpose()).norm(), 1e-14 * expected.norm());
}

TEST(DeformableSuperquadricModel, InertialForceIsMinusTheQuadratureSumOfMuLTransposeLdotQd) {
  const FullState s = full_state(2.0);
  const int n = s.model.velocity_count();
  Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
  s.model.add_inertial_force(s.q, s.qd, g);
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(n);
  const auto& points = s.model.quadrature_points();
  for (size_t k = 0; k < points.size(); ++k) {
    const Eigen::Vector2d u(points[k].u, points[k].v);
    expected -= s.model.quadrature_masses()[k] *
                (Eigen::MatrixXd(s.model.position_jacobian(s.q, u)).transpose() *
                 s.model.jacobian_rate_times_velocity(s.q, s.qd, u));
  }
  // Same sum, different order: round-off only.
  EXPECT_LT((g - expected).norm(), 1e-11 * expected.norm());
}

TEST(DeformableSuperquadricModel, InertialForcePowerIsMinusHalfMdotQuadraticForm) {
  // Energy balance of the free motion: d/dt (1/2 qd^T M qd) = qd^T (M qdd) + 1/2 qd^T Mdot qd
  // vanishes when M qdd = g, so qd^T g = -1/2 qd^T Mdot qd (Mdot by differences along q "+" t qd).
  for (const double exponent : {0.5, 1.0, 2.0}) {
    const FullState s = full_state(exponent, 0.0);
    const int n = s.model.velocity_count();
    Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
    s.model.add_inertial_force(s.q, s.qd, g);
    const double h = 1e-5;
    ModelMatrices plus;
    ModelMatrices minus;
    s.model.assemble_matrices(advance(s.model, s.q, h * s.qd), plus);
    s.model.assemble_matrices(advance(s.model, s.q, -h * s.qd), minus);
    const double mdot_form = s.qd.dot((plus.mass - minus.mass) * s.qd) / (2.0 * h);
    // Central difference of M: h^2 truncation ~ 1e-10 relative, round-off 1e-16 |M| / h.
    EXPECT_NEAR(s.qd.dot(g), -0.5 * mdot_form, 1e-7 * std::abs(mdot_form) + 1e-9)
        << "exponent " << exponent;
  }
}

TEST(DeformableSuperquadricModel, RigidInertialForceIsTheGyroscopicTerm) {
  DeformableSuperquadricModel model(superellipsoid(1.0, 1.0, 0.7, 1.4, 0.6, 1.5));
  ASSERT_EQ(model.velocity_count(), 6);
  const Eigen::VectorXd q = model.initial_coordinates();
  Eigen::VectorXd qd(6);
  qd << 0.1, 0.2, 0.3, 1.0, -2.0, 0.5;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(6);
  model.add_inertial_force(q, qd, g);
  const Eigen::Vector3d omega = qd.tail<3>();
  const Eigen::Matrix3d inertia = model.reference_mass_properties().inertia_about_origin;
  // A symmetric superellipsoid has its centre of mass at the origin (to round-off).
  EXPECT_LT(g.head<3>().norm(), 1e-12);
  EXPECT_LT((g.tail<3>() + omega.cross(inertia * omega)).norm(), 1e-13);
}

TEST(DeformableSuperquadricModel, RigidMassFromPrecomputedPropertiesEqualsQuadratureSum) {
  // A bent (centre of mass off the origin), rotated rigid body: the 6 x 6 M assembled from the
  // mass properties equals the quadrature sum of mu L^T L.
  SuperquadricShapeParameters shape = superellipsoid(1.0, 1.3, 0.9, 0.7, 0.6, 1.4);
  shape[Shape::kBendAmplitude] = 0.2;
  shape[Shape::kBendFrequency] = 0.5;
  const DeformableSuperquadricModel model(shape, Eigen::Vector3d(1, -1, 2), some_rotation());
  ASSERT_TRUE(model.is_rigid());
  const Eigen::VectorXd q = model.initial_coordinates();
  ModelMatrices matrices;
  model.assemble_matrices(q, matrices);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(6, 6);
  for (size_t k = 0; k < model.quadrature_points().size(); ++k) {
    const ParameterQuadraturePoint& point = model.quadrature_points()[k];
    const Eigen::MatrixXd l =
        Eigen::MatrixXd(model.position_jacobian(q, Eigen::Vector2d(point.u, point.v)));
    expected += model.quadrature_masses()[k] * l.transpose() * l;
  }
  EXPECT_GT(model.reference_mass_properties().centre_of_mass.norm(), 1e-3);
  // Same quadrature, summed in a different order: round-off.
  EXPECT_LT((Eigen::MatrixXd(matrices.mass) - expected).norm(), 1e-12 * expected.norm());
}

TEST(DeformableSuperquadricModel, WithoutRotationAndShapeParametersMatricesAreConstant) {
  // Translation and local displacements only: L = [I, R S] does not depend on q.
  DeformableSuperquadricSettings settings;
  settings.parts = DeformableSuperquadricParts::rigid();
  settings.parts.rotation = false;
  settings.parts.local = true;
  settings.mesh_cells_u = 3;
  settings.mesh_cells_v = 4;
  const DeformableSuperquadricModel model(superellipsoid(1, 1, 1, 1, 1, 1), Eigen::Vector3d::Zero(),
                                          some_rotation(), settings);
  ASSERT_TRUE(model.matrices_are_constant());
  ASSERT_NE(model.constant_matrices(), nullptr);
  Eigen::VectorXd q = model.initial_coordinates();
  q += 0.1 * pattern_vector(model.coordinate_count(), 7.0);
  ModelMatrices matrices;
  model.assemble_matrices(q, matrices);
  EXPECT_EQ(
      (Eigen::MatrixXd(matrices.mass) - Eigen::MatrixXd(model.constant_matrices()->mass)).norm(),
      0.0);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(model.velocity_count());
  model.add_inertial_force(q, pattern_vector(model.velocity_count(), 8.0), g);
  EXPECT_EQ(g.norm(), 0.0);
}

// Finite values everywhere ------------------------------------------------------------------------

TEST(DeformableSuperquadricModel, NoNanOrInfAtAnyQuadraturePointForExponentsFromTenthToFour) {
  for (const double e1 : exponents) {
    for (const double e2 : exponents) {
      DeformableSuperquadricSettings settings;
      settings.parts = every_part();
      settings.mesh_cells_u = 4;
      settings.mesh_cells_v = 6;
      settings.quadrature_points = 3;
      const DeformableSuperquadricModel model(deformed_shape(e1, e2), Eigen::Vector3d::Zero(),
                                              some_rotation(), settings);
      const Eigen::VectorXd q = model.initial_coordinates();
      const Eigen::VectorXd qd = pattern_vector(model.velocity_count(), 3.0);
      for (const ParameterQuadraturePoint& point : model.quadrature_points()) {
        const Eigen::Vector2d u(point.u, point.v);
        ASSERT_TRUE(Eigen::MatrixXd(model.position_jacobian(q, u)).allFinite())
            << e1 << " " << e2 << " at " << u.transpose();
        ASSERT_TRUE(model.jacobian_rate_times_velocity(q, qd, u).allFinite());
      }
      // The poles and seams themselves, too.
      for (const Eigen::Vector2d& u :
           {Eigen::Vector2d(kPi / 2, 0.0), Eigen::Vector2d(-kPi / 2, 1.0),
            Eigen::Vector2d(0.0, -kPi), Eigen::Vector2d(0.0, kPi / 2)}) {
        ASSERT_TRUE(Eigen::MatrixXd(model.position_jacobian(q, u)).allFinite());
        ASSERT_TRUE(model.jacobian_rate_times_velocity(q, qd, u).allFinite());
      }
      ModelMatrices matrices;
      model.assemble_matrices(q, matrices);
      ASSERT_TRUE(Eigen::MatrixXd(matrices.mass).allFinite()) << e1 << " " << e2;
      ASSERT_TRUE(Eigen::MatrixXd(matrices.stiffness).allFinite());
      Eigen::VectorXd g = Eigen::VectorXd::Zero(model.velocity_count());
      model.add_inertial_force(q, qd, g);
      ASSERT_TRUE(g.allFinite()) << e1 << " " << e2;
    }
  }
}

// Mass properties -------------------------------------------------------------------------------

TEST(SphereShell, MassIsFourPiMuRSquaredAndInertiaTwoThirdsMassRadiusSquared) {
  const double r = 1.7;
  const double mu = 2.3;
  const double mass = mu * 4.0 * kPi * r * r;
  double previous_error = 1.0;
  for (const int points : {1, 2, 3, 4, 5, 6}) {
    DeformableSuperquadricSettings settings;
    settings.mass_density = mu;
    settings.quadrature_points = points;
    const DeformableSuperquadricModel model(superellipsoid(r, 1, 1, 1, 1, 1),
                                            Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(),
                                            settings);
    const RigidMassProperties& props = model.reference_mass_properties();
    const double mass_error = std::abs(props.mass - mass) / mass;
    const double inertia_error =
        (props.inertia_about_centre - (2.0 / 3.0) * mass * r * r * Eigen::Matrix3d::Identity())
            .norm() /
        (mass * r * r);
    const double error = std::max(mass_error, inertia_error);
    std::cout << "sphere shell, " << points << " Gauss points per direction and cell (8 x 16 "
              << "cells): relative mass error " << mass_error << ", inertia error " << inertia_error
              << "\n";
    // The integrand (cos u, cos^3 u, ...) is smooth: Gauss-Legendre converges geometrically
    // until round-off (~1e-15).
    EXPECT_TRUE(error < 0.1 * previous_error || error < 1e-14) << points << " points: " << error;
    previous_error = error;
    EXPECT_LT(props.centre_of_mass.norm(), 1e-14 * r);
  }
  EXPECT_LT(previous_error, 1e-12);  // 6 points: converged to round-off
}

/// Inertia tensor (about the origin) of the ellipsoid shell (A cos t cos f, B cos t sin f,
/// C sin t) with unit density, by the midpoint rule on an n x 2n (t, f) grid, written here
/// independently of the model's geometry and quadrature.
Eigen::Matrix3d ellipsoid_shell_inertia_midpoint(double a, double b, double c, int n,
                                                 double& mass) {
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  mass = 0.0;
  const double dt = kPi / n;
  const double df = 2.0 * kPi / (2 * n);
  for (int i = 0; i < n; ++i) {
    const double t = -kPi / 2 + (i + 0.5) * dt;
    for (int j = 0; j < 2 * n; ++j) {
      const double f = -kPi + (j + 0.5) * df;
      const Eigen::Vector3d x(a * std::cos(t) * std::cos(f), b * std::cos(t) * std::sin(f),
                              c * std::sin(t));
      const Eigen::Vector3d x_t(-a * std::sin(t) * std::cos(f), -b * std::sin(t) * std::sin(f),
                                c * std::cos(t));
      const Eigen::Vector3d x_f(-a * std::cos(t) * std::sin(f), b * std::cos(t) * std::cos(f), 0.0);
      const double dm = x_t.cross(x_f).norm() * dt * df;
      mass += dm;
      inertia += dm * (x.squaredNorm() * Eigen::Matrix3d::Identity() - x * x.transpose());
    }
  }
  return inertia;
}

TEST(EllipsoidShell, InertiaMatchesAnIndependentMidpointIntegral) {
  const double a = 1.0;
  const double a1 = 1.5;
  const double a2 = 1.0;
  const double a3 = 0.6;
  // Richardson extrapolation of the O(h^2) midpoint rule (n = 400 and 800): error O(h^4).
  double coarse_mass = 0.0;
  double fine_mass = 0.0;
  const Eigen::Matrix3d coarse =
      ellipsoid_shell_inertia_midpoint(a * a1, a * a2, a * a3, 400, coarse_mass);
  const Eigen::Matrix3d fine =
      ellipsoid_shell_inertia_midpoint(a * a1, a * a2, a * a3, 800, fine_mass);
  const double reference_mass = (4.0 * fine_mass - coarse_mass) / 3.0;
  const Eigen::Matrix3d reference = (4.0 * fine - coarse) / 3.0;
  DeformableSuperquadricSettings settings;
  settings.quadrature_points = 6;
  const DeformableSuperquadricModel model(superellipsoid(a, a1, a2, a3, 1, 1),
                                          Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(),
                                          settings);
  const RigidMassProperties& props = model.reference_mass_properties();
  const double mass_error = std::abs(props.mass - reference_mass) / reference_mass;
  const double inertia_error = (props.inertia_about_origin - reference).norm() / reference.norm();
  std::cout << "ellipsoid shell (1.5, 1, 0.6): relative mass error " << mass_error
            << ", inertia error " << inertia_error
            << " against an extrapolated 800 x 1600 midpoint rule\n";
  // Extrapolated midpoint error O(h^4), h = pi/800: ~1e-10; Gauss with 6 points per cell is
  // converged further.
  EXPECT_LT(mass_error, 1e-9);
  EXPECT_LT(inertia_error, 1e-9);
  // Principal moments ordered like the semi-axes: the longest axis (x) has the smallest moment.
  EXPECT_LT(props.inertia_about_origin(0, 0), props.inertia_about_origin(1, 1));
  EXPECT_LT(props.inertia_about_origin(1, 1), props.inertia_about_origin(2, 2));
}

// Forces ----------------------------------------------------------------------------------------

TEST(DeformableSuperquadricModel, InternalForceIsMinusEnergyGradientAndHasNoRigidPart) {
  FullState s = full_state(0.7);
  const int n = s.model.velocity_count();
  // Move q_s off its rest values.
  const int shape_count = static_cast<int>(s.model.free_shape_parameters().size());
  s.q.segment(s.model.shape_coordinate_offset(), shape_count) +=
      0.02 * pattern_vector(shape_count, 5.0);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  s.model.add_internal_force(s.q, f);
  // Internal forces act on the deformation only: no force on c, no torque.
  EXPECT_EQ(f.head<6>().norm(), 0.0);
  EXPECT_GT(f.norm(), 0.0);
  const double h = 1e-6;
  for (int j = 0; j < n; ++j) {
    const Eigen::VectorXd step = h * Eigen::VectorXd::Unit(n, j);
    const double fd = -(s.model.potential_energy(advance(s.model, s.q, step)) -
                        s.model.potential_energy(advance(s.model, s.q, -step))) /
                      (2.0 * h);
    // Quadratic energy: central differences are exact up to round-off 1e-16 E / h.
    EXPECT_NEAR(fd, f[j], 1e-8) << "coordinate " << j;
  }
}

TEST(DeformableSuperquadricModel, GravityGivesTotalWeightOnTheCentreAndNoTorqueAboutCentroid) {
  DeformableSuperquadricSettings settings;
  settings.mass_density = 0.8;
  const DeformableSuperquadricModel model(superellipsoid(1.0, 1.2, 0.9, 0.7, 0.5, 2.0),
                                          Eigen::Vector3d(1, 2, 3), some_rotation(), settings);
  const Eigen::Vector3d gravity(0.0, 0.0, -9.81);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(6);
  model.add_distributed_force(
      model.initial_coordinates(),
      [&](const MaterialSample& sample) -> Eigen::Vector3d {
        return sample.mass_density * gravity;
      },
      f);
  const double mass = model.reference_mass_properties().mass;
  // Same quadrature as the mass: round-off.
  EXPECT_LT((f.head<3>() - mass * gravity).norm(), 1e-12 * mass * 9.81);
  EXPECT_LT(f.tail<3>().norm(), 1e-12 * mass * 9.81);
}

// Coordinates -------------------------------------------------------------------------------------

TEST(DeformableSuperquadricModel, RotationIsAdvancedByTheExponentialMapAndStaysUnit) {
  const DeformableSuperquadricModel model(superellipsoid(1, 1, 1, 1, 1, 1));
  ASSERT_EQ(model.coordinate_count(), 7);
  ASSERT_EQ(model.velocity_count(), 6);
  Eigen::VectorXd q = model.initial_coordinates();
  Eigen::VectorXd dv = Eigen::VectorXd::Zero(6);
  dv.tail<3>() = Eigen::Vector3d(0.0, 0.0, kPi / 2);
  Eigen::VectorXd out(7);
  model.advance_coordinates(q, dv, out);
  const Eigen::Matrix3d rotation = model.orientation(out).toRotationMatrix();
  const Eigen::Matrix3d expected =
      Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_LT((rotation - expected).norm(), 1e-15);
  EXPECT_NEAR(out.segment<4>(3).norm(), 1.0, 1e-15);
}

TEST(DeformableSuperquadricModel, PerParameterSwitchesGiveOnlyTheFreeCoordinates) {
  // Rotation and a, e1, e2 free; translation and every other q_s entry held.
  DeformableSuperquadricSettings settings;
  settings.parts = DeformableSuperquadricParts::rigid();
  settings.parts.translation = false;
  settings.parts.shape[Shape::kScale] = true;
  settings.parts.shape[Shape::kSquareness1] = true;
  settings.parts.shape[Shape::kSquareness2] = true;
  settings.regularization = 0.0;  // no redundancy among (w, a, e1, e2)
  const DeformableSuperquadricModel model(deformed_shape(0.5, 2.0), Eigen::Vector3d(1, 2, 3),
                                          some_rotation(), settings);
  EXPECT_EQ(model.coordinate_count(), 4 + 3);
  EXPECT_EQ(model.velocity_count(), 3 + 3);
  EXPECT_EQ(model.translation_velocity_offset(), -1);
  EXPECT_EQ(model.rotation_velocity_offset(), 0);
  EXPECT_EQ(model.shape_velocity_offset(), 3);
  EXPECT_FALSE(model.is_rigid());
  const Eigen::VectorXd q = model.initial_coordinates();
  EXPECT_DOUBLE_EQ(q[4], 1.3);  // a
  EXPECT_DOUBLE_EQ(q[5], 0.5);  // e1
  EXPECT_DOUBLE_EQ(q[6], 2.0);  // e2
  const Eigen::Vector2d u(0.4, -1.1);
  // The held centre still places the shape.
  const Eigen::Vector3d body =
      DeformableSuperquadricShape(deformed_shape(0.5, 2.0)).point(0.4, -1.1);
  EXPECT_LT((model.position(q, u) - (Eigen::Vector3d(1, 2, 3) + some_rotation() * body)).norm(),
            1e-14);
  const Eigen::MatrixXd jacobian = Eigen::MatrixXd(model.position_jacobian(q, u));
  for (int j = 0; j < 6; ++j) {
    const double h = 1e-6;
    const Eigen::VectorXd step = h * Eigen::VectorXd::Unit(6, j);
    const Eigen::Vector3d fd =
        (model.position(advance(model, q, step), u) - model.position(advance(model, q, -step), u)) /
        (2.0 * h);
    // Central differences, as in JacobianMatchesFiniteDifferencesForEveryCoordinate.
    EXPECT_LT((fd - jacobian.col(j)).norm(), 1e-7 * (1.0 + jacobian.col(j).norm())) << j;
  }
  ModelMatrices matrices;
  model.assemble_matrices(q, matrices);
  EXPECT_EQ(matrices.mass.rows(), 6);
  // Regular: (w, a, e1, e2) are independent motions.
  EXPECT_GT(Eigen::MatrixXd(matrices.mass).ldlt().vectorD().minCoeff(), 0.0);
}

TEST(DeformableSuperquadricModel, ProjectionKeepsExponentsInRangeAndQuaternionUnit) {
  DeformableSuperquadricSettings settings;
  settings.parts = DeformableSuperquadricParts::global();
  const DeformableSuperquadricModel model(superellipsoid(1, 1, 1, 1, 1, 1), Eigen::Vector3d::Zero(),
                                          Eigen::Quaterniond::Identity(), settings);
  Eigen::VectorXd q = model.initial_coordinates();
  Eigen::VectorXd qd = Eigen::VectorXd::Ones(model.velocity_count());
  q.segment<4>(3) *= 1.1;  // a quaternion drifted off unit length
  const auto& free = model.free_shape_parameters();
  const int e1 =
      model.shape_coordinate_offset() +
      static_cast<int>(std::find(free.begin(), free.end(), Shape::kSquareness1) - free.begin());
  const int e1_rate = e1 - model.shape_coordinate_offset() + model.shape_velocity_offset();
  q[e1] = 4.5;
  model.project_state(q, qd);
  EXPECT_DOUBLE_EQ(q.segment<4>(3).norm(), 1.0);
  EXPECT_EQ(q[e1], kMaxSquareness);
  EXPECT_EQ(qd[e1_rate], 0.0);  // the outward rate is removed
  q[e1] = 0.01;
  qd[e1_rate] = -1.0;
  model.project_state(q, qd);
  EXPECT_EQ(q[e1], kMinSquareness);
  EXPECT_EQ(qd[e1_rate], 0.0);
}

// Bad input ---------------------------------------------------------------------------------------

void expect_error_naming(const std::function<void()>& build, const std::string& text) {
  try {
    build();
    ADD_FAILURE() << "no Error for " << text;
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr(text));
  }
}

TEST(DeformableSuperquadricModel, BadInputThrowsErrorNamingTheValue) {
  using Model = DeformableSuperquadricModel;
  expect_error_naming([] { Model m(superellipsoid(0.0, 1, 1, 1, 1, 1)); }, "scale a = 0");
  expect_error_naming([] { Model m(superellipsoid(-2.0, 1, 1, 1, 1, 1)); }, "scale a = -2");
  expect_error_naming([] { Model m(superellipsoid(1, 1, 0, 1, 1, 1)); }, "aspect a2 = 0");
  expect_error_naming([] { Model m(superellipsoid(1, 1, 1, 1, 0.05, 1)); }, "squareness e1 = 0.05");
  expect_error_naming([] { Model m(superellipsoid(1, 1, 1, 1, 1, 4.5)); }, "squareness e2 = 4.5");
  expect_error_naming([] { Model m(superellipsoid(1, 1, 1, 1, std::nan(""), 1)); },
                      "squareness e1 nan");
  expect_error_naming(
      [] { Model m(superellipsoid(1, 1, 1, 1, 1, 1), Eigen::Vector3d(0, std::nan(""), 0)); },
      "centre coordinate nan");
  // A quaternion off unit length by more than 1e-6 is rejected, naming its norm ...
  expect_error_naming(
      [] {
        Model m(superellipsoid(1, 1, 1, 1, 1, 1), Eigen::Vector3d::Zero(),
                Eigen::Quaterniond(2.0, 0.0, 0.0, 0.0));
      },
      "has norm 2");
  // ... one within 1e-6 is normalized.
  const Model nearly(superellipsoid(1, 1, 1, 1, 1, 1), Eigen::Vector3d::Zero(),
                     Eigen::Quaterniond(1.0 + 1e-9, 0.0, 0.0, 0.0));
  EXPECT_DOUBLE_EQ(nearly.initial_coordinates().segment<4>(3).norm(), 1.0);
  DeformableSuperquadricSettings settings;
  settings.mass_density = -1.0;
  expect_error_naming(
      [&] {
        Model m(superellipsoid(1, 1, 1, 1, 1, 1), Eigen::Vector3d::Zero(),
                Eigen::Quaterniond::Identity(), settings);
      },
      "mass density -1");
  settings = {};
  settings.damping_alpha = std::nan("");
  expect_error_naming(
      [&] {
        Model m(superellipsoid(1, 1, 1, 1, 1, 1), Eigen::Vector3d::Zero(),
                Eigen::Quaterniond::Identity(), settings);
      },
      "alpha = nan");
}

}  // namespace
}  // namespace dnurbs
