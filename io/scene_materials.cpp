#include "io/scene_materials.h"

namespace dnurbs {

DNurbsSettings dnurbs_settings(const SceneDNurbsSettings& settings) {
  DNurbsSettings result;
  result.weight_mode = settings.free_weights ? WeightMode::kFree : WeightMode::kFixed;
  result.quadrature_points = settings.quadrature_points;
  result.minimum_weight = settings.minimum_weight;
  return result;
}

DNurbsCurveMaterial dnurbs_curve_material(double mass_density, double damping_density,
                                          double tension, double rigidity) {
  DNurbsCurveMaterial material;
  material.mass_density = mass_density;
  material.damping_density = damping_density;
  material.tension = tension;
  material.rigidity = rigidity;
  return material;
}

DNurbsSurfaceMaterial dnurbs_surface_material(double mass_density, double damping_density,
                                              const Eigen::Matrix<double, 5, 1>& stiffness) {
  DNurbsSurfaceMaterial material;
  material.mass_density = mass_density;
  material.damping_density = damping_density;
  material.a10 = stiffness(0);
  material.a01 = stiffness(1);
  material.b20 = stiffness(2);
  material.b11 = stiffness(3);
  material.b02 = stiffness(4);
  return material;
}

}  // namespace dnurbs
