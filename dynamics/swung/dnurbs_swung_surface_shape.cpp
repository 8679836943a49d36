// The shape of the swung D-NURBS model through the Model contract: its parameter domain, outward
// orientation, parametric surface with exact normals, exact (tensor-product) shape and the
// tangent kinematics of surface orientation constraints (Qin & Terzopoulos, Dynamic NURBS swung
// surfaces for physics-based shape design, CAD 27(2) 1995).

#include <array>

#include "dnurbs/dynamics/swung/dnurbs_swung_surface.h"
#include "dnurbs/dynamics/swung/swung_parametric_surface.h"
#include "dnurbs/dynamics/swung/swung_tangent_kinematics.h"

namespace dnurbs {

ParameterDomain DNurbsSwungSurface::parameter_domain(ConstVectorRef q) const {
  return swung_parameter_domain(surface(q));
}

ParametricSurface DNurbsSwungSurface::parametric_surface(ConstVectorRef q) const {
  const SwungSurface shape = surface(q);
  return swung_parametric_surface(shape, swung_parameter_domain(shape), orientation_);
}

std::optional<Shape> DNurbsSwungSurface::exact_shape(ConstVectorRef q) const {
  return Shape(surface(q).to_nurbs_surface());
}

void DNurbsSwungSurface::tangent_kinematics(ConstVectorRef q, ConstVectorRef qd,
                                            const Eigen::Vector2d& u,
                                            TangentKinematics& tangents) const {
  SwungJacobian tangent_jacobian;
  jacobian(q, u, 1, tangent_jacobian);
  std::array<Eigen::Vector3d, 6> rates;
  jacobian_rate(q, qd, u, 1, rates);
  swung_tangent_kinematics(tangent_jacobian, qd, rates, tangents);
}

}  // namespace dnurbs
