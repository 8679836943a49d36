#include "dnurbs/nurbs/closest_point.h"

namespace dnurbs {

CurveProjection closest_point(const NurbsCurve& curve, const Eigen::Vector3d& point) {
  return CurveProjector(curve).closest_point(point);
}

SurfaceProjection closest_point(const NurbsSurface& surface, const Eigen::Vector3d& point) {
  return SurfaceProjector(surface).closest_point(point);
}

double invert_point(const NurbsCurve& curve, const Eigen::Vector3d& point, double tolerance) {
  return CurveProjector(curve).invert(point, tolerance);
}

Eigen::Vector2d invert_point(const NurbsSurface& surface, const Eigen::Vector3d& point,
                             double tolerance) {
  return SurfaceProjector(surface).invert(point, tolerance);
}

}  // namespace dnurbs
