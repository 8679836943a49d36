#include "dnurbs/dynamics/swung/swung_parametric_surface.h"

#include <cmath>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/gauss_legendre.h"

namespace dnurbs {
namespace {

// Points per non-empty span of the orientation integrals: only their signs are used.
constexpr int kOrientationPoints = 8;

// integral f(c, c') over the domain of `curve` by Gauss-Legendre sums over its non-empty spans.
template <typename Integrand>
double integrate_over_curve(const NurbsCurve& curve, Integrand&& integrand) {
  const KnotVector& knots = curve.knots();
  CurveDerivatives c;
  double sum = 0.0;
  for (const int span : knots.non_empty_spans()) {
    const GaussLegendreRule rule =
        gauss_legendre_rule_on(kOrientationPoints, knots[span], knots[span + 1]);
    for (Eigen::Index k = 0; k < rule.nodes.size(); ++k) {
      curve.derivatives(rule.nodes[k], 1, c);
      sum += rule.weights[k] * integrand(c);
    }
  }
  return sum;
}

}  // namespace

ParameterDomain swung_parameter_domain(const SwungSurface& surface) {
  return nurbs_parameter_domain(surface.to_nurbs_surface());
}

NormalOrientation swung_normal_orientation(const SwungSurface& surface) {
  // The trajectory's swept area integral (t x t') dv, and the profile integrals of I_r and I_z.
  const double swept = integrate_over_curve(surface.trajectory(), [](const CurveDerivatives& t) {
    return t(0, 0) * t(1, 1) - t(0, 1) * t(1, 0);
  });
  const double radial = -integrate_over_curve(
      surface.profile(), [](const CurveDerivatives& p) { return p(0, 0) * p(0, 0) * p(1, 2); });
  const double vertical = integrate_over_curve(
      surface.profile(), [](const CurveDerivatives& p) { return p(0, 0) * p(1, 0); });
  // Relative to the profile's extent: a flat profile's p_z' is exactly 0, a curved one's is not.
  const Eigen::MatrixX3d& points = surface.profile().control_points();
  const double extent = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
  const double scale = extent * extent * extent;
  double sign = 0.0;
  if (std::abs(radial) > 1e-12 * scale) {
    sign = radial * swept;
  } else if (std::abs(vertical) > 1e-12 * scale) {
    sign = vertical * swept;
  }
  if (sign == 0.0 || !std::isfinite(sign)) {
    throw make_error("swung surface orientation is undefined: the surface has no area (radial ",
                     "integral ", radial, ", vertical integral ", vertical, ", swept area ", swept,
                     ")");
  }
  return sign > 0.0 ? NormalOrientation::kSuCrossSv : NormalOrientation::kSvCrossSu;
}

ParametricSurface swung_parametric_surface(const SwungSurface& surface,
                                           const ParameterDomain& domain,
                                           NormalOrientation orientation) {
  const double sign = orientation == NormalOrientation::kSuCrossSv ? 1.0 : -1.0;
  return ParametricSurface(
      domain, [surface](double u, double v) { return surface.point(u, v); },
      [surface, sign](double u, double v) {
        return Eigen::Vector3d(sign * surface.unit_normal(u, v));
      },
      orientation);
}

}  // namespace dnurbs
