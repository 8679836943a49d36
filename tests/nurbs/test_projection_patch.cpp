#include "dnurbs/nurbs/projection_patch.h"

#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "tests/nurbs/random_shapes.h"

#include "dnurbs/nurbs/bezier_extraction.h"

namespace dnurbs {
namespace {

// A random Bezier patch of degrees (p, q): control points in [-1, 1]^3, weights 0.05..20 if
// rational (else 1), homogeneous rows.
Eigen::MatrixXd random_patch(int p, int q, std::mt19937& generator, bool rational = true) {
  Eigen::MatrixX3d points;
  Eigen::VectorXd weights;
  testing::random_net((p + 1) * (q + 1), rational, generator, points, weights);
  Eigen::MatrixXd rows((p + 1) * (q + 1), 4);
  rows.leftCols<3>() = points.array().colwise() * weights.array();
  rows.col(3) = weights;
  return rows;
}

/// Records what a search reports.
class Recorder : public ProjectionVisitor {
 public:
  explicit Recorder(const ProjectionPatch& patch, const Eigen::Vector3d& query)
      : patch_(patch), query_(query) {}
  double stationary_point(double s, double t, bool exact) override {
    points.emplace_back(s, t);
    exact_count += exact ? 1 : 0;
    bound = std::min(bound, (patch_.evaluate(s, t).point - query_).norm());
    return bound;
  }
  double surface_point(double distance) override {
    bound = std::min(bound, distance);
    return bound;
  }
  std::vector<Eigen::Vector2d> points;
  int exact_count = 0;
  double bound = std::numeric_limits<double>::infinity();

 private:
  const ProjectionPatch& patch_;
  const Eigen::Vector3d& query_;
};

TEST(ProjectionPatch, DerivativesMatchFiniteDifferences) {
  std::mt19937 generator(9001U);
  const double h = 1e-6;
  for (int trial = 0; trial < 50; ++trial) {
    const int p = 1 + trial % 5;
    const int q = 1 + (trial / 5) % 5;
    const ProjectionPatch patch(random_patch(p, q, generator), p, q, true,
                                Eigen::Vector4d(0, 1, 0, 1));
    const double s = testing::random_real(generator, 0.1, 0.9);
    const double t = testing::random_real(generator, 0.1, 0.9);
    const PatchPoint at = patch.evaluate(s, t);
    const PatchPoint ds_plus = patch.evaluate(s + h, t);
    const PatchPoint ds_minus = patch.evaluate(s - h, t);
    const PatchPoint dt_plus = patch.evaluate(s, t + h);
    const PatchPoint dt_minus = patch.evaluate(s, t - h);
    // Central differences: O(h^2) truncation (third derivatives of rational patches with
    // weight ratios up to 400 reach ~1e4, so ~1e-8) plus round-off ~1e-16 / h = 1e-10, relative
    // to the derivative's size.
    const auto near = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return (a - b).norm() <= 1e-5 * (1.0 + a.norm());
    };
    EXPECT_TRUE(near(at.s, (ds_plus.point - ds_minus.point) / (2 * h))) << trial;
    EXPECT_TRUE(near(at.t, (dt_plus.point - dt_minus.point) / (2 * h))) << trial;
    EXPECT_TRUE(near(at.ss, (ds_plus.s - ds_minus.s) / (2 * h))) << trial;
    EXPECT_TRUE(near(at.st, (dt_plus.s - dt_minus.s) / (2 * h))) << trial;
    EXPECT_TRUE(near(at.tt, (dt_plus.t - dt_minus.t) / (2 * h))) << trial;
    // The corners are the corner control points (a weighted sum with one non-zero term: ulps).
    EXPECT_LT((patch.evaluate(1.0, 0.0).point - patch.corner(1)).norm(), 1e-14);
    EXPECT_LT((patch.evaluate(0.0, 1.0).point - patch.corner(2)).norm(), 1e-14);
  }
}

TEST(ProjectionPatch, LowerBoundNeverExceedsTheDistanceOfAnyPoint) {
  std::mt19937 generator(9002U);
  for (int trial = 0; trial < 100; ++trial) {
    const ProjectionPatch patch(random_patch(3, 2, generator), 3, 2, true,
                                Eigen::Vector4d(0, 1, 0, 1));
    const Eigen::Vector3d query(testing::random_real(generator, -3, 3),
                                testing::random_real(generator, -3, 3),
                                testing::random_real(generator, -3, 3));
    const double lower = patch.lower_bound(query);
    for (int i = 0; i <= 20; ++i) {
      for (int j = 0; j <= 20; ++j) {
        // A bound, not an estimate: only the evaluation's ulps may cross it.
        EXPECT_LE(lower, (patch.evaluate(i / 20.0, j / 20.0).point - query).norm() + 1e-15);
      }
    }
  }
}

TEST(ProjectionPatch, ReportsStationaryPointsWhereTheGradientVanishes) {
  // Every point reported is a zero of (S - Q).S_s and (S - Q).S_t (to round-off), and no sample
  // of the square's interior is nearer than both the nearest of them and the edges' samples.
  std::mt19937 generator(9003U);
  std::vector<double> workspace;
  for (int trial = 0; trial < 100; ++trial) {
    const int p = 1 + trial % 4;
    const int q = 1 + (trial / 4) % 4;
    const bool rational = trial % 2 == 0;
    const ProjectionPatch patch(random_patch(p, q, generator, rational), p, q, rational,
                                Eigen::Vector4d(0, 1, 0, 1));
    const Eigen::Vector3d query(testing::random_real(generator, -2, 2),
                                testing::random_real(generator, -2, 2),
                                testing::random_real(generator, -2, 2));
    Recorder recorder(patch, query);
    int budget = 4000;
    patch.stationary_points(query, std::numeric_limits<double>::infinity(), 0.0, workspace, budget,
                            recorder);
    EXPECT_EQ(recorder.exact_count, static_cast<int>(recorder.points.size())) << trial;
    for (const Eigen::Vector2d& st : recorder.points) {
      const PatchPoint value = patch.evaluate(st.x(), st.y());
      const Eigen::Vector3d offset = value.point - query;
      // Newton converged: the gradient is round-off of |S - Q| |S_s| (~10 here).
      EXPECT_NEAR(offset.dot(value.s), 0.0, 1e-12 * (1.0 + offset.norm() * value.s.norm()));
      EXPECT_NEAR(offset.dot(value.t), 0.0, 1e-12 * (1.0 + offset.norm() * value.t.norm()));
    }
    // The minimum over the closed square is at a reported point or on the edges: sampling
    // the interior finds nothing nearer than both.
    double edges = std::numeric_limits<double>::infinity();
    double interior = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 100; ++i) {
      for (int j = 0; j <= 100; ++j) {
        const double d = (patch.evaluate(i / 100.0, j / 100.0).point - query).norm();
        const bool edge = i == 0 || j == 0 || i == 100 || j == 100;
        (edge ? edges : interior) = std::min(edge ? edges : interior, d);
      }
    }
    EXPECT_LE(std::min(recorder.bound, edges), interior + 1e-15) << trial;  // ulps of a distance
  }
}

}  // namespace
}  // namespace dnurbs
