// Tests of nurbs/simplex_spline.h: Micchelli's recurrence for bivariate simplex splines with
// derivatives, the half-open convention, and the normalization (integral 1 / ((m+1)(m+2))).

#include "dnurbs/nurbs/simplex_spline.h"

#include <random>

#include <gtest/gtest.h>

#include "../common/error_message.h"
#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/dunavant_rules.h"

namespace dnurbs {
namespace {

using testing::error_message;

// Eight knots in general position (no three collinear) spread over about [0, 2] x [0, 1.6].
Eigen::MatrixX2d eight_knots() {
  Eigen::MatrixX2d knots(8, 2);
  knots << 0.0, 0.1, 1.9, 0.0, 1.1, 1.6, 0.6, 0.45, 1.3, 0.5, 0.9, 1.0, 0.35, 1.1, 1.6, 1.2;
  return knots;
}

std::uint32_t first_knots(int count) {
  return (1U << static_cast<unsigned>(count)) - 1U;
}

Eigen::Matrix<double, 6, 1> evaluate_one(const SimplexSplineSet& set, const Eigen::Vector2d& u,
                                         int order) {
  Eigen::Matrix<double, 6, Eigen::Dynamic> result;
  set.evaluate(u, Eigen::Vector2d(0.8, 0.6), 1e-13, order, result);
  return result.col(0);
}

TEST(SimplexSplineDegreeZero, IsOneOverTheDeterminantOnItsHalfOpenTriangle) {
  Eigen::MatrixX2d knots(4, 2);
  knots << 0, 0, 2, 0, 2, 1, 0, 1;  // a 2 x 1 rectangle, split along the diagonal (0, 2)
  const SimplexSplineSet set(knots, {0b0111U, 0b1101U});
  Eigen::Matrix<double, 6, Eigen::Dynamic> result;
  set.evaluate(Eigen::Vector2d(1.5, 0.2), Eigen::Vector2d(1, 0), 1e-13, 0, result);
  EXPECT_DOUBLE_EQ(result(0, 0), 0.5);  // 1 / |det| = 1 / (2 * area 1)
  EXPECT_EQ(result(0, 1), 0.0);
  // Points on the diagonal, at the corners and on the outer edges, in several directions
  // (some along an edge, where d_perp decides): the two half-open triangles tile the
  // rectangle, so exactly one of them holds the point, or none where u + eps d + eps^2 d_perp
  // leaves the rectangle.
  const std::vector<Eigen::Vector2d> points = {{1.0, 0.5}, {0.0, 0.0}, {2.0, 1.0}, {1.0, 0.0}};
  const std::vector<Eigen::Vector2d> directions = {{1, 0}, {-1, 0}, {0, 1}, {0.3, -0.7}, {2, 1}};
  for (const auto& u : points) {
    for (const auto& d : directions) {
      set.evaluate(u, d, 1e-13, 0, result);
      const double total = result(0, 0) + result(0, 1);
      // u + eps d + eps^2 d_perp with d_perp = d turned by +90 degrees.
      const Eigen::Vector2d probe = u + 1e-6 * d + 1e-9 * Eigen::Vector2d(-d.y(), d.x());
      const bool inside = probe.x() > 0 && probe.x() < 2 && probe.y() > 0 && probe.y() < 1;
      EXPECT_EQ(total, inside ? 0.5 : 0.0) << u.transpose() << " d " << d.transpose();
    }
  }
  // A direction along the diagonal defers to its perpendicular.
  set.evaluate(Eigen::Vector2d(1.0, 0.5), Eigen::Vector2d(2, 1), 1e-13, 0, result);
  EXPECT_EQ(result(0, 1), 0.5);  // (-1, 2) points above the diagonal, into (0, 2, 3)
}

TEST(SimplexSplineHalfOpen, SideOfAnEdgeFlipsExactlyWithItsOrientation) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector2d p(coordinate(random), coordinate(random));
    const Eigen::Vector2d q(coordinate(random), coordinate(random));
    const double t = 0.5 * (coordinate(random) + 1.0);
    const Eigen::Vector2d on_line = p + t * (q - p);  // within round-off of the line
    const Eigen::Vector2d d(coordinate(random), coordinate(random));
    EXPECT_EQ(half_open_side(p, q, on_line, d, 1e-12), -half_open_side(q, p, on_line, d, 1e-12));
    const Eigen::Vector2d off(coordinate(random), coordinate(random));
    EXPECT_EQ(half_open_side(p, q, off, d, 1e-12), -half_open_side(q, p, off, d, 1e-12));
  }
}

TEST(SimplexSplineRecurrence, ValueDoesNotDependOnTheTripleChosen) {
  // Micchelli's recurrence holds for every affinely independent triple W; grouping the knots
  // differently changes the triples (and the graph) but not the spline.
  const Eigen::MatrixX2d knots = eight_knots();
  for (int count = 4; count <= 8; ++count) {
    const SimplexSplineSet plain(knots, {first_knots(count)});
    const SimplexSplineSet grouped(knots, {first_knots(count)}, {0, 1, 2, 0, 1, 2, 0, 1});
    const SimplexSplineSet other(knots, {first_knots(count)}, {2, 2, 0, 1, 0, 1, 1, 0});
    std::mt19937 random(count);
    std::uniform_real_distribution<double> x(0.0, 2.0);
    std::uniform_real_distribution<double> y(0.0, 1.6);
    for (int k = 0; k < 50; ++k) {
      const Eigen::Vector2d u(x(random), y(random));
      const auto a = evaluate_one(plain, u, 2);
      const auto b = evaluate_one(grouped, u, 2);
      const auto c = evaluate_one(other, u, 2);
      // Round-off of a few dozen products of moderate size, relative to the largest entry.
      const double scale = 1.0 + a.cwiseAbs().maxCoeff();
      EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-12 * scale) << "degree " << count - 3;
      EXPECT_LT((a - c).cwiseAbs().maxCoeff(), 1e-12 * scale) << "degree " << count - 3;
    }
  }
}

TEST(SimplexSplineRecurrence, DerivativesMatchCentralDifferences) {
  const Eigen::MatrixX2d knots = eight_knots();
  for (int count = 4; count <= 8; ++count) {
    const SimplexSplineSet set(knots, {first_knots(count)});
    std::mt19937 random(10 + count);
    std::uniform_real_distribution<double> x(0.2, 1.8);
    std::uniform_real_distribution<double> y(0.2, 1.4);
    const double h = 1e-6;
    for (int k = 0; k < 30; ++k) {
      const Eigen::Vector2d u(x(random), y(random));
      const auto d = evaluate_one(set, u, 2);
      const Eigen::Matrix<double, 6, 1> du = (evaluate_one(set, u + Eigen::Vector2d(h, 0), 2) -
                                              evaluate_one(set, u - Eigen::Vector2d(h, 0), 2)) /
                                             (2 * h);
      const Eigen::Matrix<double, 6, 1> dv = (evaluate_one(set, u + Eigen::Vector2d(0, h), 2) -
                                              evaluate_one(set, u - Eigen::Vector2d(0, h), 2)) /
                                             (2 * h);
      // Truncation h^2 |D^3 M| ~ 1e-11 and rounding 1e-16 |M| / h ~ 1e-10 (|M| <= ~1).
      const double tolerance = 1e-7 * (1.0 + d.cwiseAbs().maxCoeff());
      EXPECT_NEAR(du[0], d[1], tolerance) << "degree " << count - 3;
      EXPECT_NEAR(dv[0], d[2], tolerance);
      EXPECT_NEAR(du[1], d[3], tolerance);
      EXPECT_NEAR(dv[1], d[4], tolerance);
      EXPECT_NEAR(du[2], d[4], tolerance);  // the mixed derivative both ways
      EXPECT_NEAR(dv[2], d[5], tolerance);
    }
  }
}

TEST(SimplexSplineRecurrence, DerivativesOfEveryOrderMatchDifferencesAndVanishBeyondTheDegree) {
  const Eigen::MatrixX2d knots = eight_knots();
  for (int count = 4; count <= 7; ++count) {
    const int m = count - 3;
    const SimplexSplineSet set(knots, {first_knots(count)});
    std::mt19937 random(20 + count);
    std::uniform_real_distribution<double> x(0.3, 1.7);
    std::uniform_real_distribution<double> y(0.3, 1.3);
    const double h = 1e-6;
    Eigen::MatrixXd at;
    Eigen::MatrixXd plus;
    Eigen::MatrixXd minus;
    std::vector<double> scratch;
    const Eigen::Vector2d d(0.8, 0.6);
    for (int k = 0; k < 20; ++k) {
      const Eigen::Vector2d u(x(random), y(random));
      set.evaluate_derivatives(u, d, 1e-13, m + 1, at, scratch);
      const double scale = 1.0 + at.cwiseAbs().maxCoeff();
      // Order m + 1 vanishes inside the pieces (polynomials of degree m).
      for (int b = 0; b <= m + 1; ++b) {
        EXPECT_EQ(at(derivative_index(m + 1 - b, b), 0), 0.0);
      }
      // d/du of D^(a-1,b) and d/dv of D^(a,b-1) by central differences.
      for (int direction = 0; direction < 2; ++direction) {
        const Eigen::Vector2d step = h * Eigen::Vector2d::Unit(direction);
        set.evaluate_derivatives(u + step, d, 1e-13, m, plus, scratch);
        set.evaluate_derivatives(u - step, d, 1e-13, m, minus, scratch);
        for (int total = 1; total <= m; ++total) {
          for (int b = 0; b <= total; ++b) {
            const int a = total - b;
            if ((direction == 0 && a == 0) || (direction == 1 && b == 0)) {
              continue;
            }
            const int lower =
                direction == 0 ? derivative_index(a - 1, b) : derivative_index(a, b - 1);
            const double difference = (plus(lower, 0) - minus(lower, 0)) / (2 * h);
            // Truncation h^2 |D^(total+2) M| and rounding 1e-16 |D^(total-1) M| / h, relative.
            EXPECT_NEAR(difference, at(derivative_index(a, b), 0), 1e-7 * scale)
                << "degree " << m << " derivative (" << a << ", " << b << ")";
          }
        }
      }
      // The first six rows are evaluate()'s.
      Eigen::Matrix<double, 6, Eigen::Dynamic> six;
      set.evaluate(u, d, 1e-13, 2, six);
      Eigen::MatrixXd two;
      set.evaluate_derivatives(u, d, 1e-13, 2, two, scratch);
      EXPECT_EQ((six - two).cwiseAbs().maxCoeff(), 0.0);
    }
  }
}

TEST(SimplexSplineNormalization, IntegralIsOneOverMPlusOneTimesMPlusTwo) {
  // Seidel's normalization: integral M(. | V) = 1 / ((m + 1)(m + 2)) for degree m. Integrated
  // by a degree-6 rule on 96^2 sub-triangles of a triangle containing the knots; the spline is
  // C^(m-1), so the composite error falls like h^(m+1) (about 1e-5 relative for m = 1).
  const Eigen::MatrixX2d knots = eight_knots();
  const TriangleRule rule = subdivided_rule(dunavant_rule(6), 96);
  const Eigen::Vector2d a(-0.5, -0.5);
  const Eigen::Vector2d b(4.5, -0.5);
  const Eigen::Vector2d c(-0.5, 3.5);
  const double area = 0.5 * signed_double_area(a, b, c);
  for (int count = 4; count <= 7; ++count) {
    const SimplexSplineSet set(knots, {first_knots(count)});
    Eigen::Matrix<double, 6, Eigen::Dynamic> result;
    std::vector<double> scratch;
    double integral = 0.0;
    for (int g = 0; g < rule.point_count(); ++g) {
      const Eigen::Vector2d u =
          rule.barycentric(g, 0) * a + rule.barycentric(g, 1) * b + rule.barycentric(g, 2) * c;
      set.evaluate(u, Eigen::Vector2d(0.8, 0.6), 1e-13, 0, result, scratch);
      integral += area * rule.weights[g] * result(0, 0);
    }
    const int m = count - 3;
    EXPECT_NEAR(integral * (m + 1) * (m + 2), 1.0, 3e-5) << "degree " << m;
  }
}

TEST(SimplexSplineSet, CollinearKnotsGiveTheZeroFunctionAndBadInputThrows) {
  Eigen::MatrixX2d line(4, 2);
  line << 0, 0, 1, 1, 2, 2, 3, 3;
  const SimplexSplineSet collinear(line, {0b0111U, 0b1111U});
  Eigen::Matrix<double, 6, Eigen::Dynamic> result;
  collinear.evaluate(Eigen::Vector2d(1.5, 1.5), Eigen::Vector2d(1, 0), 1e-13, 2, result);
  EXPECT_EQ(result.cwiseAbs().maxCoeff(), 0.0);
  const Eigen::MatrixX2d knots = eight_knots();
  EXPECT_NE(error_message([&] { SimplexSplineSet(knots, {0b0011U}); }).find("at least 3"),
            std::string::npos);
  EXPECT_THROW(SimplexSplineSet(knots, {0x1FFU}), Error);  // knot 8 does not exist
  EXPECT_THROW(SimplexSplineSet(Eigen::MatrixX2d::Zero(33, 2), {}), Error);
  EXPECT_THROW(SimplexSplineSet(knots, {0b0111U}, {0, 1}), Error);  // group size mismatch
  Eigen::MatrixX2d bad = knots;
  bad(3, 0) = std::nan("");
  EXPECT_THROW(SimplexSplineSet(bad, {0b0111U}), Error);
  const SimplexSplineSet set(knots, {0b1111U});
  EXPECT_THROW(set.evaluate(Eigen::Vector2d(1, 1), Eigen::Vector2d(1, 0), 1e-13, 3, result), Error);
}

}  // namespace
}  // namespace dnurbs
