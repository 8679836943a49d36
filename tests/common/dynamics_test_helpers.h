#pragma once
// Shapes and materials shared by the dynamics tests.

#include <Eigen/Core>
#include <vector>

#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/nurbs/knot_vector.h"
#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"
#include "dnurbs/nurbs/shape_generators.h"

namespace dnurbs::test {

/// A thin plate under tension with unit-order coefficients of every kind (a10 = 2, a01 = 0.5,
/// b20 = 1, b11 = 0.7, b02 = 3), unit mass density and the given damping density.
inline DNurbsSurfaceMaterial plate_under_tension(double damping_density = 0.0) {
  DNurbsSurfaceMaterial material;
  material.damping_density = damping_density;
  material.a10 = 2.0;
  material.a01 = 0.5;
  material.b20 = 1.0;
  material.b11 = 0.7;
  material.b02 = 3.0;
  return material;
}

/// Greville abscissae of a knot vector: placing control points there makes x(u) = u.
inline Eigen::VectorXd greville(const KnotVector& knots) {
  const std::vector<double> abscissae = greville_abscissae(knots);
  return Eigen::Map<const Eigen::VectorXd>(abscissae.data(),
                                           static_cast<Eigen::Index>(abscissae.size()));
}

/// The straight curve x(u) = (u, 0, 0) on [0, 1], degree p, `spans` uniform spans.
inline NurbsCurve straight_curve(int degree, int spans) {
  KnotVector knots = KnotVector::clamped_uniform(degree, spans + degree);
  const Eigen::VectorXd x = greville(knots);
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(x.size(), 3);
  points.col(0) = x;
  return NurbsCurve(knots, points);
}

/// A planar square patch x(u, v) = (u, v, 0) on [0, 1]^2, degrees (p, q), uniform spans.
inline NurbsSurface flat_patch(int degree_u, int degree_v, int spans_u, int spans_v) {
  KnotVector knots_u = KnotVector::clamped_uniform(degree_u, spans_u + degree_u);
  KnotVector knots_v = KnotVector::clamped_uniform(degree_v, spans_v + degree_v);
  const Eigen::VectorXd gu = greville(knots_u);
  const Eigen::VectorXd gv = greville(knots_v);
  Eigen::MatrixX3d points(gu.size() * gv.size(), 3);
  for (Eigen::Index i = 0; i < gu.size(); ++i) {
    for (Eigen::Index j = 0; j < gv.size(); ++j) {
      points.row(i * gv.size() + j) << gu[i], gv[j], 0.0;
    }
  }
  return NurbsSurface(knots_u, knots_v, points);
}

}  // namespace dnurbs::test
