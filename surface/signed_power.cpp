#include "dnurbs/surface/signed_power.h"

#include <cmath>

namespace dnurbs {

// One threshold: below it the value snaps to 0 and the derivative uses the floor, above it
// both are exact, so max(|x|, floor) needs no separate test.
static_assert(kSignedPowerFloor == kSignedPowerZero);

SignedPower signed_power(double x, double x_w, double e) {
  SignedPower result;
  const double magnitude = std::abs(x);
  if (magnitude <= kSignedPowerZero) {
    // Snapped to zero: value 0 for every e > 0, so d/de = 0 (the limit of |x|^e ln|x| too).
    // d/dw sign(x)|x|^e = e |x|^(e-1) x_w (the two signs cancel), with |x| floored so that the
    // factor stays finite where x = 0 and e < 1.
    result.d_w = e * std::pow(kSignedPowerFloor, e - 1.0) * x_w;
    return result;
  }
  const double power = std::pow(magnitude, e);
  result.value = x > 0.0 ? power : -power;
  // e |x|^(e-1) = e |x|^e / |x|: one pow for both (|x| > floor here).
  result.d_w = e * (power / magnitude) * x_w;
  const double logarithm = std::log(magnitude);
  result.d_e = result.value * logarithm;
  result.d_ee = result.d_e * logarithm;
  return result;
}

SignedPower signed_cos_power(double w, double e) {
  return signed_power(std::cos(w), -std::sin(w), e);
}

SignedPower signed_sin_power(double w, double e) {
  return signed_power(std::sin(w), std::cos(w), e);
}

}  // namespace dnurbs
