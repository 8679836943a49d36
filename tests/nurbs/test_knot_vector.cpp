#include "dnurbs/nurbs/knot_vector.h"

#include <cmath>
#include <limits>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/common/error_message.h"
#include "tests/nurbs/random_shapes.h"

#include "dnurbs/core/error.h"

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

TEST(PeriodicKnotVector, SeamCopyOneUlpBelowThePeriodStartIsTheSeam) {
  // Regression: this list was rejected with "knot vector decreases at index 4:
  // -0.4797091342172106 > -0.4797091342172107" (the second copy of the seam computed as
  // t_{p+n} - T, one ulp off).
  const double start = -0.4797091342172106;
  const double end = start + 1.7;
  const double copy = std::nextafter(start, -1.0);
  const KnotVector knots = KnotVector::periodic(3, {start, copy, 0.1, 0.4, 0.8, end});
  EXPECT_EQ(knots.multiplicity(start), 2);
  EXPECT_EQ(knots.period_knots()[1], start);  // snapped onto the seam exactly
}

TEST(PeriodicKnotVector, SeamCopiesAtTheEndKeepTheListsMultiplicity) {
  // Regression: the end copies sit a few ulps below t_{p+n}; the wrapped copies t_{p+n-j} - T
  // then missed t_p by round-off and the seam was stored with multiplicity 1 instead of 3.
  const double start = 0.3;
  const double end = 2.9;
  const double copy = end - 2.0 * std::numeric_limits<double>::epsilon() * end;
  const KnotVector knots = KnotVector::periodic(3, {start, 0.9, 1.4, 2.0, copy, copy, end});
  EXPECT_EQ(knots.multiplicity(start), 3);
  EXPECT_EQ(knots.multiplicity(end), 3);
  // Stored t_0..t_3: 2.0 - T, then the two wrapped end copies and t_p, all exactly t_p.
  EXPECT_NEAR(knots[0], 2.0 - (end - start), 1e-15);
  EXPECT_EQ(knots[1], start);
  EXPECT_EQ(knots[2], start);
  EXPECT_EQ(knots[3], start);
}

TEST(PeriodicKnotVector, AcceptsEveryRandomPeriodListWithItsSeamMultiplicity) {
  // 3000 lists, degrees 1..7, seam multiplicity 1..p split between both ends of the list, half
  // of them with the seam copies moved by up to 4 ulps.
  std::mt19937 generator(20240611U);
  for (int trial = 0; trial < 3000; ++trial) {
    const int degree = 1 + trial % 7;
    testing::RandomKnotOptions options;
    options.periodic = true;
    options.seam_multiplicity = 1 + (trial / 7) % degree;
    options.perturb_seam = trial % 2 == 1;
    const std::vector<double> period = testing::random_period_knots(degree, options, generator);
    const KnotVector knots = KnotVector::periodic(degree, period);
    const int n = knots.control_point_count();
    ASSERT_EQ(n + 1, static_cast<int>(period.size()));
    EXPECT_EQ(knots.multiplicity(knots.domain_start()), options.seam_multiplicity)
        << "trial " << trial;
    EXPECT_EQ(knots.domain_start(), period.front());
    EXPECT_EQ(knots.domain_end(), period.back());
    // The bi-infinite sequence: the stored knots, then t_{i+n} = t_i + T to round-off, and the
    // seam multiplicity in every period.
    const double period_length = period.back() - period.front();
    for (int i = 0; i < knots.size(); ++i) {
      ASSERT_EQ(knots.extended_knot(i), knots[i]);
    }
    for (int i = -3 * n; i < 3 * n; ++i) {
      // |t| <= 3 + 4 * 4 = 19 here, a few ulps of it per shift by T.
      EXPECT_NEAR(knots.extended_knot(i + n) - knots.extended_knot(i), period_length, 1e-13);
      EXPECT_LE(knots.extended_knot(i), knots.extended_knot(i + 1));
    }
    int copies = 0;
    for (int i = -2 * n; i < 2 * n; ++i) {
      copies += knots.extended_knot(i) == knots.domain_start() - period_length ? 1 : 0;
    }
    EXPECT_EQ(copies, options.seam_multiplicity) << "trial " << trial;
  }
}

TEST(PeriodicKnotVector, WrapToPeriodMapsTheSeamOntoThePeriodStart) {
  const KnotVector knots = KnotVector::periodic(2, {0.5, 0.9, 1.3, 1.8, 2.5});
  EXPECT_EQ(knots.wrap_to_period(2.5), 0.5);
  EXPECT_EQ(knots.wrap_to_period(std::nextafter(2.5, 0.0)), 0.5);
  EXPECT_EQ(knots.wrap_to_period(4.5), 0.5);
  EXPECT_NEAR(knots.wrap_to_period(2.9), 0.9, 1e-15);  // fmod by the period: an ulp
  EXPECT_EQ(knots.wrap_to_period(1.3), 1.3);
  // Open vectors only map into the domain.
  EXPECT_EQ(KnotVector::clamped_uniform(2, 4).wrap_to_period(1.0), 1.0);
}

TEST(PeriodicKnotVector, RejectsDecreasingPeriodKnotsBeyondTheSeamTolerance) {
  EXPECT_THAT(error_message([] {
                KnotVector::periodic(2, {0.0, 0.5, 0.4, 0.8, 1.0});
              }),
              HasSubstr("period knots decrease at index 2: 0.5 > 0.4"));
  EXPECT_THAT(error_message([] {
                KnotVector::periodic(2, {0.0, 0.5, 0.7, 1.1, 1.0});
              }),
              HasSubstr("decrease at index 4: 1.1 > 1"));
}

}  // namespace
}  // namespace dnurbs
