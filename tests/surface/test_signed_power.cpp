#include "dnurbs/surface/signed_power.h"

#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "tests/common/superquadric_test_support.h"

namespace dnurbs {
namespace {

using testing::kExponents;
using testing::kSpecialAngles;

constexpr double kPi = std::numbers::pi;
// Generic angles: |cos w| and |sin w| >= 0.2, all four quadrants.
constexpr double kGenericAngles[] = {-2.7, -1.1, -0.4, 0.3, 0.9, 1.3, 2.2, 3.0};

TEST(SignedPower, ReducesToCosineAndSineForExponentOne) {
  for (const double w : kGenericAngles) {
    // pow(|x|, 1) and the sign restore x exactly.
    EXPECT_EQ(signed_cos_power(w, 1.0).value, std::cos(w)) << w;
    EXPECT_EQ(signed_sin_power(w, 1.0).value, std::sin(w)) << w;
  }
}

TEST(SignedPower, KeepsTheSignOfCosineAndSine) {
  for (const double e : kExponents) {
    for (const double w : kGenericAngles) {
      EXPECT_EQ(std::signbit(signed_cos_power(w, e).value), std::signbit(std::cos(w)));
      EXPECT_EQ(std::signbit(signed_sin_power(w, e).value), std::signbit(std::sin(w)));
      // |C|^(1/e) = |cos|: pow round trips to a few ulps.
      EXPECT_NEAR(std::pow(std::abs(signed_cos_power(w, e).value), 1.0 / e), std::abs(std::cos(w)),
                  1e-15);
    }
  }
}

TEST(SignedPower, AngleDerivativeMatchesCentralDifferences) {
  const double step = 1e-6;
  for (const double e : kExponents) {
    for (const double w : kGenericAngles) {
      const auto cos_value = [e](double x) {
        return Eigen::Matrix<double, 1, 1>(signed_cos_power(x, e).value);
      };
      const auto sin_value = [e](double x) {
        return Eigen::Matrix<double, 1, 1>(signed_sin_power(x, e).value);
      };
      // Central differences: truncation h^2 f'''/6 <= 1e-11 (|f'''| < 10 where |cos|, |sin|
      // >= 0.2) plus rounding 1e-16/h = 1e-10.
      EXPECT_NEAR(signed_cos_power(w, e).d_w, testing::central_difference(cos_value, w, step)[0],
                  1e-9)
          << "e " << e << " w " << w;
      EXPECT_NEAR(signed_sin_power(w, e).d_w, testing::central_difference(sin_value, w, step)[0],
                  1e-9)
          << "e " << e << " w " << w;
    }
  }
}

TEST(SignedPower, ExponentDerivativeMatchesCentralDifferences) {
  const double step = 1e-6;
  for (const double e : kExponents) {
    for (const double w : kGenericAngles) {
      const auto cos_value = [w](double x) {
        return Eigen::Matrix<double, 1, 1>(signed_cos_power(w, x).value);
      };
      const auto sin_value = [w](double x) {
        return Eigen::Matrix<double, 1, 1>(signed_sin_power(w, x).value);
      };
      // d^3/de^3 |x|^e = |x|^e ln^3|x| is below 5 for |x| >= 0.2: truncation 1e-12, rounding 1e-10.
      EXPECT_NEAR(signed_cos_power(w, e).d_e, testing::central_difference(cos_value, e, step)[0],
                  1e-9)
          << "e " << e << " w " << w;
      EXPECT_NEAR(signed_sin_power(w, e).d_e, testing::central_difference(sin_value, e, step)[0],
                  1e-9)
          << "e " << e << " w " << w;
    }
  }
}

TEST(SignedPower, SecondExponentDerivativeMatchesCentralDifferences) {
  const double step = 1e-6;
  for (const double e : kExponents) {
    for (const double w : kGenericAngles) {
      const auto cos_rate = [w](double x) {
        return Eigen::Matrix<double, 1, 1>(signed_cos_power(w, x).d_e);
      };
      // d^3/de^3 of d_e is |x|^e ln^4|x| < 7 for |x| >= 0.2: truncation 1e-12, rounding 1e-10.
      EXPECT_NEAR(signed_cos_power(w, e).d_ee, testing::central_difference(cos_rate, e, step)[0],
                  1e-9)
          << "e " << e << " w " << w;
    }
  }
}

TEST(SignedPower, IsFiniteWhereCosineOrSineVanish) {
  for (const double e : kExponents) {
    for (const double w : kSpecialAngles) {
      for (const SignedPower& power : {signed_cos_power(w, e), signed_sin_power(w, e)}) {
        EXPECT_TRUE(std::isfinite(power.value)) << "e " << e << " w " << w;
        EXPECT_TRUE(std::isfinite(power.d_w)) << "e " << e << " w " << w;
        EXPECT_TRUE(std::isfinite(power.d_e)) << "e " << e << " w " << w;
        EXPECT_TRUE(std::isfinite(power.d_ee)) << "e " << e << " w " << w;
      }
    }
  }
}

TEST(SignedPower, RoundedZerosOfCosineAndSineAreExactlyZero) {
  // cos(pi/2) in doubles is 6.1e-17 and sin(pi) 1.2e-16; both snap to 0, so C(pi/2)^0.1 is 0,
  // not 0.024, and the superellipsoid closes at its poles.
  for (const double e : kExponents) {
    EXPECT_EQ(signed_cos_power(kPi / 2, e).value, 0.0);
    EXPECT_EQ(signed_cos_power(-kPi / 2, e).value, 0.0);
    EXPECT_EQ(signed_sin_power(0.0, e).value, 0.0);
    EXPECT_EQ(signed_sin_power(kPi, e).value, 0.0);
    EXPECT_EQ(signed_sin_power(-kPi, e).value, 0.0);
    // |x|^e ln|x| -> 0 as x -> 0: the exponent derivative vanishes there.
    EXPECT_EQ(signed_cos_power(kPi / 2, e).d_e, 0.0);
    EXPECT_EQ(signed_sin_power(kPi, e).d_e, 0.0);
  }
}

TEST(SignedPower, AngleDerivativeIsFlooredWhereItIsUnbounded) {
  // At cos w = 0 and e < 1 the returned derivative is e floor^(e-1) times -sin w (= -1 here).
  for (const double e : {0.1, 0.5}) {
    const double expected = -e * std::pow(kSignedPowerFloor, e - 1.0);
    // pow and the product are correctly rounded to a few ulps of the (large) value.
    EXPECT_NEAR(signed_cos_power(kPi / 2, e).d_w / expected, 1.0, 1e-14) << e;
    EXPECT_NEAR(signed_sin_power(0.0, e).d_w / -expected, 1.0, 1e-14) << e;
  }
  // e = 1: the exact derivative -sin w; e > 1: the floored factor is tiny (exact value 0).
  EXPECT_EQ(signed_cos_power(kPi / 2, 1.0).d_w, -1.0);
  EXPECT_LT(std::abs(signed_cos_power(kPi / 2, 2.0).d_w), 1e-13);
  EXPECT_LT(std::abs(signed_cos_power(kPi / 2, 4.0).d_w), 1e-40);
}

TEST(SignedPower, AngleDerivativeIsExactJustOutsideTheFloor) {
  // At |x| = 1e-10 > floor the derivative is e |x|^(e-1) x_w, unmodified.
  const double x = 1e-10;
  for (const double e : kExponents) {
    const SignedPower power = signed_power(x, 0.7, e);
    EXPECT_NEAR(power.d_w / (e * std::pow(x, e - 1.0) * 0.7), 1.0, 1e-15) << e;
  }
}

}  // namespace
}  // namespace dnurbs
