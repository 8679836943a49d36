#pragma once
// Systems the constraint tests share: a D-NURBS surface and a D-NURBS curve near it.

#include <cmath>

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/nurbs/knot_vector.h"

namespace dnurbs::testing {

/// A gently curved bicubic patch over [0, 1]^2 of 6 x 6 control points, weights optionally
/// non-uniform (free weights make every constraint non-linear in q).
inline NurbsSurface curved_patch(bool rational) {
  const KnotVector knots = KnotVector::clamped_uniform(3, 6);
  Eigen::MatrixX3d points(36, 3);
  Eigen::VectorXd weights(36);
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      const double x = i / 5.0;
      const double y = j / 5.0;
      points.row(i * 6 + j) << x, y, 0.2 * std::sin(3.0 * x) * std::cos(2.0 * y);
      weights[i * 6 + j] = rational ? 1.0 + 0.3 * std::sin(i + 2.0 * j) : 1.0;
    }
  }
  return NurbsSurface(knots, knots, points, weights);
}

/// A cubic curve that runs across the patch slightly above it.
inline NurbsCurve curve_over_patch(bool rational) {
  const KnotVector knots = KnotVector::clamped_uniform(3, 7);
  Eigen::MatrixX3d points(7, 3);
  Eigen::VectorXd weights(7);
  for (int i = 0; i < 7; ++i) {
    const double t = i / 6.0;
    points.row(i) << 0.1 + 0.8 * t, 0.2 + 0.5 * t * t, 0.05 + 0.02 * std::sin(5.0 * t);
    weights[i] = rational ? 1.0 + 0.2 * std::cos(3.0 * i) : 1.0;
  }
  return NurbsCurve(knots, points, weights);
}

/// Surface (model 0) and curve (model 1), fixed or free weights, with some stiffness.
inline System surface_and_curve(WeightMode mode) {
  DNurbsSettings settings;
  settings.weight_mode = mode;
  DNurbsSurfaceMaterial surface_material;
  surface_material.a10 = surface_material.a01 = 0.5;
  surface_material.b20 = surface_material.b02 = 0.05;
  DNurbsCurveMaterial curve_material;
  curve_material.tension = 0.2;
  curve_material.rigidity = 0.01;
  const bool rational = mode == WeightMode::kFree;
  System system;
  system.add_model(DNurbsSurface(curved_patch(rational), surface_material, settings));
  system.add_model(DNurbsCurve(curve_over_patch(rational), curve_material, settings));
  return system;
}

}  // namespace dnurbs::testing
