#include "dnurbs/surface/deformable_superquadric_shape.h"

#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "dnurbs/core/error.h"
#include "dnurbs/surface/signed_power.h"

namespace dnurbs {

bool outward_unit_normal(const Eigen::Vector3d& d_u, const Eigen::Vector3d& d_v,
                         Eigen::Vector3d& normal) {
  const Eigen::Vector3d cross = d_v.cross(d_u);
  const double length = cross.norm();
  if (!(length > 0.0) || !std::isfinite(length)) {
    return false;
  }
  normal = cross / length;
  return true;
}

bool is_superquadric_pole(double u) {
  return std::abs(std::cos(u)) <= kSignedPowerZero;
}

DeformableSuperquadricShape::DeformableSuperquadricShape()
    : DeformableSuperquadricShape(sphere(1.0)) {}

DeformableSuperquadricShape::DeformableSuperquadricShape(
    const SuperquadricShapeParameters& parameters) {
  set_parameters(parameters);
}

DeformableSuperquadricShape DeformableSuperquadricShape::sphere(double radius) {
  return DeformableSuperquadricShape(
      combine(sphere_superellipsoid_parameters(radius), GlobalDeformationParameters::Zero()));
}

SuperquadricShapeParameters DeformableSuperquadricShape::combine(
    const SuperellipsoidParameters& superellipsoid,
    const GlobalDeformationParameters& deformation) {
  SuperquadricShapeParameters parameters;
  parameters << superellipsoid, deformation;
  return parameters;
}

void DeformableSuperquadricShape::set_parameters(const SuperquadricShapeParameters& parameters) {
  validate_superellipsoid_parameters(parameters.head<kSuperellipsoidParameterCount>());
  validate_global_deformation_parameters(parameters.tail<kGlobalDeformationParameterCount>());
  parameters_ = parameters;
}

double DeformableSuperquadricShape::half_height() const {
  return parameters_[SuperquadricShapeParameter::kScale] *
         parameters_[SuperquadricShapeParameter::kAspect3];
}

Eigen::Vector3d DeformableSuperquadricShape::point(double u, double v) const {
  const Eigen::Vector3d e = superellipsoid_point(superellipsoid_parameters(), u, v);
  return apply_global_deformation(global_deformation_parameters(), half_height(), e).point;
}

SuperquadricShapeEvaluation DeformableSuperquadricShape::evaluate(double u, double v) const {
  using Q = SuperquadricShapeParameter;
  // Terzopoulos 2003, eq. 1.30: s = T(e); J = dT/de de/dq_e + dT/dh dh/dq_s + dT/dq_T.
  const SuperellipsoidEvaluation e = evaluate_superellipsoid(superellipsoid_parameters(), u, v);
  const auto t = apply_global_deformation(global_deformation_parameters(), half_height(), e.point);
  SuperquadricShapeEvaluation result;
  result.point = t.point;
  result.d_u = t.d_point * e.d_u;
  result.d_v = t.d_point * e.d_v;
  result.jacobian.leftCols<kSuperellipsoidParameterCount>() = t.d_point * e.jacobian;
  result.jacobian.rightCols<kGlobalDeformationParameterCount>() = t.d_parameters;
  // h = a a3: dh/da = a3, dh/da3 = a.
  result.jacobian.col(Q::kScale) += t.d_half_height * parameters_[Q::kAspect3];
  result.jacobian.col(Q::kAspect3) += t.d_half_height * parameters_[Q::kScale];
  return result;
}

Eigen::Matrix<double, 3, kSuperquadricShapeParameterCount>
DeformableSuperquadricShape::jacobian_rate(double u, double v,
                                           const SuperquadricShapeParameters& q_s_dot) const {
  using Q = SuperquadricShapeParameter;
  const SuperellipsoidParameters superellipsoid_dot = q_s_dot.head<kSuperellipsoidParameterCount>();
  const SuperellipsoidEvaluation e = evaluate_superellipsoid(superellipsoid_parameters(), u, v);
  const auto e_jacobian_dot =
      superellipsoid_jacobian_rate(superellipsoid_parameters(), u, v, superellipsoid_dot);
  // The motion of T's arguments: e moves at J_e q_e_dot, h = a a3 at a_dot a3 + a a3_dot.
  const double a = parameters_[Q::kScale];
  const double a3 = parameters_[Q::kAspect3];
  const double a_dot = q_s_dot[Q::kScale];
  const double a3_dot = q_s_dot[Q::kAspect3];
  DeformationMotion<kGlobalDeformationParameterCount> motion;
  motion.point = e.jacobian * superellipsoid_dot;
  motion.parameters = q_s_dot.tail<kGlobalDeformationParameterCount>();
  motion.half_height = a_dot * a3 + a * a3_dot;
  const GlobalDeformationWithRate t = apply_global_deformation_with_rate(
      global_deformation_parameters(), half_height(), e.point, motion);
  // Differentiate J = [F J_e + dT/dh dh/dq_e | dT/dtheta] in time.
  Eigen::Matrix<double, 3, kSuperquadricShapeParameterCount> rate;
  rate.leftCols<kSuperellipsoidParameterCount>() =
      t.rate.d_point * e.jacobian + t.value.d_point * e_jacobian_dot;
  rate.rightCols<kGlobalDeformationParameterCount>() = t.rate.d_parameters;
  rate.col(Q::kScale) += t.rate.d_half_height * a3 + t.value.d_half_height * a3_dot;
  rate.col(Q::kAspect3) += t.rate.d_half_height * a + t.value.d_half_height * a_dot;
  return rate;
}

Eigen::Vector3d DeformableSuperquadricShape::pole_normal(double u, double v) const {
  // n = |det F| F^-T (+-z) = +-sign(det F) (F e_x x F e_y), F = dT/dp at the pole.
  const Eigen::Vector3d e = superellipsoid_point(superellipsoid_parameters(), u, v);
  const auto t = apply_global_deformation(global_deformation_parameters(), half_height(), e);
  const double side = std::sin(u) > 0.0 ? 1.0 : -1.0;
  const double orientation = t.d_point.determinant() < 0.0 ? -1.0 : 1.0;
  const Eigen::Vector3d cross = side * orientation * t.d_point.col(0).cross(t.d_point.col(1));
  const double length = cross.norm();
  if (!(length > 0.0) || !std::isfinite(length)) {
    throw make_error("superquadric normal undefined at the pole u = ", u,
                     ": the global deformation collapses its tangent plane");
  }
  return cross / length;
}

Eigen::Vector3d DeformableSuperquadricShape::unit_normal(double u, double v) const {
  return unit_normal(u, v, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
}

Eigen::Vector3d DeformableSuperquadricShape::unit_normal(
    double u, double v, const Eigen::Vector3d& displacement_d_u,
    const Eigen::Vector3d& displacement_d_v) const {
  if (is_superquadric_pole(u)) {
    return pole_normal(u, v);
  }
  const SuperquadricShapeEvaluation s = evaluate(u, v);
  Eigen::Vector3d normal;
  if (!outward_unit_normal(s.d_u + displacement_d_u, s.d_v + displacement_d_v, normal)) {
    throw make_error("superquadric normal undefined at (u, v) = (", u, ", ", v,
                     "): the tangents are parallel or vanish");
  }
  return normal;
}

}  // namespace dnurbs
