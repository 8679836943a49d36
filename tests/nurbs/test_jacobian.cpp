#include "dnurbs/nurbs/jacobian.h"

#include <random>

#include <gtest/gtest.h>

#include "dnurbs/nurbs/primitive_shapes.h"
#include "sample_shapes.h"

namespace dnurbs {
namespace {

// Coordinates q of a shape in the layout of WeightMode.
template <typename Shape>
Eigen::VectorXd coordinates(const Shape& shape, WeightMode mode) {
  const int stride = coordinates_per_control_point(mode);
  Eigen::VectorXd q(stride * shape.control_point_count());
  for (int i = 0; i < shape.control_point_count(); ++i) {
    q.segment<3>(stride * i) = shape.control_points().row(i).transpose();
    if (mode == WeightMode::kFree) {
      q[stride * i + 3] = shape.weights()[i];
    }
  }
  return q;
}

template <typename Shape>
Shape with_coordinates(Shape shape, const Eigen::VectorXd& q, WeightMode mode) {
  const int stride = coordinates_per_control_point(mode);
  Eigen::MatrixX3d points(shape.control_point_count(), 3);
  Eigen::VectorXd weights = shape.weights();
  for (int i = 0; i < shape.control_point_count(); ++i) {
    points.row(i) = q.segment<3>(stride * i).transpose();
    if (mode == WeightMode::kFree) {
      weights[i] = q[stride * i + 3];
    }
  }
  shape.set_control_points(points);
  shape.set_weights(weights);
  return shape;
}

// Central difference of a parametric quantity with respect to every coordinate; the result is
// a dense 3 by #coordinates matrix to compare with the analytic Jacobian, zeros included.
template <typename Shape, typename Quantity>
Eigen::MatrixXd difference_jacobian(const Shape& shape, WeightMode mode, Quantity quantity) {
  const Eigen::VectorXd q = coordinates(shape, mode);
  Eigen::MatrixXd result(3, q.size());
  const double h = 1e-6;
  for (Eigen::Index c = 0; c < q.size(); ++c) {
    Eigen::VectorXd plus = q;
    Eigen::VectorXd minus = q;
    plus[c] += h;
    minus[c] -= h;
    result.col(c) = (quantity(with_coordinates(shape, plus, mode)) -
                     quantity(with_coordinates(shape, minus, mode))) /
                    (2 * h);
  }
  return result;
}

void expect_curve_jacobians_match(const NurbsCurve& curve) {
  for (WeightMode mode : {WeightMode::kFixed, WeightMode::kFree}) {
    for (double u : {0.0, 0.2, 0.33, 0.45, 0.8, 1.0}) {
      CurveJacobian jacobian;
      curve_jacobian(curve, u, 2, mode, jacobian);
      for (int order = 0; order <= 2; ++order) {
        const Eigen::MatrixXd analytic = Eigen::MatrixXd(to_sparse_matrix(
            jacobian, static_cast<CurveQuantity>(order), mode, curve.control_point_count()));
        const Eigen::MatrixXd numeric = difference_jacobian(curve, mode, [&](const NurbsCurve& c) {
          return Eigen::Vector3d(c.derivatives(u, 2).row(order).transpose());
        });
        // Position columns are exact linear functions of q (difference exact up to rounding
        // eps |C^(d)|/h); weight columns have truncation h^2 |d^3 C / dw^3| ~ 1e-12 * 1e3.
        EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-6 * (1.0 + analytic.norm()))
            << "order " << order << " u " << u << " free " << (mode == WeightMode::kFree);
        EXPECT_LT(
            (jacobian.point_derivatives.row(order) - curve.derivatives(u, 2).row(order)).norm(),
            1e-12 * (1.0 + analytic.norm()));
      }
    }
  }
}

TEST(CurveJacobian, MatchesFiniteDifferencesForFixedAndFreeWeights) {
  expect_curve_jacobians_match(testing::random_rational_curve(3, 41));
  expect_curve_jacobians_match(testing::random_rational_curve(2, 42));
  expect_curve_jacobians_match(full_circle(1.0));
}

TEST(CurveJacobian, PeriodicCurveMapsWrappedColumnsToDistinctControlPoints) {
  Eigen::MatrixX3d points(5, 3);
  points << 1, 0, 0, 0.3, 1, 0.2, -1, 0.4, 0, -0.5, -1, 0.5, 0.6, -0.8, 0;
  Eigen::VectorXd weights(5);
  weights << 1, 2, 0.5, 1, 1.5;
  const NurbsCurve closed(KnotVector::periodic(3, {0.0, 0.2, 0.3, 0.6, 0.8, 1.0}), points, weights);
  expect_curve_jacobians_match(closed);
}

TEST(CurveJacobian, OnlyActiveControlPointsAppear) {
  const NurbsCurve curve = testing::random_rational_curve(3, 43);
  CurveJacobian jacobian;
  curve_jacobian(curve, 0.5, 2, WeightMode::kFree, jacobian);
  const Eigen::SparseMatrix<double> sparse = to_sparse_matrix(
      jacobian, CurveQuantity::kPoint, WeightMode::kFree, curve.control_point_count());
  EXPECT_EQ(jacobian.active_count, 4);
  EXPECT_EQ(sparse.nonZeros(), 4 * 6);  // 3 diagonal entries plus a weight column of 3 each
  // The rational basis is a partition of unity.
  EXPECT_NEAR(jacobian.basis.row(0).head(4).sum(), 1.0, 1e-15);
}

void expect_surface_jacobians_match(const NurbsSurface& surface) {
  for (WeightMode mode : {WeightMode::kFixed, WeightMode::kFree}) {
    for (const auto& [u, v] :
         std::vector<std::pair<double, double>>{{0.0, 0.0}, {0.5, 0.3}, {0.37, 0.71}, {1.0, 0.9}}) {
      SurfaceJacobian jacobian;
      surface_jacobian(surface, u, v, 2, mode, jacobian);
      const std::array<std::pair<int, int>, 6> orders = {
          {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}}};
      for (int quantity = 0; quantity < 6; ++quantity) {
        const auto [k, l] = orders[static_cast<size_t>(quantity)];
        const Eigen::MatrixXd analytic = Eigen::MatrixXd(to_sparse_matrix(
            jacobian, static_cast<SurfaceQuantity>(quantity), mode, surface.control_point_count()));
        const Eigen::MatrixXd numeric = difference_jacobian(
            surface, mode,
            [&](const NurbsSurface& s) { return Eigen::Vector3d(s.derivatives(u, v, 2)(k, l)); });
        // As for curves: exact in the point columns, O(h^2) in the weight columns.
        EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-6 * (1.0 + analytic.norm()))
            << "S(" << k << "," << l << ") at (" << u << ", " << v << ")";
        EXPECT_LT((jacobian.point_derivatives[static_cast<size_t>(quantity)] -
                   surface.derivatives(u, v, 2)(k, l))
                      .norm(),
                  1e-12 * (1.0 + analytic.norm()));
      }
    }
  }
}

TEST(SurfaceJacobian, MatchesFiniteDifferencesForFixedAndFreeWeights) {
  expect_surface_jacobians_match(testing::random_rational_surface(2, 3, 51));
  expect_surface_jacobians_match(testing::random_rational_surface(3, 2, 52, true, false));
  expect_surface_jacobians_match(sphere(1.0));
}

}  // namespace
}  // namespace dnurbs

namespace dnurbs {
namespace {

// Jdot qd is the second derivative of x^(d)(q + t qd) at t = 0; compare with a central second
// difference (error h^2 |d^4 x / dt^4| / 12 plus rounding eps |x| / h^2 ~ 1e-8 for h = 1e-4).
TEST(JacobianRate, MatchesSecondDifferencesAlongTheVelocity) {
  const NurbsSurface surface = testing::random_rational_surface(3, 2, 71);
  const NurbsCurve curve = testing::random_rational_curve(3, 72);
  std::mt19937 generator(73);
  std::normal_distribution<double> normal(0.0, 1.0);
  const auto random_rates = [&](int count) {
    Eigen::MatrixX3d points(count, 3);
    Eigen::VectorXd weights(count);
    for (int i = 0; i < count; ++i) {
      points.row(i) << normal(generator), normal(generator), normal(generator);
      weights[i] = 0.3 * normal(generator);
    }
    return std::make_pair(points, weights);
  };
  const double h = 1e-4;
  const auto [surface_points, surface_weights] = random_rates(surface.control_point_count());
  const auto moved_surface = [&](double t) {
    NurbsSurface moved = surface;
    moved.set_control_points(surface.control_points() + t * surface_points);
    moved.set_weights(surface.weights() + t * surface_weights);
    return moved;
  };
  std::array<Eigen::Vector3d, 6> rates;
  surface_jacobian_rate(surface, 0.37, 0.61, 2, surface_points, surface_weights, rates);
  const std::array<std::pair<int, int>, 6> orders = {
      {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}}};
  for (int quantity = 0; quantity < 6; ++quantity) {
    const auto [k, l] = orders[static_cast<size_t>(quantity)];
    const auto value = [&](double t) { return moved_surface(t).derivatives(0.37, 0.61, 2)(k, l); };
    const Eigen::Vector3d expected = (value(h) - 2.0 * value(0.0) + value(-h)) / (h * h);
    EXPECT_LT((rates[static_cast<size_t>(quantity)] - expected).norm(),
              1e-5 * (1.0 + expected.norm()))
        << "quantity " << quantity;
  }
  const auto [curve_points, curve_weights] = random_rates(curve.control_point_count());
  CurveDerivatives curve_rates;
  curve_jacobian_rate(curve, 0.52, 2, curve_points, curve_weights, curve_rates);
  for (int order = 0; order <= 2; ++order) {
    const auto value = [&](double t) {
      NurbsCurve moved = curve;
      moved.set_control_points(curve.control_points() + t * curve_points);
      moved.set_weights(curve.weights() + t * curve_weights);
      return Eigen::Vector3d(moved.derivatives(0.52, 2).row(order).transpose());
    };
    const Eigen::Vector3d expected = (value(h) - 2.0 * value(0.0) + value(-h)) / (h * h);
    EXPECT_LT((curve_rates.row(order).transpose() - expected).norm(),
              1e-5 * (1.0 + expected.norm()))
        << "order " << order;
  }
  // Without weight rates the point is linear in the control points: Jdot qd = 0 exactly.
  surface_jacobian_rate(surface, 0.37, 0.61, 2, surface_points,
                        Eigen::VectorXd::Zero(surface.control_point_count()), rates);
  for (const auto& rate : rates) {
    EXPECT_EQ(rate.norm(), 0.0);
  }
}

}  // namespace
}  // namespace dnurbs
