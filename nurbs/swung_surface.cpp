#include "dnurbs/nurbs/swung_surface.h"

#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

SwungSurface::SwungSurface(NurbsCurve profile, NurbsCurve trajectory, double alpha)
    : profile_(std::move(profile)), trajectory_(std::move(trajectory)), alpha_(alpha) {
  if (!std::isfinite(alpha_) || alpha_ == 0.0) {
    throw make_error("swung surface scale alpha is ", alpha_, ", must be finite and non-zero");
  }
  // The planar curves are stored as 3-D curves with an exactly zero off-plane coordinate.
  for (int i = 0; i < profile_.control_point_count(); ++i) {
    const double y = profile_.control_points()(i, 1);
    if (y != 0.0) {
      throw make_error("profile control point ", i, " has y = ", y,
                       "; the profile must lie in the xz plane (y exactly 0)");
    }
  }
  for (int j = 0; j < trajectory_.control_point_count(); ++j) {
    const double z = trajectory_.control_points()(j, 2);
    if (z != 0.0) {
      throw make_error("trajectory control point ", j, " has z = ", z,
                       "; the trajectory must lie in the xy plane (z exactly 0)");
    }
  }
}

Eigen::Vector3d SwungSurface::point(double u, double v) const {
  const Eigen::Vector3d p = profile_.point(u);
  const Eigen::Vector3d t = trajectory_.point(v);
  // Qin & Terzopoulos, Dynamic NURBS swung surfaces, CAD 27(2) 1995: the swung surface.
  return {alpha_ * p.x() * t.x(), alpha_ * p.x() * t.y(), p.z()};
}

void SwungSurface::derivatives(double u, double v, int order, SurfaceDerivatives& result) const {
  if (order < 0 || order > kMaxDerivativeOrder) {
    throw make_error("swung surface derivative order ", order, " is outside 0..",
                     kMaxDerivativeOrder);
  }
  CurveDerivatives p;
  CurveDerivatives t;
  profile_.derivatives(u, order, p);
  trajectory_.derivatives(v, order, t);
  result.reset(order);
  // Each factor depends on one parameter only: S^(k,l) = (alpha p_x^(k) t^(l), [l == 0] p_z^(k)).
  for (int k = 0; k <= order; ++k) {
    for (int l = 0; k + l <= order; ++l) {
      const double scale = alpha_ * p(k, 0);
      result(k, l) = Eigen::Vector3d(scale * t(l, 0), scale * t(l, 1), l == 0 ? p(k, 2) : 0.0);
    }
  }
}

SurfaceDerivatives SwungSurface::derivatives(double u, double v, int order) const {
  SurfaceDerivatives result;
  derivatives(u, v, order, result);
  return result;
}

Eigen::Vector3d SwungSurface::unit_normal(double u, double v) const {
  const CurveDerivatives p = profile_.derivatives(u, 1);
  const CurveDerivatives t = trajectory_.derivatives(v, 1);
  // S_u x S_v = alpha p_x m: the factor alpha p_x carries the pole's degeneracy, m does not.
  const double t_cross = t(0, 0) * t(1, 1) - t(0, 1) * t(1, 0);
  const Eigen::Vector3d m(-p(1, 2) * t(1, 1), p(1, 2) * t(1, 0), alpha_ * p(1, 0) * t_cross);
  double sign = alpha_ * p(0, 0);
  if (sign == 0.0) {
    // On the axis: p_x ~ p_x'(u0) (u - u0) moving into the domain (u - u0 < 0 at its end).
    const double side = profile_.knots().to_domain(u) >= u_end() ? -1.0 : 1.0;
    sign = side * alpha_ * p(1, 0);
  }
  const double length = m.norm();
  if (sign == 0.0 || !(length > 0.0) || !std::isfinite(length)) {
    throw make_error("swung surface normal is undefined at (u, v) = (", u, ", ", v, ")");
  }
  return (sign > 0.0 ? 1.0 : -1.0) * m / length;
}

NurbsSurface SwungSurface::to_nurbs_surface() const {
  const int m = profile_.control_point_count();
  const int n = trajectory_.control_point_count();
  Eigen::MatrixX3d points(m * n, 3);
  Eigen::VectorXd weights(m * n);
  for (int i = 0; i < m; ++i) {
    const double x = alpha_ * profile_.control_points()(i, 0);
    const double z = profile_.control_points()(i, 2);
    for (int j = 0; j < n; ++j) {
      // Row i * n + j: the u index outer, as NurbsSurface stores its net.
      points.row(i * n + j) << x * trajectory_.control_points()(j, 0),
          x * trajectory_.control_points()(j, 1), z;
      weights[i * n + j] = profile_.weights()[i] * trajectory_.weights()[j];
    }
  }
  return NurbsSurface(profile_.knots(), trajectory_.knots(), std::move(points), std::move(weights));
}

}  // namespace dnurbs
