#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"

#include "dnurbs/dynamics/dnurbs/local_sculpting.h"

namespace dnurbs {

namespace {

std::array<MaterialFunction, kQuantityCount> curve_stiffness(const DNurbsCurveMaterial& material) {
  // Quantity numbering of quadrature_assembly.h: 1 = x_u, 3 = x_uu.
  std::array<MaterialFunction, kQuantityCount> stiffness;
  stiffness[1] = material.tension;
  stiffness[3] = material.rigidity;
  return stiffness;
}

}  // namespace

DNurbsCurve::DNurbsCurve(const NurbsCurve& curve, const DNurbsCurveMaterial& material,
                         const DNurbsSettings& settings)
    : DNurbsModel(curve.knots(), nullptr, curve.control_points(), curve.weights(),
                  material.mass_density, material.damping_density, curve_stiffness(material),
                  {"", "tension w1", "", "rigidity w2", "", ""}, settings),
      curve_(curve) {}

NurbsCurve DNurbsCurve::curve(ConstVectorRef q) const {
  return NurbsCurve(curve_.knots(), control_points(q), weights(q));
}

ParameterDomain DNurbsCurve::parameter_domain(ConstVectorRef /*q*/) const {
  ParameterDomain domain;
  domain.u_min = curve_.knots().domain_start();
  domain.u_max = curve_.knots().domain_end();
  domain.periodic_u = curve_.knots().is_periodic();
  return domain;
}

std::optional<Shape> DNurbsCurve::exact_shape(ConstVectorRef q) const {
  return Shape(curve(q));
}

int DNurbsCurve::freeze_outside(const SculptedRegion& region, int margin) {
  return freeze_outside_sculpted_region(*this, region, margin);
}

}  // namespace dnurbs
