// Tests of nurbs/triangular_polynomial_cells.h: the cells tile their triangle, no knot segment
// crosses a cell, and every B-spline is one polynomial of degree n on every cell.

#include "dnurbs/nurbs/triangular_polynomial_cells.h"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/dunavant_rules.h"
#include "dnurbs/nurbs/simplex_spline.h"
#include "triangular_test_helpers.h"

namespace dnurbs {
namespace {

double area_of(const ConvexPolygon& polygon) {
  double twice = 0.0;
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d& a = polygon[k];
    const Eigen::Vector2d& b = polygon[(k + 1) % polygon.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

TEST(PolynomialCells, TileTheTriangleAndNoKnotSegmentCrossesThem) {
  const Triangulation triangulation = test::triangular_test_domains()[3].second;  // perturbed
  for (int n = 1; n <= 3; ++n) {
    const TriangularBSplineBasis basis(triangulation, standard_knot_clouds(triangulation, n));
    int segment_count = 0;
    for (int t = 0; t < triangulation.triangle_count(); ++t) {
      const std::vector<ConvexPolygon> cells = polynomial_cells(basis, t);
      const Eigen::MatrixX4d segments = knot_segments_in_triangle(basis, t);
      segment_count += static_cast<int>(segments.rows());
      double total = 0.0;
      for (const ConvexPolygon& cell : cells) {
        ASSERT_GE(cell.size(), 3U);
        total += area_of(cell);
        // Convex and counter-clockwise.
        for (size_t k = 0; k < cell.size(); ++k) {
          EXPECT_GE(
              signed_double_area(cell[k], cell[(k + 1) % cell.size()], cell[(k + 2) % cell.size()]),
              -1e-15);
        }
        // No knot segment passes through the cell's interior: the part of the segment at
        // least 1e-9 inside every edge of the cell is empty.
        for (Eigen::Index k = 0; k < segments.rows(); ++k) {
          const Eigen::Vector2d p = segments.row(k).head<2>();
          const Eigen::Vector2d q = segments.row(k).tail<2>();
          double enter = 0.0;
          double leave = 1.0;
          for (size_t e = 0; e < cell.size(); ++e) {
            const Eigen::Vector2d& e0 = cell[e];
            const Eigen::Vector2d& e1 = cell[(e + 1) % cell.size()];
            const double length = (e1 - e0).norm();
            const double f0 = signed_double_area(e0, e1, p) / length - 1e-9;
            const double f1 = signed_double_area(e0, e1, q) / length - 1e-9;
            if (f0 < 0.0 && f1 < 0.0) {
              leave = -1.0;
            } else if (f0 < 0.0) {
              enter = std::max(enter, f0 / (f0 - f1));
            } else if (f1 < 0.0) {
              leave = std::min(leave, f0 / (f0 - f1));
            }
          }
          EXPECT_LE((leave - enter) * (q - p).norm(), 1e-9) << "triangle " << t << " segment " << k;
        }
      }
      // The cells tile the triangle: areas add up to round-off.
      EXPECT_NEAR(total, triangulation.area(t), 1e-14) << "triangle " << t;
    }
    EXPECT_GT(segment_count, triangulation.triangle_count());  // the test sees segments
  }
  EXPECT_THROW(
      knot_segments_in_triangle(
          TriangularBSplineBasis(triangulation, standard_knot_clouds(triangulation, 1)), -1),
      Error);
}

TEST(PolynomialCells, EveryBSplineIsOnePolynomialOfDegreeNOnEveryCell) {
  const Triangulation triangulation = l_shape_triangulation(1);
  for (int n = 1; n <= 3; ++n) {
    const TriangularBSplineBasis basis(triangulation, standard_knot_clouds(triangulation, n));
    const TriangleRule& rule = dunavant_rule(2 * n + 2);  // more points than coefficients
    const int terms = (n + 1) * (n + 2) / 2;
    double worst = 0.0;
    TriangularBasisValues values;
    for (int t = 0; t < triangulation.triangle_count(); t += 2) {
      for (const ConvexPolygon& cell : polynomial_cells(basis, t)) {
        if (area_of(cell) < 1e-6 * triangulation.area(t)) {
          continue;  // fitting on slivers is ill-conditioned; their pieces are tested by others
        }
        // Points of the rule on the cell's first fan triangle, fitted by a polynomial of degree
        // n in local coordinates: the residual is round-off only if the B-splines are one
        // polynomial there.
        const Eigen::Vector2d a = cell[0];
        const Eigen::Vector2d b = cell[1];
        const Eigen::Vector2d c = cell[2];
        Eigen::MatrixXd design(rule.point_count(), terms);
        Eigen::MatrixXd samples;
        for (int g = 0; g < rule.point_count(); ++g) {
          const Eigen::Vector2d u =
              rule.barycentric(g, 0) * a + rule.barycentric(g, 1) * b + rule.barycentric(g, 2) * c;
          basis.evaluate_in_triangle(t, u, 0, values);
          if (g == 0) {
            samples.resize(rule.point_count(), values.count);
          }
          samples.row(g) = values.value.row(0);
          int column = 0;
          for (int i = 0; i <= n; ++i) {
            for (int j = 0; i + j <= n; ++j) {
              design(g, column++) =
                  std::pow(rule.barycentric(g, 1), i) * std::pow(rule.barycentric(g, 2), j);
            }
          }
        }
        const Eigen::MatrixXd fit = design.colPivHouseholderQr().solve(samples);
        worst = std::max(worst, (design * fit - samples).cwiseAbs().maxCoeff());
      }
    }
    // Round-off of the values (<= 1) and of a small least-squares fit.
    EXPECT_LT(worst, 1e-11) << "degree " << n;
  }
}

}  // namespace
}  // namespace dnurbs
