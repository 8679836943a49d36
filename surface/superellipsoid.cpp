#include "dnurbs/surface/superellipsoid.h"

#include <cmath>

#include "dnurbs/core/error.h"
#include "dnurbs/surface/signed_power.h"

namespace dnurbs {

namespace {

// The four signed powers of e(u, v) (Terzopoulos 2003, eq. 1.30) with their derivatives:
// C(u)^e1, S(u)^e1, C(v)^e2, S(v)^e2, from one cos and one sin per angle.
struct SuperellipsoidPowers {
  SignedPower cu;
  SignedPower su;
  SignedPower cv;
  SignedPower sv;
};

SuperellipsoidPowers superellipsoid_powers(const SuperellipsoidParameters& parameters, double u,
                                           double v) {
  using P = SuperellipsoidParameter;
  const double cos_u = std::cos(u);
  const double sin_u = std::sin(u);
  const double cos_v = std::cos(v);
  const double sin_v = std::sin(v);
  return {signed_power(cos_u, -sin_u, parameters[P::kSquareness1]),
          signed_power(sin_u, cos_u, parameters[P::kSquareness1]),
          signed_power(cos_v, -sin_v, parameters[P::kSquareness2]),
          signed_power(sin_v, cos_v, parameters[P::kSquareness2])};
}

}  // namespace

SuperellipsoidParameters sphere_superellipsoid_parameters(double radius) {
  SuperellipsoidParameters parameters;
  parameters << radius, 1.0, 1.0, 1.0, 1.0, 1.0;
  return parameters;
}

void validate_superellipsoid_parameters(const SuperellipsoidParameters& parameters) {
  static constexpr const char* kNames[kSuperellipsoidParameterCount] = {
      "scale a", "aspect a1", "aspect a2", "aspect a3", "squareness e1", "squareness e2"};
  for (int k = 0; k < kSuperellipsoidParameterCount; ++k) {
    const double value = parameters[k];
    if (!std::isfinite(value) || !(value > 0.0)) {
      throw make_error("superellipsoid ", kNames[k], " is ", value,
                       "; it must be finite and positive");
    }
  }
}

Eigen::Vector3d superellipsoid_point(const SuperellipsoidParameters& parameters, double u,
                                     double v) {
  using P = SuperellipsoidParameter;
  const double a = parameters[P::kScale];
  const auto [cu, su, cv, sv] = superellipsoid_powers(parameters, u, v);
  return {a * parameters[P::kAspect1] * cu.value * cv.value,
          a * parameters[P::kAspect2] * cu.value * sv.value,
          a * parameters[P::kAspect3] * su.value};
}

SuperellipsoidEvaluation evaluate_superellipsoid(const SuperellipsoidParameters& parameters,
                                                 double u, double v) {
  using P = SuperellipsoidParameter;
  const double a = parameters[P::kScale];
  const double a1 = parameters[P::kAspect1];
  const double a2 = parameters[P::kAspect2];
  const double a3 = parameters[P::kAspect3];
  const auto [cu, su, cv, sv] = superellipsoid_powers(parameters, u, v);

  SuperellipsoidEvaluation result;
  // The unscaled directions: e = a * diag(a1, a2, a3) * r with r = (Cu Cv, Cu Sv, Su).
  const Eigen::Vector3d r(cu.value * cv.value, cu.value * sv.value, su.value);
  const Eigen::Vector3d scale(a * a1, a * a2, a * a3);
  result.point = scale.cwiseProduct(r);

  // Tangents: e1 enters through u only, e2 through v only.
  result.d_u = scale.cwiseProduct(Eigen::Vector3d(cu.d_w * cv.value, cu.d_w * sv.value, su.d_w));
  result.d_v = scale.cwiseProduct(Eigen::Vector3d(cu.value * cv.d_w, cu.value * sv.d_w, 0.0));

  // Jacobian columns (a, a1, a2, a3, e1, e2).
  result.jacobian.setZero();
  result.jacobian.col(P::kScale) = Eigen::Vector3d(a1, a2, a3).cwiseProduct(r);
  result.jacobian(0, P::kAspect1) = a * r.x();
  result.jacobian(1, P::kAspect2) = a * r.y();
  result.jacobian(2, P::kAspect3) = a * r.z();
  result.jacobian.col(P::kSquareness1) =
      scale.cwiseProduct(Eigen::Vector3d(cu.d_e * cv.value, cu.d_e * sv.value, su.d_e));
  result.jacobian.col(P::kSquareness2) =
      scale.cwiseProduct(Eigen::Vector3d(cu.value * cv.d_e, cu.value * sv.d_e, 0.0));
  return result;
}

Eigen::Matrix<double, 3, kSuperellipsoidParameterCount> superellipsoid_jacobian_rate(
    const SuperellipsoidParameters& parameters, double u, double v,
    const SuperellipsoidParameters& parameters_dot) {
  using P = SuperellipsoidParameter;
  const double a = parameters[P::kScale];
  const Eigen::Vector3d aspect(parameters[P::kAspect1], parameters[P::kAspect2],
                               parameters[P::kAspect3]);
  const double a_dot = parameters_dot[P::kScale];
  const Eigen::Vector3d aspect_dot(parameters_dot[P::kAspect1], parameters_dot[P::kAspect2],
                                   parameters_dot[P::kAspect3]);
  const double e1_dot = parameters_dot[P::kSquareness1];
  const double e2_dot = parameters_dot[P::kSquareness2];
  const auto [cu, su, cv, sv] = superellipsoid_powers(parameters, u, v);

  // Rates of the signed powers (w fixed): Cu_dot = dCu/de1 e1_dot, and so on.
  const double cu_dot = cu.d_e * e1_dot;
  const double su_dot = su.d_e * e1_dot;
  const double cv_dot = cv.d_e * e2_dot;
  const double sv_dot = sv.d_e * e2_dot;
  const Eigen::Vector3d r(cu.value * cv.value, cu.value * sv.value, su.value);
  const Eigen::Vector3d r_dot(cu_dot * cv.value + cu.value * cv_dot,
                              cu_dot * sv.value + cu.value * sv_dot, su_dot);
  const Eigen::Vector3d scale = a * aspect;
  const Eigen::Vector3d scale_dot = a_dot * aspect + a * aspect_dot;

  // Differentiate each column of evaluate_superellipsoid's Jacobian in time.
  Eigen::Matrix<double, 3, kSuperellipsoidParameterCount> rate;
  rate.setZero();
  rate.col(P::kScale) = aspect_dot.cwiseProduct(r) + aspect.cwiseProduct(r_dot);
  rate(0, P::kAspect1) = a_dot * r.x() + a * r_dot.x();
  rate(1, P::kAspect2) = a_dot * r.y() + a * r_dot.y();
  rate(2, P::kAspect3) = a_dot * r.z() + a * r_dot.z();
  const Eigen::Vector3d rho1(cu.d_e * cv.value, cu.d_e * sv.value, su.d_e);
  const Eigen::Vector3d rho1_dot(cu.d_ee * e1_dot * cv.value + cu.d_e * cv_dot,
                                 cu.d_ee * e1_dot * sv.value + cu.d_e * sv_dot, su.d_ee * e1_dot);
  rate.col(P::kSquareness1) = scale_dot.cwiseProduct(rho1) + scale.cwiseProduct(rho1_dot);
  const Eigen::Vector3d rho2(cu.value * cv.d_e, cu.value * sv.d_e, 0.0);
  const Eigen::Vector3d rho2_dot(cu_dot * cv.d_e + cu.value * cv.d_ee * e2_dot,
                                 cu_dot * sv.d_e + cu.value * sv.d_ee * e2_dot, 0.0);
  rate.col(P::kSquareness2) = scale_dot.cwiseProduct(rho2) + scale.cwiseProduct(rho2_dot);
  return rate;
}

double superellipsoid_inside_outside(const SuperellipsoidParameters& parameters,
                                     const Eigen::Vector3d& point) {
  using P = SuperellipsoidParameter;
  const double a = parameters[P::kScale];
  const double e1 = parameters[P::kSquareness1];
  const double e2 = parameters[P::kSquareness2];
  const double x = std::abs(point.x() / (a * parameters[P::kAspect1]));
  const double y = std::abs(point.y() / (a * parameters[P::kAspect2]));
  const double z = std::abs(point.z() / (a * parameters[P::kAspect3]));
  const double horizontal = std::pow(x, 2.0 / e2) + std::pow(y, 2.0 / e2);
  return std::pow(horizontal, e2 / e1) + std::pow(z, 2.0 / e1);
}

}  // namespace dnurbs
