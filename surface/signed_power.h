#pragma once
// The signed powers of the superellipsoid (Terzopoulos 2003, below eq 1.30; DESIGN.md "Deformable
// superquadrics"): C(w)^e = sign(cos w)|cos w|^e and S(w)^e = sign(sin w)|sin w|^e, with their
// derivatives with respect to the angle w and the exponent e. Every result is finite for every
// finite w and every exponent e > 0 (tested for e in [kMinSquareness, kMaxSquareness]).

namespace dnurbs {

/// Smallest squareness exponent whose derivatives are tested to stay finite and accurate.
inline constexpr double kMinSquareness = 0.1;
/// Largest squareness exponent tested.
inline constexpr double kMaxSquareness = 4.0;

/// |cos w| or |sin w| at or below this is taken to be exactly zero.
///
/// The double nearest pi/2 gives cos = 6.1e-17, not 0, and pi gives sin = 1.2e-16; with a small
/// exponent (0.1) that rounding would be magnified to 0.024, leaving a hole at the poles and a
/// gap at the seams. Snapping |x| <= 1e-14 (about 50 ulps of pi) to zero makes the surface
/// close exactly; it moves w by at most 1e-14, far below any sampling or quadrature spacing.
inline constexpr double kSignedPowerZero = 1e-14;

/// Floor of |cos w| (|sin w|) in the factor |x|^(e - 1) of the w-derivative.
///
/// d/dw |cos w|^e = -e |cos w|^(e-1) sin w is unbounded where cos w = 0 and e < 1. There the
/// returned derivative is e * max(|x|, kSignedPowerFloor)^(e-1) times the smooth factor, so it
/// is finite (at most 0.1 * 1e-14^-0.9 = 4e11 for e = 0.1) and keeps its sign and direction. It
/// equals the exact derivative wherever |x| > kSignedPowerFloor.
inline constexpr double kSignedPowerFloor = kSignedPowerZero;

/// A signed power, its first derivatives and its second derivative in the exponent.
struct SignedPower {
  double value = 0.0;  ///< sign(x) |x|^e with x = cos w or sin w
  double d_w = 0.0;    ///< d value / d w (floored as documented at kSignedPowerFloor)
  double d_e = 0.0;    ///< d value / d e = sign(x) |x|^e ln|x|, 0 where x is (snapped to) 0
  double d_ee = 0.0;   ///< d^2 value / d e^2 = sign(x) |x|^e ln^2|x|, 0 where x is 0
};

/// C(w)^e = sign(cos w)|cos w|^e and its derivatives. Requires e > 0 (not checked here: the
/// shape classes validate their exponents once).
SignedPower signed_cos_power(double w, double e);

/// S(w)^e = sign(sin w)|sin w|^e and its derivatives. Requires e > 0.
SignedPower signed_sin_power(double w, double e);

/// The signed power of a given x = cos w or sin w whose derivative dx/dw is x_w (so that
/// signed_cos_power(w, e) = signed_power(cos w, -sin w, e)). Requires e > 0.
SignedPower signed_power(double x, double x_w, double e);

}  // namespace dnurbs
