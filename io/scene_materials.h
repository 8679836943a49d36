#pragma once
// The library's settings and materials of a scene's D-NURBS models: what SceneSimulation builds
// the models with and what the "fit" key's smoothness energy uses at load time.

#include <Eigen/Core>

#include "dynamics/dnurbs/dnurbs_curve.h"
#include "dynamics/dnurbs/dnurbs_model.h"
#include "dynamics/dnurbs/dnurbs_surface.h"
#include "io/scene.h"

namespace dnurbs {

/// Weight mode, quadrature points and minimum weight of a D-NURBS model.
DNurbsSettings dnurbs_settings(const SceneDNurbsSettings& settings);

/// A D-NURBS curve's material from the scene's values (constants).
DNurbsCurveMaterial dnurbs_curve_material(double mass_density, double damping_density,
                                          double tension, double rigidity);

/// A D-NURBS surface's material; `stiffness` is (a10, a01, b20, b11, b02).
DNurbsSurfaceMaterial dnurbs_surface_material(double mass_density, double damping_density,
                                              const Eigen::Matrix<double, 5, 1>& stiffness);

}  // namespace dnurbs
