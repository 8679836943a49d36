// Tests of dynamics/dnurbs/dnurbs_curve.h: mass and stiffness matrices (Terzopoulos 2003,
// eqs. 1.25-1.26), their natural frequencies under knot refinement, and input validation.

#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "dnurbs/core/error.h"
#include "tests/common/dynamics_test_helpers.h"

namespace dnurbs {
namespace {

using test::straight_curve;

Eigen::MatrixXd dense(const SparseMatrix& m) {
  return Eigen::MatrixXd(m);
}

TEST(DNurbsCurveMass, EntriesSumToDensityTimesParametricLength) {
  // Sum_ij integral mu R_i R_j = integral mu (sum R)^2 = mu * length (partition of unity).
  for (int p = 1; p <= 4; ++p) {
    KnotVector knots = KnotVector::clamped_from_breakpoints(p, {0.0, 0.3, 0.5, 1.2, 2.0});
    const Eigen::MatrixX3d points = Eigen::MatrixX3d::Random(knots.control_point_count(), 3);
    DNurbsCurveMaterial material;
    material.mass_density = 2.5;
    const DNurbsCurve model(NurbsCurve(knots, points), material);
    const double sum = dense(model.scalar_matrices()->mass).sum();
    // Gauss rule exact for the degree-2p integrand; round-off of O(100) additions.
    EXPECT_NEAR(sum, 2.5 * 2.0, 1e-12) << "degree " << p;
  }
}

TEST(DNurbsCurveMass, RationalFixedWeightsStillSumToDensityTimesLength) {
  // The rational basis is a partition of unity too; the quadrature of the rational integrand
  // is approximate, so use many points (error of the Gauss rule on a smooth rational function).
  KnotVector knots = KnotVector::clamped_uniform(2, 6);
  Eigen::VectorXd weights(6);
  weights << 1.0, 0.5, 2.0, 1.5, 0.7, 1.0;
  DNurbsSettings settings;
  settings.quadrature_points = 12;
  const DNurbsCurve model(NurbsCurve(knots, Eigen::MatrixX3d::Random(6, 3), weights), {}, settings);
  EXPECT_NEAR(dense(model.scalar_matrices()->mass).sum(), 1.0, 1e-12);
}

TEST(DNurbsCurveMass, IsSymmetricPositiveDefiniteWithKroneckerStructure) {
  DNurbsCurveMaterial material;
  material.mass_density = MaterialFunction([](const Eigen::Vector2d& u) { return 1.0 + u.x(); });
  const DNurbsCurve model(straight_curve(3, 7), material);
  const Eigen::MatrixXd S = dense(model.scalar_matrices()->mass);
  EXPECT_LT((S - S.transpose()).norm(), 1e-15);  // exact symmetry by construction
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(S);
  EXPECT_GT(eigen.eigenvalues().minCoeff(), 0.0);
  // M = S (x) I_3 entry by entry.
  const Eigen::MatrixXd M = dense(model.constant_matrices()->mass);
  for (int i = 0; i < S.rows(); ++i) {
    for (int j = 0; j < S.cols(); ++j) {
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
          EXPECT_EQ(M(3 * i + r, 3 * j + c), r == c ? S(i, j) : 0.0);
        }
      }
    }
  }
}

TEST(DNurbsCurveStiffness, RigidTranslationCostsNothingAndKIsSymmetricPsd) {
  DNurbsCurveMaterial material;
  material.tension = 2.0;
  material.rigidity = MaterialFunction([](const Eigen::Vector2d& u) { return 0.5 + u.x(); });
  KnotVector knots = KnotVector::clamped_from_breakpoints(3, {0.0, 0.2, 0.25, 0.7, 1.0});
  const DNurbsCurve model(NurbsCurve(knots, Eigen::MatrixX3d::Random(7, 3)), material);
  const Eigen::MatrixXd K = dense(model.constant_matrices()->stiffness);
  Eigen::VectorXd translation(K.rows());
  for (int i = 0; i < K.rows() / 3; ++i) {
    translation.segment<3>(3 * i) << 0.3, -1.2, 2.0;
  }
  // sum_i R_i' = 0 pointwise; round-off of entries of size ~|K| = O(100).
  EXPECT_LT((K * translation).lpNorm<Eigen::Infinity>(), 1e-12 * K.lpNorm<Eigen::Infinity>());
  EXPECT_LT((K - K.transpose()).norm(), 1e-15);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(K);
  // PSD up to the eigen solver's round-off relative to the largest eigenvalue.
  EXPECT_GT(eigen.eigenvalues().minCoeff(), -1e-12 * eigen.eigenvalues().maxCoeff());
}

TEST(DNurbsCurveStiffness, PotentialEnergyIsHalfQTransposeKQ) {
  DNurbsCurveMaterial material;
  material.tension = 1.5;
  material.rigidity = 0.25;
  const DNurbsCurve model(straight_curve(3, 5), material);
  const Eigen::VectorXd q = Eigen::VectorXd::Random(model.coordinate_count());
  const double expected = 0.5 * q.dot(model.constant_matrices()->stiffness * q);
  EXPECT_NEAR(model.potential_energy(q), expected, 1e-13 * std::abs(expected));  // round-off
}

TEST(DNurbsCurveStiffness, EnergyChangeOfAFarStraightRodKeepsItsDigits) {
  // A straight rod x(u) = c + 2 u e_x (linear parametrization: control points at the Greville
  // abscissae), far from the origin (c = 1e3 (1, 1, 0)), bent by d = 1e-3 phi in z only. Exactly,
  // E(q0) = (1/2) w1 |x_u|^2 length = (1/2) w1 4 and, as x0_u . d_u = 0 and x0_uu = 0,
  // E(q0 + d) - E(q0) = (1/2) d^T K d. The plain form (1/2) q^T K q would lose that change to
  // the rounding of its 1e6-size terms (eps |K| |q|^2 ~ 1e-8, the change ~ 1e-6); the model
  // expands about q0, which keeps the rounding of the small terms only.
  DNurbsCurveMaterial material;
  material.tension = 1.5;
  material.rigidity = 0.25;
  const KnotVector knots = KnotVector::clamped_from_breakpoints(3, {0.0, 0.25, 0.5, 0.75, 1.0});
  Eigen::MatrixX3d points(knots.control_point_count(), 3);
  for (int i = 0; i < points.rows(); ++i) {
    const double greville = (knots[i + 1] + knots[i + 2] + knots[i + 3]) / 3.0;
    points.row(i) << 1e3 + 2.0 * greville, 1e3, 0.0;
  }
  const DNurbsCurve model(NurbsCurve(knots, points), material);
  const Eigen::VectorXd q0 = model.initial_coordinates();
  // E(q0) by quadrature: x_u = sum_i N_i' P_i rounds by eps sum_i |N_i'| |P_i| <= eps 1e3 2 p / h
  // (h = 0.25: ~5e-12 against |x_u| = 2), so |x_u|^2 and E(q0) = 3 to ~5e-12 relative.
  EXPECT_NEAR(model.potential_energy(q0), 0.5 * 1.5 * 4.0, 3.0 * 1e-11);
  Eigen::VectorXd d = Eigen::VectorXd::Zero(q0.size());
  for (int i = 0; i < points.rows(); ++i) {
    d[3 * i + 2] = 1e-3 * std::sin(0.7 * i + 0.3);
  }
  const double change = model.potential_energy(q0 + d) - model.potential_energy(q0);
  const double expected = 0.5 * d.dot(model.constant_matrices()->stiffness * d);
  // Both sides round terms of size |K| |d|^2 ~ 1e-6, and the difference rounds E ~ 3: a few
  // ulps of 3 (1e-14 absolute), against the change ~ 1e-6.
  EXPECT_NEAR(change, expected, 1e-14 * 3.0);
  EXPECT_GT(expected, 1e-7);  // the change is resolved, not rounding
}

// Relative errors of the first five eigenvalues of K phi = lambda M phi (scalar matrices,
// `clamped` control points fixed at each end) against the exact ones.
Eigen::VectorXd eigenvalue_errors(int degree, int spans, bool beam) {
  DNurbsCurveMaterial material;
  material.mass_density = 1.0;
  if (beam) {
    material.rigidity = 1.0;
  } else {
    material.tension = 1.0;
  }
  const DNurbsCurve model(straight_curve(degree, spans), material);
  const Eigen::MatrixXd M = dense(model.scalar_matrices()->mass);
  const Eigen::MatrixXd K = dense(model.scalar_matrices()->stiffness);
  const int clamped = beam ? 2 : 1;
  const auto free = static_cast<int>(M.rows()) - 2 * clamped;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eigen(
      K.block(clamped, clamped, free, free), M.block(clamped, clamped, free, free));
  const std::array<double, 5> beta_l = {4.730040745, 7.853204624, 10.99560784, 14.13716549,
                                        17.27875966};
  Eigen::VectorXd errors(5);
  for (int k = 0; k < 5; ++k) {
    const double exact = beam ? std::pow(beta_l[static_cast<size_t>(k)], 4)
                              : std::pow((k + 1) * std::numbers::pi, 2);
    errors[k] = std::abs(eigen.eigenvalues()[k] - exact) / exact;
  }
  return errors;
}

// Observed orders log2(e(h) / e(h/2)) of the five eigenvalues between `spans` and 2 spans.
Eigen::VectorXd observed_orders(int degree, int spans, bool beam) {
  const Eigen::VectorXd coarse = eigenvalue_errors(degree, spans, beam);
  const Eigen::VectorXd fine = eigenvalue_errors(degree, 2 * spans, beam);
  Eigen::VectorXd orders(5);
  for (int k = 0; k < 5; ++k) {
    orders[k] = std::log2(coarse[k] / fine[k]);
  }
  std::cout << (beam ? "beam" : "string") << " p=" << degree << " spans " << spans << "->"
            << 2 * spans << ": errors " << fine.transpose() << " orders " << orders.transpose()
            << "\n";
  return orders;
}

// Isogeometric eigenvalue errors of a 2m-th order operator with degree-p splines converge like
// h^(2(p + 1 - m)) (the energy-norm error squared): string m = 1 gives 2p, beam m = 2 gives
// 2(p - 1). The lower bound leaves 0.3 for the pre-asymptotic range of the fifth mode.
TEST(DNurbsCurveFrequencies, ClampedStringEigenvaluesConvergeAtOrderTwoP) {
  for (const int p : {2, 3}) {
    const int spans = p == 2 ? 32 : 16;  // errors stay far above round-off (>1e-11)
    const Eigen::VectorXd orders = observed_orders(p, spans, false);
    for (int k = 0; k < 5; ++k) {
      EXPECT_GE(orders[k], 2.0 * p - 0.3) << "degree " << p << " mode " << k + 1;
    }
    EXPECT_LT(eigenvalue_errors(p, 2 * spans, false)[0], 1e-6);
  }
}

TEST(DNurbsCurveFrequencies, ClampedBeamEigenvaluesConvergeAtOrderTwoPMinusTwo) {
  for (const int p : {2, 3}) {
    const int spans = p == 2 ? 32 : 16;
    const Eigen::VectorXd orders = observed_orders(p, spans, true);
    for (int k = 0; k < 5; ++k) {
      EXPECT_GE(orders[k], 2.0 * (p - 1) - 0.3) << "degree " << p << " mode " << k + 1;
    }
  }
}

TEST(DNurbsCurveValidation, NanDensityIsRejectedWithItsValue) {
  DNurbsCurveMaterial material;
  material.mass_density = std::numeric_limits<double>::quiet_NaN();
  try {
    DNurbsCurve model(straight_curve(2, 3), material);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("mass density is nan"), std::string::npos)
        << error.what();
  }
}

TEST(DNurbsCurveValidation, NegativeStiffnessIsRejectedWithItsValue) {
  DNurbsCurveMaterial material;
  material.rigidity = MaterialFunction([](const Eigen::Vector2d& u) { return u.x() - 0.5; });
  try {
    DNurbsCurve model(straight_curve(3, 3), material);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("rigidity w2 is negative"), std::string::npos)
        << error.what();
  }
  material.rigidity = 0.0;
  material.tension = -1.0;
  EXPECT_THROW(DNurbsCurve(straight_curve(3, 3), material), Error);
}

TEST(DNurbsCurveValidation, FreeWeightBelowMinimumIsRejected) {
  KnotVector knots = KnotVector::clamped_uniform(2, 4);
  Eigen::VectorXd weights(4);
  weights << 1.0, 1e-4, 1.0, 1.0;
  DNurbsSettings settings;
  settings.weight_mode = WeightMode::kFree;
  try {
    DNurbsCurve model(NurbsCurve(knots, Eigen::MatrixX3d::Random(4, 3), weights), {}, settings);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("free weight 1 is 1e-04"), std::string::npos)
        << error.what();
  }
  settings.minimum_weight = -1.0;
  EXPECT_THROW(DNurbsCurve(straight_curve(2, 3), {}, settings), Error);
  settings.minimum_weight = 1e-3;
  settings.quadrature_points = 99;
  EXPECT_THROW(DNurbsCurve(straight_curve(2, 3), {}, settings), Error);
}

TEST(DNurbsCurveValidation, FixedIndexOutOfRangeIsRejectedWithItsValue) {
  DNurbsCurve model(straight_curve(2, 3));
  try {
    model.fix_control_point(5);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("control point index 5"), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(model.fix_coordinate(-1), Error);
  EXPECT_THROW(model.fix_coordinate(15), Error);
  model.fix_control_point(4);
  EXPECT_EQ(model.fixed_coordinates(), (std::vector<int>{12, 13, 14}));
}

TEST(DNurbsCurveModel, PositionAndJacobianMatchTheCurve) {
  const NurbsCurve curve(KnotVector::clamped_uniform(3, 6), Eigen::MatrixX3d::Random(6, 3),
                         (Eigen::VectorXd(6) << 1.0, 0.6, 1.4, 2.0, 0.9, 1.0).finished());
  for (const WeightMode mode : {WeightMode::kFixed, WeightMode::kFree}) {
    DNurbsSettings settings;
    settings.weight_mode = mode;
    const DNurbsCurve model(curve, {}, settings);
    const Eigen::VectorXd q = model.initial_coordinates();
    for (const double u : {0.0, 0.13, 0.5, 0.77, 1.0}) {
      const Eigen::Vector2d parameter(u, 0.0);
      // Both evaluate the same rational sums; round-off only.
      EXPECT_LT((model.position(q, parameter) - curve.point(u)).norm(), 1e-14);
      // x is homogeneous: x = L q (degree 1 in P, 0 in w).
      EXPECT_LT((model.position_jacobian(q, parameter) * q - curve.point(u)).norm(), 1e-14);
    }
  }
}

}  // namespace
}  // namespace dnurbs
