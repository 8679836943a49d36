#include "dnurbs/surface/parametric_surface.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// d/dt of f at t over [lo, hi] with step h: central where the stencil fits (or the direction
// wraps), otherwise the second-order one-sided formula pointing into the interval.
template <typename Function>
Eigen::Vector3d derivative(const Function& f, double t, double lo, double hi, double h,
                           bool periodic) {
  if (periodic || (t - h >= lo && t + h <= hi)) {
    double plus = t + h;
    double minus = t - h;
    if (periodic) {
      const double period = hi - lo;
      if (plus > hi) {
        plus -= period;
      }
      if (minus < lo) {
        minus += period;
      }
    }
    return (f(plus) - f(minus)) / (2.0 * h);
  }
  const double s = (t - h < lo) ? h : -h;
  return (-3.0 * f(t) + 4.0 * f(t + s) - f(t + 2.0 * s)) / (2.0 * s);
}

bool is_finite(const Eigen::Vector3d& x) {
  return x.allFinite();
}

}  // namespace

void ParameterDomain::validate() const {
  if (!std::isfinite(u_min) || !std::isfinite(u_max) || !(u_min < u_max)) {
    throw make_error("parameter domain: u range [", u_min, ", ", u_max,
                     "] is not a finite interval with u_min < u_max");
  }
  if (!std::isfinite(v_min) || !std::isfinite(v_max) || !(v_min < v_max)) {
    throw make_error("parameter domain: v range [", v_min, ", ", v_max,
                     "] is not a finite interval with v_min < v_max");
  }
  if (periodic_u && (pole_u_min || pole_u_max)) {
    throw make_error("parameter domain: u is periodic and bounded by a pole");
  }
  if (periodic_v && (pole_v_min || pole_v_max)) {
    throw make_error("parameter domain: v is periodic and bounded by a pole");
  }
}

int ParameterDomain::pole_at(double u, double v) const {
  if (pole_u_min && u == u_min) {
    return 0;
  }
  if (pole_u_max && u == u_max) {
    return 1;
  }
  if (pole_v_min && v == v_min) {
    return 2;
  }
  if (pole_v_max && v == v_max) {
    return 3;
  }
  return -1;
}

ParametricSurface::ParametricSurface(const ParameterDomain& domain, SurfaceFunction point,
                                     SurfaceFunction unit_normal, NormalOrientation orientation)
    : domain_(domain),
      point_(std::move(point)),
      normal_(std::move(unit_normal)),
      orientation_(orientation) {
  domain_.validate();
  if (!point_) {
    throw make_error("parametric surface: the point function is empty");
  }
}

Eigen::Vector3d ParametricSurface::point(double u, double v) const {
  Eigen::Vector3d x = point_(u, v);
  if (!is_finite(x)) {
    throw make_error("parametric surface: point at (", u, ", ", v, ") is not finite");
  }
  return x;
}

Eigen::Vector3d ParametricSurface::unit_normal(double u, double v) const {
  if (!normal_) {
    return difference_normal(u, v);
  }
  const Eigen::Vector3d n = normal_(u, v);
  if (!is_finite(n) || n.norm() == 0.0) {
    throw make_error("parametric surface: normal at (", u, ", ", v, ") is undefined");
  }
  return n.normalized();
}

Eigen::Vector3d ParametricSurface::difference_normal(double u, double v) const {
  const ParameterDomain& d = domain_;
  const double extent_u = d.u_max - d.u_min;
  const double extent_v = d.v_max - d.v_min;
  const int pole = d.pole_at(u, v);
  if (pole >= 0) {
    // Pole: the mean of the difference normals on a ring of 16 parameters just off the pole
    // (its first-order variation around the ring cancels)
    constexpr int kRing = 16;
    constexpr double kOffset = 1e-4;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int k = 0; k < kRing; ++k) {
      const double t = (k + 0.5) / kRing;
      if (pole < 2) {
        const double u_in = pole == 0 ? d.u_min + kOffset * extent_u : d.u_max - kOffset * extent_u;
        sum += difference_normal(u_in, d.v_at(t));
      } else {
        const double v_in = pole == 2 ? d.v_min + kOffset * extent_v : d.v_max - kOffset * extent_v;
        sum += difference_normal(d.u_at(t), v_in);
      }
    }
    if (!(sum.norm() > 0.0)) {
      throw make_error("parametric surface: the normal at the pole (", u, ", ", v,
                       ") is undefined");
    }
    return sum.normalized();
  }
  // Tangents S_u, S_v by differences with steps kDifferenceStep times the extents
  const Eigen::Vector3d s_u = derivative([&](double t) { return point(t, v); }, u, d.u_min, d.u_max,
                                         kDifferenceStep * extent_u, d.periodic_u);
  const Eigen::Vector3d s_v = derivative([&](double t) { return point(u, t); }, v, d.v_min, d.v_max,
                                         kDifferenceStep * extent_v, d.periodic_v);
  const Eigen::Vector3d cross =
      orientation_ == NormalOrientation::kSuCrossSv ? s_u.cross(s_v) : s_v.cross(s_u);
  const double length = cross.norm();
  // A cross product below 1e-12 of the tangents' product is rounding noise: no tangent plane
  if (!std::isfinite(length) || !(length > 1e-12 * s_u.norm() * s_v.norm()) || length == 0.0) {
    throw make_error("parametric surface: the tangents at (", u, ", ", v,
                     ") are parallel or vanish; the normal is undefined");
  }
  return cross / length;
}

ParameterDomain nurbs_parameter_domain(const NurbsSurface& surface, double tolerance) {
  ParameterDomain domain;
  domain.u_min = surface.knots_u().domain_start();
  domain.u_max = surface.knots_u().domain_end();
  domain.v_min = surface.knots_v().domain_start();
  domain.v_max = surface.knots_v().domain_end();
  const Eigen::MatrixX3d& net = surface.control_points();
  const double size = (net.colwise().maxCoeff() - net.colwise().minCoeff()).norm();
  const double limit = tolerance * std::max(size, 1e-300);
  constexpr int kSamples = 9;
  // Seams: both edge curves of a clamped direction agree at every sample
  auto same_edges = [&](bool along_u) {
    for (int k = 0; k < kSamples; ++k) {
      const double t = static_cast<double>(k) / (kSamples - 1);
      const Eigen::Vector3d a = along_u ? surface.point(domain.u_min, domain.v_at(t))
                                        : surface.point(domain.u_at(t), domain.v_min);
      const Eigen::Vector3d b = along_u ? surface.point(domain.u_max, domain.v_at(t))
                                        : surface.point(domain.u_at(t), domain.v_max);
      if ((a - b).norm() > limit) {
        return false;
      }
    }
    return true;
  };
  // Poles: every sample of one edge curve is the same point
  auto collapsed = [&](bool u_edge, double value) {
    const Eigen::Vector3d first =
        u_edge ? surface.point(value, domain.v_min) : surface.point(domain.u_min, value);
    for (int k = 1; k < kSamples; ++k) {
      const double t = static_cast<double>(k) / (kSamples - 1);
      const Eigen::Vector3d x =
          u_edge ? surface.point(value, domain.v_at(t)) : surface.point(domain.u_at(t), value);
      if ((x - first).norm() > limit) {
        return false;
      }
    }
    return true;
  };
  domain.periodic_u = surface.knots_u().is_periodic() || same_edges(true);
  domain.periodic_v = surface.knots_v().is_periodic() || same_edges(false);
  if (!domain.periodic_u) {
    domain.pole_u_min = collapsed(true, domain.u_min);
    domain.pole_u_max = collapsed(true, domain.u_max);
  }
  if (!domain.periodic_v) {
    domain.pole_v_min = collapsed(false, domain.v_min);
    domain.pole_v_max = collapsed(false, domain.v_max);
  }
  return domain;
}

ParametricSurface parametric_surface(const NurbsSurface& surface) {
  return parametric_surface(surface, nurbs_parameter_domain(surface));
}

ParametricSurface parametric_surface(const NurbsSurface& surface, const ParameterDomain& domain) {
  return ParametricSurface(
      domain, [surface](double u, double v) { return surface.point(u, v); },
      [surface](double u, double v) { return surface.unit_normal(u, v); },
      NormalOrientation::kSuCrossSv);
}

ParameterDomain superquadric_parameter_domain() {
  ParameterDomain domain;
  domain.u_min = -std::numbers::pi / 2.0;
  domain.u_max = std::numbers::pi / 2.0;
  domain.v_min = -std::numbers::pi;
  domain.v_max = std::numbers::pi;
  domain.periodic_v = true;
  domain.pole_u_min = true;
  domain.pole_u_max = true;
  return domain;
}

ParametricSurface parametric_surface(const DeformableSuperquadricShape& shape) {
  return ParametricSurface(
      superquadric_parameter_domain(), [shape](double u, double v) { return shape.point(u, v); },
      [shape](double u, double v) { return shape.unit_normal(u, v); },
      NormalOrientation::kSvCrossSu);
}

}  // namespace dnurbs
