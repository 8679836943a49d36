// Tests of nurbs/triangular_nurbs_surface.h: the rational form (flat and affine maps
// reproduced, invariance under a common weight factor), its parametric derivatives and its
// Jacobian with respect to control points and weights, all against finite differences.

#include "dnurbs/nurbs/triangular_nurbs_surface.h"

#include <random>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "triangular_test_helpers.h"

namespace dnurbs {
namespace {

std::shared_ptr<const TriangularBSplineBasis> l_shape_basis(int n) {
  const Triangulation triangulation = l_shape_triangulation(1);
  return std::make_shared<const TriangularBSplineBasis>(triangulation,
                                                        standard_knot_clouds(triangulation, n));
}

// A curved rational surface: the flat control net lifted by a smooth height, random weights.
TriangularNurbsSurface curved_surface(const std::shared_ptr<const TriangularBSplineBasis>& basis,
                                      unsigned seed) {
  TriangularNurbsSurface flat = flat_triangular_surface(basis);
  Eigen::MatrixX3d points = flat.control_points();
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  Eigen::VectorXd weights(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    points(i, 2) = std::sin(points(i, 0)) * std::cos(1.3 * points(i, 1));
    weights[i] = weight(random);
  }
  return {basis, points, weights};
}

// Points away from edges and vertices (knot lines) of the L-shape's unit cells.
std::vector<Eigen::Vector2d> interior_points() {
  return {{0.3, 0.2}, {0.62, 0.81}, {1.4, 0.35}, {1.7, 0.7}, {0.25, 1.55}, {0.8, 1.3}};
}

TEST(TriangularNurbsSurface, FlatSurfaceIsTheIdentityAndWeightsScaleOut) {
  const auto basis = l_shape_basis(3);
  const TriangularNurbsSurface flat = flat_triangular_surface(basis);
  EXPECT_FALSE(flat.is_rational());
  for (const auto& u : interior_points()) {
    const auto d = flat.derivatives(u, 2);
    EXPECT_LT((d[0] - Eigen::Vector3d(u.x(), u.y(), 0.0)).norm(), 1e-14);
    EXPECT_LT((d[1] - Eigen::Vector3d::UnitX()).norm(), 1e-12);
    EXPECT_LT((d[2] - Eigen::Vector3d::UnitY()).norm(), 1e-12);
    EXPECT_LT(d[3].norm() + d[4].norm() + d[5].norm(),
              1e-10);  // second derivatives ~1/r^2 round-off
    EXPECT_LT((flat.unit_normal(u) - Eigen::Vector3d::UnitZ()).norm(), 1e-14);
  }
  // Multiplying every weight by one factor leaves a rational surface unchanged.
  const TriangularNurbsSurface curved = curved_surface(basis, 1);
  const TriangularNurbsSurface scaled(basis, curved.control_points(), 3.7 * curved.weights());
  EXPECT_TRUE(curved.is_rational());
  for (const auto& u : interior_points()) {
    const auto a = curved.derivatives(u, 2);
    const auto b = scaled.derivatives(u, 2);
    for (int q = 0; q < 6; ++q) {
      EXPECT_LT((a[static_cast<size_t>(q)] - b[static_cast<size_t>(q)]).norm(),
                1e-12 * (1.0 + a[static_cast<size_t>(q)].norm()));
    }
  }
}

TEST(TriangularNurbsSurface, RationalDerivativesMatchCentralDifferences) {
  for (int n = 2; n <= 3; ++n) {
    const TriangularNurbsSurface surface = curved_surface(l_shape_basis(n), 2);
    const double h = 1e-6;
    for (const auto& u : interior_points()) {
      const auto d = surface.derivatives(u, 2);
      const auto pu = surface.derivatives(u + Eigen::Vector2d(h, 0), 1);
      const auto mu = surface.derivatives(u - Eigen::Vector2d(h, 0), 1);
      const auto pv = surface.derivatives(u + Eigen::Vector2d(0, h), 1);
      const auto mv = surface.derivatives(u - Eigen::Vector2d(0, h), 1);
      // Truncation h^2 |x'''| and rounding 1e-16 / h, relative to the derivatives (~1..100).
      const double tolerance = 1e-7 * (1.0 + d[3].norm() + d[4].norm() + d[5].norm());
      EXPECT_LT(((pu[0] - mu[0]) / (2 * h) - d[1]).norm(), tolerance);
      EXPECT_LT(((pv[0] - mv[0]) / (2 * h) - d[2]).norm(), tolerance);
      EXPECT_LT(((pu[1] - mu[1]) / (2 * h) - d[3]).norm(), tolerance);
      EXPECT_LT(((pv[1] - mv[1]) / (2 * h) - d[4]).norm(), tolerance);
      EXPECT_LT(((pu[2] - mu[2]) / (2 * h) - d[4]).norm(), tolerance);
      EXPECT_LT(((pv[2] - mv[2]) / (2 * h) - d[5]).norm(), tolerance);
    }
  }
}

TEST(TriangularNurbsSurface, JacobianWithRespectToControlPointsAndWeightsMatchesDifferences) {
  const auto basis = l_shape_basis(2);
  const TriangularNurbsSurface surface = curved_surface(basis, 3);
  const double h = 1e-7;
  TriangularBasisValues values;
  TriangularRationalJacobian jacobian;
  for (const auto& u : interior_points()) {
    basis->evaluate(u, 2, values);
    triangular_rational_jacobian(values, 2, surface.control_net(), true, jacobian);
    for (int a = 0; a < values.count; a += 3) {
      const int f = values.function[static_cast<size_t>(a)];
      // d x^alpha / d P_a = R(alpha, a) I_3 (the surface is linear in P: exact differences).
      Eigen::MatrixX3d moved = surface.control_points();
      moved(f, 2) += 1.0;
      const auto shifted =
          TriangularNurbsSurface(basis, moved, surface.weights()).derivatives(u, 2);
      const auto base = surface.derivatives(u, 2);
      for (int alpha = 0; alpha < 6; ++alpha) {
        const auto k = static_cast<size_t>(alpha);
        EXPECT_NEAR(shifted[k].z() - base[k].z(), jacobian.rational(alpha, a),
                    1e-10 * (1.0 + std::abs(jacobian.rational(alpha, a))));
        EXPECT_LT((jacobian.point[k] - base[k]).norm(), 1e-12 * (1.0 + base[k].norm()));
      }
      // d x^alpha / d w_a = E^alpha_a by central differences in the weight.
      Eigen::VectorXd plus = surface.weights();
      Eigen::VectorXd minus = surface.weights();
      plus[f] += h;
      minus[f] -= h;
      const auto xp =
          TriangularNurbsSurface(basis, surface.control_points(), plus).derivatives(u, 2);
      const auto xm =
          TriangularNurbsSurface(basis, surface.control_points(), minus).derivatives(u, 2);
      for (int alpha = 0; alpha < 6; ++alpha) {
        const auto k = static_cast<size_t>(alpha);
        const Eigen::Vector3d difference = (xp[k] - xm[k]) / (2 * h);
        // Truncation h^2 and rounding 1e-16 |x^alpha| / h with |x^alpha| up to ~100.
        EXPECT_LT((difference - jacobian.weight_column[k].col(a)).norm(),
                  1e-6 * (1.0 + base[k].norm()))
            << "alpha " << alpha;
      }
    }
  }
}

TEST(TriangularNurbsSurface, BadInputThrowsErrorNamingTheValue) {
  const auto basis = l_shape_basis(1);
  const Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(basis->function_count(), 3);
  EXPECT_THROW(TriangularNurbsSurface(nullptr, points), Error);
  EXPECT_THROW(TriangularNurbsSurface(basis, Eigen::MatrixX3d::Zero(3, 3)), Error);
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(basis->function_count());
  weights[4] = 0.0;
  EXPECT_THROW(TriangularNurbsSurface(basis, points, weights), Error);
  weights[4] = 1.0;
  EXPECT_THROW(TriangularNurbsSurface(basis, points, weights.head(3)), Error);
  Eigen::MatrixX3d bad = points;
  bad(2, 1) = std::nan("");
  EXPECT_THROW(TriangularNurbsSurface(basis, bad), Error);
  const TriangularNurbsSurface zero(basis, points);
  EXPECT_THROW(zero.unit_normal(Eigen::Vector2d(0.3, 0.2)), Error);  // all tangents vanish
  EXPECT_THROW(zero.point(Eigen::Vector2d(1.5, 1.5)), Error);        // in the notch
}

}  // namespace
}  // namespace dnurbs
