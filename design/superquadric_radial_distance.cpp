#include "dnurbs/design/superquadric_radial_distance.h"

#include <cmath>
#include <numbers>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

using G = GlobalDeformationParameter;

// g^n = (|e| / A)^n of the inside-outside function with its partial derivatives
// d/de = n g / e, d/dA = -n g / A and d/dn = g ln(|e| / A) (all 0 where e = 0 and g = 0).
struct PowerTerm {
  double value = 0.0;
  double d_coordinate = 0.0;
  double d_size = 0.0;
  double d_power = 0.0;
};

PowerTerm power_term(double coordinate, double size, double power) {
  PowerTerm term;
  if (coordinate == 0.0) {
    return term;
  }
  const double ratio = std::abs(coordinate) / size;
  term.value = std::pow(ratio, power);
  term.d_coordinate = power * term.value / coordinate;
  term.d_size = -power * term.value / size;
  term.d_power = term.value * std::log(ratio);
  return term;
}

// The intermediate values of e = T^-1(p) (file comment of the header) that the reverse sweep
// of the gradient reads.
struct Undeformed {
  Eigen::Vector3d e;
  double x1, y1;       // unsheared
  double x2, y2;       // untwisted
  double twist_angle;  // tau z / h
  double bend_angle;   // (z + b2) pi b3 / h
  double f1, f2;       // taper factors t z/h + 1
  bool valid = true;   // false where a taper factor is <= 1e-9
};

Undeformed undeform(const GlobalDeformationParameters& deformation, double h,
                    const Eigen::Vector3d& p) {
  Undeformed r{};
  const double z = p.z();
  r.x1 = p.x() - deformation[G::kShearX] * z;
  r.y1 = p.y() - deformation[G::kShearY] * z;
  r.twist_angle = deformation[G::kTwist] * z / h;
  const double c = std::cos(r.twist_angle);
  const double s = std::sin(r.twist_angle);
  r.x2 = c * r.x1 + s * r.y1;
  r.y2 = -s * r.x1 + c * r.y1;
  r.bend_angle =
      (z + deformation[G::kBendOffset]) * std::numbers::pi * deformation[G::kBendFrequency] / h;
  const double x3 = r.x2 - deformation[G::kBendAmplitude] * std::cos(r.bend_angle);
  r.f1 = deformation[G::kTaper1] * z / h + 1.0;
  r.f2 = deformation[G::kTaper2] * z / h + 1.0;
  r.valid = r.f1 > 1e-9 && r.f2 > 1e-9;
  r.e = r.valid ? Eigen::Vector3d(x3 / r.f1, r.y2 / r.f2, z) : Eigen::Vector3d::Zero();
  return r;
}

}  // namespace

double superquadric_body_radial_distance(const Eigen::Vector3d& size, double e1, double e2,
                                         const GlobalDeformationParameters& deformation,
                                         const Eigen::Vector3d& p,
                                         SuperquadricRadialDistanceGradient* gradient) {
  if (gradient != nullptr) {
    *gradient = SuperquadricRadialDistanceGradient{};
  }
  const double h = size.z();
  const double z = p.z();
  const Undeformed u = undeform(deformation, h, p);
  // Where a taper factor vanishes the inverse does not exist: a large residual.
  const double big = 10.0 * size.maxCoeff();
  if (!u.valid) {
    return big;
  }
  const Eigen::Vector3d& e = u.e;
  const PowerTerm gx = power_term(e.x(), size.x(), 2.0 / e2);
  const PowerTerm gy = power_term(e.y(), size.y(), 2.0 / e2);
  const PowerTerm gz = power_term(e.z(), size.z(), 2.0 / e1);
  const double sum_xy = gx.value + gy.value;
  const double lateral = std::pow(sum_xy, e2 / e1);
  const double F = lateral + gz.value;
  const double radius = e.norm();
  if (!(F > 0.0) || !std::isfinite(F)) {
    return F > 0.0 ? big : -size.minCoeff();
  }
  const double G = std::pow(F, -0.5 * e1);
  const double d = radius * (1.0 - G);
  if (!std::isfinite(d)) {
    return big;
  }
  if (gradient == nullptr) {
    return d;
  }
  // d = |e| (1 - G), G = F^(-e1/2), F = S^(e2/e1) + gz, S = gx + gy (the inside-outside
  // function of the superellipsoid e of Terzopoulos, eq. 1.30); adjoints accumulate backwards.
  SuperquadricRadialDistanceGradient& g = *gradient;
  const double adjoint_radius = 1.0 - G;
  const double adjoint_G = -radius;
  const double adjoint_F = adjoint_G * (-0.5 * e1) * G / F;
  g.e1 += adjoint_G * (-0.5 * std::log(F)) * G;
  double adjoint_S = 0.0;
  if (sum_xy > 0.0) {
    adjoint_S = adjoint_F * (e2 / e1) * lateral / sum_xy;
    const double log_S = std::log(sum_xy);
    g.e1 += adjoint_F * lateral * log_S * (-e2 / (e1 * e1));
    g.e2 += adjoint_F * lateral * log_S / e1;
  }
  const double adjoint_gz = adjoint_F;
  // g(e, A, n) with n = 2/e2 or 2/e1: dn/de = -2/e^2.
  const double adjoint_ex = adjoint_S * gx.d_coordinate + adjoint_radius * e.x() / radius;
  const double adjoint_ey = adjoint_S * gy.d_coordinate + adjoint_radius * e.y() / radius;
  double adjoint_z = adjoint_gz * gz.d_coordinate + adjoint_radius * e.z() / radius;
  g.size.x() += adjoint_S * gx.d_size;
  g.size.y() += adjoint_S * gy.d_size;
  g.size.z() += adjoint_gz * gz.d_size;
  g.e2 += adjoint_S * (gx.d_power + gy.d_power) * (-2.0 / (e2 * e2));
  g.e1 += adjoint_gz * gz.d_power * (-2.0 / (e1 * e1));
  double adjoint_h = 0.0;
  // Untaper: e = (x3 / f1, y2 / f2, z), f_i = t_i z / h + 1.
  const double adjoint_x3 = adjoint_ex / u.f1;
  const double adjoint_y2 = adjoint_ey / u.f2;
  const double adjoint_f1 = -adjoint_ex * e.x() / u.f1;
  const double adjoint_f2 = -adjoint_ey * e.y() / u.f2;
  const double t1 = deformation[G::kTaper1];
  const double t2 = deformation[G::kTaper2];
  adjoint_z += (adjoint_f1 * t1 + adjoint_f2 * t2) / h;
  adjoint_h -= (adjoint_f1 * t1 + adjoint_f2 * t2) * z / (h * h);
  g.deformation[G::kTaper1] = adjoint_f1 * z / h;
  g.deformation[G::kTaper2] = adjoint_f2 * z / h;
  // Unbend: x3 = x2 - b1 cos(angle), angle = (z + b2) pi b3 / h.
  const double b1 = deformation[G::kBendAmplitude];
  const double b2 = deformation[G::kBendOffset];
  const double b3 = deformation[G::kBendFrequency];
  const double adjoint_x2 = adjoint_x3;
  const double adjoint_bend_angle = adjoint_x3 * b1 * std::sin(u.bend_angle);
  g.deformation[G::kBendAmplitude] = -adjoint_x3 * std::cos(u.bend_angle);
  g.deformation[G::kBendOffset] = adjoint_bend_angle * std::numbers::pi * b3 / h;
  g.deformation[G::kBendFrequency] = adjoint_bend_angle * std::numbers::pi * (z + b2) / h;
  adjoint_z += adjoint_bend_angle * std::numbers::pi * b3 / h;
  adjoint_h -= adjoint_bend_angle * u.bend_angle / h;
  // Untwist: (x2, y2) = (c x1 + s y1, -s x1 + c y1), angle = tau z / h; d(x2, y2)/d angle =
  // (y2, -x2).
  const double c = std::cos(u.twist_angle);
  const double s = std::sin(u.twist_angle);
  const double adjoint_twist_angle = adjoint_x2 * u.y2 - adjoint_y2 * u.x2;
  const double adjoint_x1 = c * adjoint_x2 - s * adjoint_y2;
  const double adjoint_y1 = s * adjoint_x2 + c * adjoint_y2;
  g.deformation[G::kTwist] = adjoint_twist_angle * z / h;
  adjoint_z += adjoint_twist_angle * deformation[G::kTwist] / h;
  adjoint_h -= adjoint_twist_angle * u.twist_angle / h;
  // Unshear: x1 = p_x - sx z, y1 = p_y - sy z.
  g.deformation[G::kShearX] = -adjoint_x1 * z;
  g.deformation[G::kShearY] = -adjoint_y1 * z;
  adjoint_z -= deformation[G::kShearX] * adjoint_x1 + deformation[G::kShearY] * adjoint_y1;
  g.point = Eigen::Vector3d(adjoint_x1, adjoint_y1, adjoint_z);
  g.size.z() += adjoint_h;
  return d;
}

double superquadric_radial_distance(const SuperquadricShapeParameters& shape,
                                    const Eigen::Vector3d& centre, const Eigen::Matrix3d& rotation,
                                    const Eigen::Vector3d& x) {
  using P = SuperquadricShapeParameter;
  const Eigen::Vector3d size = shape[P::kScale] * shape.segment<3>(P::kAspect1);
  return superquadric_body_radial_distance(size, shape[P::kSquareness1], shape[P::kSquareness2],
                                           shape.tail<kGlobalDeformationParameterCount>(),
                                           rotation.transpose() * (x - centre));
}

Eigen::Vector2d superquadric_radial_projection(const SuperquadricShapeParameters& shape,
                                               const Eigen::Vector3d& p) {
  using P = SuperquadricShapeParameter;
  const Eigen::Vector3d size = shape[P::kScale] * shape.segment<3>(P::kAspect1);
  const double e1 = shape[P::kSquareness1];
  const double e2 = shape[P::kSquareness2];
  const Undeformed u = undeform(shape.tail<kGlobalDeformationParameterCount>(), size.z(), p);
  const double F = superellipsoid_inside_outside(shape.head<kSuperellipsoidParameterCount>(), u.e);
  if (!u.valid || !(F > 0.0) || !std::isfinite(F)) {
    throw make_error("no radial projection of the body point (", p.x(), ", ", p.y(), ", ", p.z(),
                     "): it maps to the superellipsoid point (", u.e.x(), ", ", u.e.y(), ", ",
                     u.e.z(), ") with taper factors ", u.f1, ", ", u.f2);
  }
  // The superellipsoid point on the ray, in the parameters of its signed powers.
  const Eigen::Vector3d on = u.e * std::pow(F, -0.5 * e1);
  const double sine = std::copysign(std::pow(std::abs(on.z()) / size.z(), 1.0 / e1), on.z());
  const double lateral_x = std::pow(std::abs(on.x()) / size.x(), 2.0 / e2);
  const double lateral_y = std::pow(std::abs(on.y()) / size.y(), 2.0 / e2);
  const double cosine = std::pow(lateral_x + lateral_y, 0.5 * e2 / e1);
  const double v_cosine = std::copysign(std::pow(std::abs(on.x()) / size.x(), 1.0 / e2), on.x());
  const double v_sine = std::copysign(std::pow(std::abs(on.y()) / size.y(), 1.0 / e2), on.y());
  return {std::atan2(sine, cosine), std::atan2(v_sine, v_cosine)};
}

}  // namespace dnurbs
