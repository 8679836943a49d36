#include "nurbs/knot_vector.h"

#include <cmath>
#include <limits>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/common/error_message.h"

#include "core/error.h"

namespace dnurbs {
namespace {

using testing::error_message;

using ::testing::HasSubstr;

TEST(KnotVector, RejectsDecreasingKnotsNamingTheIndex) {
  const std::string message = error_message([] { KnotVector(2, {0, 0, 0, 0.6, 0.4, 1, 1, 1}); });
  EXPECT_THAT(message, HasSubstr("decreases at index 4"));
  EXPECT_THAT(message, HasSubstr("0.6"));
}

TEST(KnotVector, RejectsNonFiniteKnots) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(error_message([&] {
                KnotVector(1, {0, 0, nan, 1, 1});
              }),
              HasSubstr("knot 2 is not finite"));
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THAT(error_message([&] { KnotVector(1, {0, 0, 1, inf}); }), HasSubstr("inf"));
}

TEST(KnotVector, RejectsInteriorMultiplicityAboveDegree) {
  EXPECT_THAT(error_message([] {
                KnotVector(2, {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1});
              }),
              HasSubstr("knot 0.5 has multiplicity 3"));
  EXPECT_THAT(error_message([] {
                KnotVector(2, {0, 0, 0, 0, 1, 1, 1});
              }),
              HasSubstr("knot 0 has multiplicity 4"));
}

TEST(KnotVector, RejectsBadDegreeAndTooFewKnots) {
  EXPECT_THAT(error_message([] { KnotVector(0, {0, 1}); }), HasSubstr("degree 0"));
  EXPECT_THAT(error_message([] { KnotVector(kMaxDegree + 1, std::vector<double>(40, 0.0)); }),
              HasSubstr("degree 16"));
  EXPECT_THAT(error_message([] { KnotVector(3, {0, 0, 0, 1, 1, 1}); }), HasSubstr("got 6"));
  EXPECT_THAT(error_message([] { KnotVector(1, {0, 0, 0, 0}); }), HasSubstr("empty domain"));
  EXPECT_THAT(error_message([] { KnotVector::clamped_uniform(3, 3); }),
              HasSubstr("at least 4 control points, got 3"));
}

TEST(KnotVector, ClampedUniformHasEndMultiplicities) {
  const KnotVector knots = KnotVector::clamped_uniform(3, 7, -1.0, 2.0);
  EXPECT_EQ(knots.size(), 11);
  EXPECT_EQ(knots.multiplicity(-1.0), 4);
  EXPECT_EQ(knots.multiplicity(2.0), 4);
  EXPECT_EQ(knots.control_point_count(), 7);
  EXPECT_DOUBLE_EQ(knots.domain_start(), -1.0);
  EXPECT_DOUBLE_EQ(knots.domain_end(), 2.0);
  EXPECT_EQ(knots.non_empty_spans(), (std::vector<int>{3, 4, 5, 6}));
}

TEST(KnotVector, FindSpanAtRepeatedKnotsAndTheLastKnot) {
  const KnotVector knots(2, {0, 0, 0, 0.5, 0.5, 1, 1, 1});
  EXPECT_EQ(knots.find_span(0.0), 2);
  EXPECT_EQ(knots.find_span(0.25), 2);
  EXPECT_EQ(knots.find_span(0.5), 4);  // the non-empty span [t_4, t_5) = [0.5, 1)
  EXPECT_EQ(knots.find_span(1.0), 4);  // the last knot belongs to the last non-empty span
  EXPECT_EQ(knots.multiplicity(0.5), 2);
  EXPECT_EQ(knots.non_empty_spans(), (std::vector<int>{2, 4}));
}

TEST(KnotVector, FindSpanBracketsEveryParameter) {
  const KnotVector knots(3, {0, 0, 0, 0, 0.1, 0.1, 0.35, 0.6, 0.6, 0.6, 0.9, 1, 1, 1, 1});
  std::mt19937 generator(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const double u =
        trial < 4 ? std::vector<double>{0.1, 0.35, 0.6, 0.9}[trial] : uniform(generator);
    const int span = knots.find_span(u);
    EXPECT_LE(knots[span], u);
    EXPECT_LT(u, knots[span + 1]);
  }
}

TEST(KnotVector, ParametersOutsideTheDomainAreRejected) {
  const KnotVector knots = KnotVector::clamped_uniform(2, 5);
  EXPECT_THAT(error_message([&] { knots.find_span(1.5); }), HasSubstr("parameter 1.5 is outside"));
  EXPECT_THAT(error_message([&] { knots.find_span(std::nan("")); }), HasSubstr("not finite"));
  // Round-off just past the end is accepted and clamped.
  EXPECT_EQ(knots.find_span(1.0 + 1e-15), knots.find_span(1.0));
}

TEST(KnotVector, PeriodicVectorWrapsParametersAndControlPoints) {
  const KnotVector knots = KnotVector::periodic(3, {0.0, 0.2, 0.3, 0.6, 0.8, 1.0});
  EXPECT_TRUE(knots.is_periodic());
  EXPECT_EQ(knots.control_point_count(), 5);
  EXPECT_EQ(knots.size(), 5 + 2 * 3 + 1);
  EXPECT_DOUBLE_EQ(knots.domain_start(), 0.0);
  EXPECT_DOUBLE_EQ(knots.domain_end(), 1.0);
  // The extension repeats the spacing of the period: t_{i+n} - t_i = T.
  for (int i = 0; i + 5 < knots.size(); ++i) {
    EXPECT_NEAR(knots[i + 5] - knots[i], 1.0, 1e-15);
  }
  EXPECT_NEAR(knots.to_domain(1.25), 0.25, 1e-15);
  EXPECT_NEAR(knots.to_domain(-0.75), 0.25, 1e-15);
  EXPECT_EQ(knots.find_span(1.25), knots.find_span(0.25));
  const int last_span = knots.find_span(0.9);
  EXPECT_EQ(knots.control_point_index(last_span, 3), (last_span - 3 + 3) % 5);
  EXPECT_EQ(knots.period_knots(), (std::vector<double>{0.0, 0.2, 0.3, 0.6, 0.8, 1.0}));
}

TEST(KnotVector, PeriodicRejectsTooFewControlPointsAndMultiplicityAcrossTheWrap) {
  EXPECT_THAT(error_message([] {
                KnotVector::periodic(3, {0, 0.5, 1});
              }),
              HasSubstr("at least 5 period knots"));
  // 0 twice at the start and 1 twice at the end wrap onto one knot of multiplicity 3 > p = 2.
  EXPECT_THAT(error_message([] {
                KnotVector::periodic(2, {0, 0, 0.5, 0.7, 1, 1});
              }),
              HasSubstr("multiplicity 3"));
}

}  // namespace
}  // namespace dnurbs
