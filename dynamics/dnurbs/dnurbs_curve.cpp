#include "dynamics/dnurbs/dnurbs_curve.h"

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

}  // namespace dnurbs
