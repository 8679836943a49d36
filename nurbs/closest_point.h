#pragma once
// Closest-point projection onto NURBS curves and surfaces: a coarse sampling for the start,
// then Newton's method on the first-order conditions (S - P).Su = (S - P).Sv = 0 with the
// parameters kept in the domain (Piegl & Tiller section 6.1).

#include <Eigen/Core>

#include "nurbs/nurbs_curve.h"
#include "nurbs/nurbs_surface.h"

namespace dnurbs {

struct CurveProjection {
  double parameter = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance = 0.0;
};

struct SurfaceProjection {
  Eigen::Vector2d parameter = Eigen::Vector2d::Zero();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance = 0.0;
};

/// The parameter of the curve point nearest to `point` (samples per non-empty span for the
/// start, then at most 50 Newton steps to |delta u| <= 1e-15 (domain length)).
CurveProjection closest_point(const NurbsCurve& curve, const Eigen::Vector3d& point);
/// The parameters of the surface point nearest to `point`: damped Newton searches from the 4
/// nearest of kSamplesPerSpan^2 samples per non-empty span pair, the best result kept.
SurfaceProjection closest_point(const NurbsSurface& surface, const Eigen::Vector3d& point);

}  // namespace dnurbs
