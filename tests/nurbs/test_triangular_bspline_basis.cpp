// Tests of nurbs/triangular_bspline_basis.h: the DMS B-splines form a non-negative partition of
// unity, reproduce every polynomial of degree <= n through its blossom, are C^(n-1) across
// interior edges and knot segments (one-sided derivatives), and their derivatives match finite
// differences.

#include "dnurbs/nurbs/triangular_bspline_basis.h"

#include <random>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/triangular_polynomial_cells.h"
#include "triangular_test_helpers.h"

namespace dnurbs {
namespace {

// Sample points of a domain: random points in its bounding box that lie in it, the midpoints
// and thirds of every edge and every vertex.
std::vector<Eigen::Vector2d> sample_points(const Triangulation& triangulation, int random_count) {
  std::vector<Eigen::Vector2d> points;
  std::mt19937 random(11);
  const Eigen::Vector2d lo = triangulation.vertices().colwise().minCoeff().transpose();
  const Eigen::Vector2d hi = triangulation.vertices().colwise().maxCoeff().transpose();
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  while (static_cast<int>(points.size()) < random_count) {
    const Eigen::Vector2d u =
        lo + (hi - lo).cwiseProduct(Eigen::Vector2d(unit(random), unit(random)));
    if (triangulation.locate(u) >= 0) {
      points.push_back(u);
    }
  }
  for (int t = 0; t < triangulation.triangle_count(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector2d a = triangulation.corner(t, c);
      const Eigen::Vector2d b = triangulation.corner(t, (c + 1) % 3);
      points.push_back(a);
      points.push_back(0.5 * (a + b));
      points.push_back(a + (b - a) / 3.0);
    }
  }
  return points;
}

TEST(TriangularBSplineBasis, IsANonNegativePartitionOfUnityOnEveryTestDomain) {
  for (const auto& [name, triangulation] : test::triangular_test_domains()) {
    for (int n = 1; n <= 4; ++n) {
      const TriangularBSplineBasis basis(triangulation, standard_knot_clouds(triangulation, n));
      TriangularBasisValues values;
      double sum_error = 0.0;
      double minimum = 0.0;
      double derivative_sum = 0.0;
      for (const auto& u : sample_points(triangulation, 300)) {
        basis.evaluate(u, 2, values);
        const Eigen::Matrix<double, 6, 1> sum = values.value.rowwise().sum();
        sum_error = std::max(sum_error, std::abs(sum[0] - 1.0));
        minimum = std::min(minimum, values.value.row(0).minCoeff());
        // Derivatives of the sum vanish; relative to the derivatives' size.
        const double scale = values.value.bottomRows<5>().cwiseAbs().maxCoeff();
        derivative_sum = std::max(derivative_sum, sum.tail<5>().cwiseAbs().maxCoeff() / scale);
      }
      // Round-off of the recurrence (barycentric coordinates from differences, ~1e-16 each).
      EXPECT_LT(sum_error, 1e-14) << name << " degree " << n;
      EXPECT_GT(minimum, -1e-14) << name << " degree " << n;
      EXPECT_LT(derivative_sum, 1e-12) << name << " degree " << n;
    }
  }
}

TEST(TriangularBSplineBasis, PartitionOfUnityHoldsAtTheHighestSupportedDegree) {
  const Triangulation square =
      rectangle_triangulation(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), 2, 2);
  for (int n = 5; n <= kMaxTriangularDegree; ++n) {
    const TriangularBSplineBasis basis(square, standard_knot_clouds(square, n));
    TriangularBasisValues values;
    double sum_error = 0.0;
    for (const auto& u : sample_points(square, 100)) {
      basis.evaluate(u, 0, values);
      sum_error = std::max(sum_error, std::abs(values.value.row(0).sum() - 1.0));
      EXPECT_GT(values.value.row(0).minCoeff(), -1e-14);
    }
    EXPECT_LT(sum_error, 1e-14) << "degree " << n;
  }
}

TEST(TriangularBSplineBasis, ReproducesEveryPolynomialOfDegreeAtMostN) {
  // Dahmen, Micchelli & Seidel 1992: F = sum_I sum_beta f(blossom arguments) N_beta^I.
  for (const auto& [name, triangulation] : test::triangular_test_domains()) {
    for (int n = 1; n <= 4; ++n) {
      const TriangularBSplineBasis basis(triangulation, standard_knot_clouds(triangulation, n));
      std::vector<Eigen::MatrixX2d> arguments;
      arguments.reserve(static_cast<size_t>(basis.function_count()));
      for (int f = 0; f < basis.function_count(); ++f) {
        arguments.push_back(basis.blossom_arguments(f));
      }
      TriangularBasisValues values;
      double value_error = 0.0;
      double derivative_error = 0.0;
      for (const auto& u : sample_points(triangulation, 100)) {
        basis.evaluate(u, 2, values);
        const double derivative_scale = values.value.bottomRows<5>().cwiseAbs().maxCoeff();
        for (int a = 0; a <= n; ++a) {
          for (int b = 0; a + b <= n; ++b) {
            Eigen::Matrix<double, 6, 1> sum = Eigen::Matrix<double, 6, 1>::Zero();
            double coefficient_size = 1.0;
            for (int k = 0; k < values.count; ++k) {
              const auto& knots =
                  arguments[static_cast<size_t>(values.function[static_cast<size_t>(k)])];
              const double coefficient = test::monomial_blossom(a, b, knots);
              coefficient_size = std::max(coefficient_size, std::abs(coefficient));
              sum += coefficient * values.value.col(k);
            }
            // The monomial u^a v^b and its derivatives.
            auto power = [](double x, int e) { return e < 0 ? 0.0 : std::pow(x, e); };
            const double x = u.x();
            const double y = u.y();
            Eigen::Matrix<double, 6, 1> exact;
            exact << power(x, a) * power(y, b), a * power(x, a - 1) * power(y, b),
                b * power(x, a) * power(y, b - 1), a * (a - 1) * power(x, a - 2) * power(y, b),
                a * b * power(x, a - 1) * power(y, b - 1),
                b * (b - 1) * power(x, a) * power(y, b - 2);
            value_error =
                std::max(value_error, std::abs(sum[0] - exact[0]) / (1.0 + std::abs(exact[0])));
            derivative_error =
                std::max(derivative_error, (sum - exact).tail<5>().cwiseAbs().maxCoeff() /
                                               (coefficient_size * derivative_scale));
          }
        }
      }
      // Values: round-off of sums of ~50 terms of size <= 1 (domains within [0, 3]^2).
      EXPECT_LT(value_error, 1e-12) << name << " degree " << n;
      // Derivatives: round-off relative to the coefficients times the B-splines' own
      // derivatives, which reach 1 / (cloud radius)^2 near knot segments.
      EXPECT_LT(derivative_error, 1e-13) << name << " degree " << n;
    }
  }
}

// Largest difference of the derivatives of order <= order between the two one-sided limits at
// u, relative to their size, over all B-splines.
double one_sided_jump(const TriangularBSplineBasis& basis, int t, const Eigen::Vector2d& u,
                      const Eigen::Vector2d& normal, int order_low, int order_high) {
  TriangularBasisValues plus;
  TriangularBasisValues minus;
  basis.evaluate_in_triangle(t, u, normal, 2, plus);
  basis.evaluate_in_triangle(t, u, -normal, 2, minus);
  const int first = order_low == 0 ? 0 : (order_low == 1 ? 1 : 3);
  const int last = order_high == 0 ? 1 : (order_high == 1 ? 3 : 6);
  const double scale = 1.0 + plus.value.middleRows(first, last - first).cwiseAbs().maxCoeff();
  return (plus.value - minus.value).middleRows(first, last - first).cwiseAbs().maxCoeff() / scale;
}

TEST(TriangularBSplineBasis, IsCnMinusOneAcrossInteriorEdgesAndKnotSegments) {
  const Triangulation triangulation = test::triangular_test_domains()[3].second;  // perturbed
  for (int n = 1; n <= 4; ++n) {
    const TriangularBSplineBasis basis(triangulation, standard_knot_clouds(triangulation, n));
    const int smooth = std::min(n - 1, 2);  // highest order that must be continuous (and computed)
    double continuous = 0.0;
    double jump = 0.0;
    for (int t = 0; t < triangulation.triangle_count(); ++t) {
      // Interior domain edges (knot lines t_{i,0} t_{j,0}) and knot segments inside t.
      std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> lines;
      for (int e = 0; e < 3; ++e) {
        if (triangulation.neighbor(t, e) >= 0) {
          lines.emplace_back(triangulation.corner(t, (e + 1) % 3),
                             triangulation.corner(t, (e + 2) % 3));
        }
      }
      const Eigen::MatrixX4d segments = knot_segments_in_triangle(basis, t);
      for (Eigen::Index k = 0; k < segments.rows(); ++k) {
        lines.emplace_back(segments.row(k).head<2>().transpose(),
                           segments.row(k).tail<2>().transpose());
      }
      for (const auto& [p, q] : lines) {
        const Eigen::Vector2d normal = Eigen::Vector2d(q.y() - p.y(), p.x() - q.x()).normalized();
        for (const double s : {0.31, 0.5, 0.77}) {
          const Eigen::Vector2d u = p + s * (q - p);
          continuous = std::max(continuous, one_sided_jump(basis, t, u, normal, 0, smooth));
          if (n <= 2) {
            jump = std::max(jump, one_sided_jump(basis, t, u, normal, n, n));
          }
        }
      }
    }
    // Orders <= n - 1 agree to round-off (values ~1, second derivatives ~1 / r^2).
    EXPECT_LT(continuous, 1e-10) << "degree " << n;
    if (n <= 2) {
      // The n-th derivatives jump (so the comparison can fail).
      EXPECT_GT(jump, 1e-2) << "degree " << n;
    }
  }
}

TEST(TriangularBSplineBasis, DerivativesMatchCentralDifferences) {
  const Triangulation triangulation = l_shape_triangulation(1);
  for (int n = 1; n <= 4; ++n) {
    const TriangularBSplineBasis basis(triangulation, standard_knot_clouds(triangulation, n));
    TriangularBasisValues values;
    TriangularBasisValues shifted_plus;
    TriangularBasisValues shifted_minus;
    const double h = 1e-6;
    double worst = 0.0;
    for (const auto& u : sample_points(triangulation, 60)) {
      const int t = triangulation.locate(u);
      if (triangulation.barycentric(t, u).minCoeff() < 0.05) {
        continue;  // edges and vertices are knot lines: differences straddle them
      }
      basis.evaluate_in_triangle(t, u, 2, values);
      for (int direction = 0; direction < 2; ++direction) {
        const Eigen::Vector2d step = h * Eigen::Vector2d::Unit(direction);
        basis.evaluate_in_triangle(t, u + step, 2, shifted_plus);
        basis.evaluate_in_triangle(t, u - step, 2, shifted_minus);
        const Eigen::Matrix<double, 6, Eigen::Dynamic> difference =
            (shifted_plus.value - shifted_minus.value) / (2 * h);
        // d/du of (N, N_u, N_v) is (N_u, N_uu, N_uv); d/dv is (N_v, N_uv, N_vv).
        const std::array<int, 3> target =
            direction == 0 ? std::array<int, 3>{1, 3, 4} : std::array<int, 3>{2, 4, 5};
        for (int r = 0; r < 3; ++r) {
          const double scale =
              1.0 + values.value.row(target[static_cast<size_t>(r)]).cwiseAbs().maxCoeff();
          worst =
              std::max(worst, (difference.row(r) - values.value.row(target[static_cast<size_t>(r)]))
                                      .cwiseAbs()
                                      .maxCoeff() /
                                  scale);
        }
      }
    }
    // Truncation h^2 |D^3 N| and rounding 1e-16 |N| / h, relative: ~1e-9; a point within h of
    // a knot segment would show an O(1) difference.
    EXPECT_LT(worst, 1e-6) << "degree " << n;
  }
}

TEST(TriangularBSplineBasis, SupportsAndNumberingFollowTheKnotSets) {
  const Triangulation square =
      rectangle_triangulation(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), 2, 2);
  const TriangularBSplineBasis basis(square, standard_knot_clouds(square, 3));
  EXPECT_EQ(basis.functions_per_triangle(), 10);
  EXPECT_EQ(basis.function_count(), 80);
  EXPECT_EQ(basis.multi_index(0), (std::array<int, 3>{3, 0, 0}));
  EXPECT_EQ(basis.local_index({1, 1, 1}), 4);  // after (3,0,0) (2,1,0) (2,0,1) (1,2,0)
  EXPECT_THROW(basis.local_index({1, 1, 0}), Error);
  for (int f = 0; f < basis.function_count(); ++f) {
    EXPECT_GT(basis.normalization(f), 0.0);
    EXPECT_EQ(basis.knot_set(f).rows(), 6);
    EXPECT_EQ(basis.blossom_arguments(f).rows(), 3);
  }
  // A B-spline vanishes outside the bounding box of its knot set.
  TriangularBasisValues values;
  for (const auto& u : sample_points(square, 100)) {
    basis.evaluate(u, 0, values);
    for (int k = 0; k < values.count; ++k) {
      const Eigen::MatrixX2d knots = basis.knot_set(values.function[static_cast<size_t>(k)]);
      const bool in_box =
          (u.transpose().array() >= knots.colwise().minCoeff().array() - 1e-12).all() &&
          (u.transpose().array() <= knots.colwise().maxCoeff().array() + 1e-12).all();
      if (!in_box) {
        EXPECT_EQ(values.value(0, k), 0.0);
      }
    }
  }
  EXPECT_THROW(basis.evaluate(Eigen::Vector2d(1.5, 0.5), 0, values), Error);
  EXPECT_THROW(basis.evaluate(Eigen::Vector2d(0.5, 0.5), 3, values), Error);
  EXPECT_THROW(basis.evaluate_in_triangle(8, Eigen::Vector2d(0.5, 0.5), 0, values), Error);
}

}  // namespace
}  // namespace dnurbs
