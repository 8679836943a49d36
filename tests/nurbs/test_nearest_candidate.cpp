#include "dnurbs/nurbs/nearest_candidate.h"

#include <gtest/gtest.h>

namespace dnurbs {
namespace {

TEST(NearestCandidate, NearerWinsAndTiesGoToTheSmallerParameter) {
  NearestCandidate<double> best;
  best.absolute_tie = 1e-13;
  best.offer(2.0, 0.7, true);
  EXPECT_EQ(best.parameter, 0.7);
  best.offer(1.5, 0.9, true);  // nearer
  EXPECT_EQ(best.parameter, 0.9);
  best.offer(1.5 + 1e-14, 0.1, true);  // a tie (within 1e-13 (1.5 + 1)), smaller parameter
  EXPECT_EQ(best.parameter, 0.1);
  best.offer(1.5 + 1e-9, 0.0, true);  // not a tie
  EXPECT_EQ(best.parameter, 0.1);
  EXPECT_DOUBLE_EQ(best.distance, 1.5 + 1e-14);
}

TEST(NearestCandidate, ApproximatePointsMustBeStrictlyNearer) {
  NearestCandidate<Eigen::Vector2d> best;
  best.offer(1.0, Eigen::Vector2d(0.5, 0.5), true);
  best.offer(1.0, Eigen::Vector2d(0.1, 0.1), false);  // tie, but approximate
  EXPECT_EQ(best.parameter, Eigen::Vector2d(0.5, 0.5));
  best.offer(0.5, Eigen::Vector2d(0.9, 0.9), false);  // strictly nearer
  EXPECT_EQ(best.parameter, Eigen::Vector2d(0.9, 0.9));
  EXPECT_FALSE(best.exact);
  best.offer(0.5, Eigen::Vector2d(0.95, 0.0), true);  // an exact tie beats an approximate one
  EXPECT_TRUE(best.exact);
  // Surfaces order parameters by u, then v.
  best.offer(0.5, Eigen::Vector2d(0.95, -1.0), true);
  EXPECT_EQ(best.parameter, Eigen::Vector2d(0.95, -1.0));
}

TEST(NearestCandidate, BoundsLowerWithoutChangingTheAnswer) {
  NearestCandidate<double> best;
  best.offer(3.0, 0.2, true);
  best.bound_by(1.0);  // a point of the shape that is not a candidate
  EXPECT_EQ(best.distance, 3.0);
  EXPECT_NEAR(best.pruning_bound(), 1.0, 1e-12);  // the bound times 1 + 1e-13
}

}  // namespace
}  // namespace dnurbs
