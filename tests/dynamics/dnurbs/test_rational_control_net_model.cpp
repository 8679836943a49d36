// The weight regularization of free weights (rational_control_net_model.h, "Well-posed free
// weights"): the scale-aware default, the anchor force against finite differences of its energy,
// and its stiffness in K.

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/nurbs/knot_vector.h"

namespace dnurbs {
namespace {

// A bent cubic (7 control points) with tension and rigidity, every coordinate scaled by `size`.
DNurbsCurve bent_rod(double size, DNurbsSettings settings) {
  const KnotVector knots = KnotVector::clamped_uniform(3, 7);
  Eigen::MatrixX3d points(7, 3);
  for (int i = 0; i < 7; ++i) {
    points.row(i) << i / 6.0, 0.1 * std::sin(i), 0.2 * std::cos(1.3 * i);
  }
  DNurbsCurveMaterial material;
  material.tension = 1.0;
  material.rigidity = 0.1;
  settings.weight_mode = WeightMode::kFree;
  return DNurbsCurve(NurbsCurve(knots, size * points), material, settings);
}

// Mean of the weight diagonals of M and K at the initial state without regularization.
Eigen::Vector2d natural_weight_diagonals(double size) {
  DNurbsSettings exact;
  exact.weight_inertia = 0.0;
  exact.weight_stiffness = 0.0;
  const DNurbsCurve model = bent_rod(size, exact);
  ModelMatrices matrices;
  model.assemble_matrices(model.initial_coordinates(), matrices);
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (int i = 0; i < model.control_point_count(); ++i) {
    const int w = model.weight_offset(i);
    mean += Eigen::Vector2d(matrices.mass.coeff(w, w), matrices.stiffness.coeff(w, w));
  }
  return mean / model.control_point_count();
}

TEST(WeightRegularization, DefaultIsScaledFromTheShapesOwnWeightDiagonals) {
  const DNurbsCurve model = bent_rod(1.0, {});
  const Eigen::Vector2d natural = natural_weight_diagonals(1.0);
  // m_w = 10 mean M_ww, k_w = 2 mean K_ww (the same sums: equal up to rounding).
  EXPECT_NEAR(model.weight_inertia(), 10.0 * natural.x(), 1e-14 * natural.x());
  EXPECT_NEAR(model.weight_stiffness(), 2.0 * natural.y(), 1e-14 * natural.y());
  // Scale-aware: E_a = dx/dw_a grows with the shape, so m_w and k_w grow with its size squared.
  const DNurbsCurve doubled = bent_rod(2.0, {});
  EXPECT_NEAR(doubled.weight_inertia() / model.weight_inertia(), 4.0, 1e-12);
  EXPECT_NEAR(doubled.weight_stiffness() / model.weight_stiffness(), 4.0, 1e-12);
  // An explicit inertia alone switches the stiffness off (exact D-NURBS plus that inertia).
  DNurbsSettings explicit_inertia;
  explicit_inertia.weight_inertia = 0.5;
  const DNurbsCurve given = bent_rod(1.0, explicit_inertia);
  EXPECT_EQ(given.weight_inertia(), 0.5);
  EXPECT_EQ(given.weight_stiffness(), 0.0);
  DNurbsSettings negative;
  negative.weight_stiffness = -1.0;
  EXPECT_THROW(bent_rod(1.0, negative), Error);
}

TEST(WeightRegularization, AnchorForceIsMinusTheGradientOfItsEnergyAndItsStiffnessIsInK) {
  DNurbsSettings settings;
  settings.weight_inertia = 0.0;
  settings.weight_stiffness = 0.7;
  const DNurbsCurve anchored = bent_rod(1.0, settings);
  settings.weight_stiffness = 0.0;
  const DNurbsCurve plain = bent_rod(1.0, settings);
  Eigen::VectorXd q = anchored.initial_coordinates();
  for (int i = 0; i < anchored.control_point_count(); ++i) {
    q[anchored.weight_offset(i)] += 0.1 * std::sin(2.0 * i + 1.0);
  }
  // The anchor's part of E and f_int: (1/2) k_w |w - w_0|^2 and -k_w (w - w_0).
  auto anchor_energy = [&](const Eigen::VectorXd& x) {
    return anchored.potential_energy(x) - plain.potential_energy(x);
  };
  Eigen::VectorXd force = Eigen::VectorXd::Zero(q.size());
  Eigen::VectorXd plain_force = Eigen::VectorXd::Zero(q.size());
  anchored.add_internal_force(q, force);
  plain.add_internal_force(q, plain_force);
  force -= plain_force;
  const double h = 1e-6;
  for (int i = 0; i < anchored.control_point_count(); ++i) {
    const int w = anchored.weight_offset(i);
    Eigen::VectorXd plus = q;
    Eigen::VectorXd minus = q;
    plus[w] += h;
    minus[w] -= h;
    const double derivative = (anchor_energy(plus) - anchor_energy(minus)) / (2.0 * h);
    // Central differences of a quadratic are exact; rounding of energies of size 1 over 2h
    // leaves ~1e-16 / 1e-6 = 1e-10.
    EXPECT_NEAR(force[w], -derivative, 1e-9);
    EXPECT_NEAR(force[w], -0.7 * (q[w] - anchored.initial_coordinates()[w]), 1e-15);
  }
  // K differs by exactly k_w on every weight diagonal, nowhere else.
  ModelMatrices a;
  ModelMatrices b;
  anchored.assemble_matrices(q, a);
  plain.assemble_matrices(q, b);
  Eigen::MatrixXd difference = Eigen::MatrixXd(a.stiffness) - Eigen::MatrixXd(b.stiffness);
  for (int i = 0; i < anchored.control_point_count(); ++i) {
    const int w = anchored.weight_offset(i);
    EXPECT_NEAR(difference(w, w), 0.7, 1e-12);
    difference(w, w) = 0.0;
  }
  EXPECT_EQ(difference.norm(), 0.0);
}

}  // namespace
}  // namespace dnurbs
