#pragma once
// Shapes shared by the design tests.

#include <Eigen/Core>

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/nurbs/knot_vector.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs::test {

/// Greville abscissae of a knot vector: control points there make x(u) = u.
inline Eigen::VectorXd greville_abscissae(const KnotVector& knots) {
  const int p = knots.degree();
  Eigen::VectorXd result(knots.control_point_count());
  for (int i = 0; i < knots.control_point_count(); ++i) {
    double sum = 0.0;
    for (int k = 1; k <= p; ++k) {
      sum += knots[i + k];
    }
    result[i] = sum / p;
  }
  return result;
}

/// The patch x(u, v) = (u, v, height(u, v)) sampled at the Greville points (height 0: a plane).
template <typename Height>
NurbsSurface graph_patch(const KnotVector& knots_u, const KnotVector& knots_v, Height height) {
  const Eigen::VectorXd gu = greville_abscissae(knots_u);
  const Eigen::VectorXd gv = greville_abscissae(knots_v);
  Eigen::MatrixX3d points(gu.size() * gv.size(), 3);
  for (Eigen::Index i = 0; i < gu.size(); ++i) {
    for (Eigen::Index j = 0; j < gv.size(); ++j) {
      points.row(i * gv.size() + j) << gu[i], gv[j], height(gu[i], gv[j]);
    }
  }
  return NurbsSurface(knots_u, knots_v, points);
}

inline NurbsSurface flat_patch(int degree, int spans) {
  const KnotVector knots = KnotVector::clamped_uniform(degree, spans + degree);
  return graph_patch(knots, knots, [](double, double) { return 0.0; });
}

/// Thin plate under tension.
inline DNurbsSurfaceMaterial plate_material() {
  DNurbsSurfaceMaterial material;
  material.a10 = 1.0;
  material.a01 = 1.0;
  material.b20 = 0.1;
  material.b11 = 0.1;
  material.b02 = 0.1;
  return material;
}

/// A constant point force f at u.
inline Force point_force(const Eigen::Vector2d& u, const Eigen::Vector3d& f) {
  return [u, f](const Model& model, double, ConstVectorRef q, ConstVectorRef, VectorRef force) {
    model.add_point_force(q, u, f, force);
  };
}

}  // namespace dnurbs::test
