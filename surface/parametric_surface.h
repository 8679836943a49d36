#pragma once
// A generic parametric surface S(u, v) over a parameter rectangle: what the uniform and the
// adaptive tessellations (Goldenstein et al. 2005, section 5: "a sampling function to evaluate the
// geometry of the surface at a vertex of the mesh") see of a NURBS surface, a superquadric, a
// deformed surface or a dynamic model. It carries the rectangle, which of its edges are identified
// (periodic directions, seams of closed surfaces) and which collapse to a single point (poles).

#include <functional>

#include <Eigen/Core>

#include "dnurbs/nurbs/nurbs_surface.h"
#include "dnurbs/surface/deformable_superquadric_shape.h"

namespace dnurbs {

/// The parameter rectangle [u_min, u_max] x [v_min, v_max] of a surface and its closures.
///
/// periodic_u: the edges u = u_min and u = u_max are the same curve of the surface (a periodic
/// direction or the seam of a closed clamped surface); a tessellation identifies them, so the
/// seam has no duplicated vertices and u_max itself is never sampled. Likewise periodic_v.
/// pole_u_min: the whole edge u = u_min is one point of the surface (the pole of a sphere);
/// a tessellation gives it a single vertex. Likewise pole_u_max, pole_v_min, pole_v_max.
/// A direction cannot be both periodic and bounded by a pole.
struct ParameterDomain {
  double u_min = 0.0;
  double u_max = 1.0;
  double v_min = 0.0;
  double v_max = 1.0;
  bool periodic_u = false;
  bool periodic_v = false;
  bool pole_u_min = false;
  bool pole_u_max = false;
  bool pole_v_min = false;
  bool pole_v_max = false;

  /// Throws Error naming the value unless the bounds are finite with u_min < u_max and
  /// v_min < v_max, and no direction is both periodic and bounded by a pole.
  void validate() const;
  /// u_min + (u_max - u_min) t, exactly u_max for t >= 1 (and likewise v_at). Every
  /// tessellation places its samples through these two functions, so meshes of different
  /// resolutions share bitwise-identical parameters where their samples coincide.
  double u_at(double t) const { return t >= 1.0 ? u_max : u_min + (u_max - u_min) * t; }
  double v_at(double t) const { return t >= 1.0 ? v_max : v_min + (v_max - v_min) * t; }
  /// The pole (0: u_min, 1: u_max, 2: v_min, 3: v_max) that (u, v) lies on exactly, or -1.
  int pole_at(double u, double v) const;
};

/// Which cross product of the parametric tangents the surface's unit normal follows.
enum class NormalOrientation {
  kSuCrossSv,  ///< n ~ S_u x S_v (NURBS surfaces)
  kSvCrossSu,  ///< n ~ S_v x S_u (the superquadric's (latitude, longitude) parameterization)
};

/// (u, v) -> a 3-vector: a surface point or a unit normal.
using SurfaceFunction = std::function<Eigen::Vector3d(double u, double v)>;

/// A surface S(u, v) over a ParameterDomain, a value type (the functions are copied with it).
///
/// The unit normal is the given normal function if there is one; otherwise it comes from
/// central differences of S (ParametricSurface::kDifferenceStep of the domain's extent, one-sided
/// steps kept inside the domain at open edges) as the normalized cross product named by the
/// orientation; on a pole it is the normalized mean of the difference normals on a ring of
/// parameters just off the pole. Tessellations wind their triangles so that the geometric
/// normal (b - a) x (c - a) points the same way.
class ParametricSurface {
 public:
  /// Relative step of the difference normals: truncation error ~ (step extent)^2 |S'''|, and
  /// rounding ~ 1e-16 / step relative, both near 1e-10 for a unit-sized surface.
  static constexpr double kDifferenceStep = 1e-5;

  /// Throws Error if the domain is invalid or `point` is empty.
  ParametricSurface(const ParameterDomain& domain, SurfaceFunction point,
                    SurfaceFunction unit_normal = {},
                    NormalOrientation orientation = NormalOrientation::kSuCrossSv);

  const ParameterDomain& domain() const { return domain_; }
  NormalOrientation orientation() const { return orientation_; }
  bool has_normal_function() const { return static_cast<bool>(normal_); }

  /// S(u, v), 3-vector. Throws Error if it is not finite.
  Eigen::Vector3d point(double u, double v) const;
  /// The unit normal at (u, v), 3-vector (see the class comment). Throws Error where it is
  /// undefined (vanishing tangents off the poles) or not finite.
  Eigen::Vector3d unit_normal(double u, double v) const;
  /// The unit normal from central differences of S, ignoring any normal function.
  Eigen::Vector3d difference_normal(double u, double v) const;

 private:
  ParameterDomain domain_;
  SurfaceFunction point_;
  SurfaceFunction normal_;
  NormalOrientation orientation_ = NormalOrientation::kSuCrossSv;
};

/// The domain of a NURBS surface with its closures detected: a periodic knot vector makes a
/// periodic direction; a clamped direction whose two edge curves coincide (at 9 sample
/// parameters, within `tolerance` times the control net's bounding-box diagonal) is a seam and
/// is made periodic too; an edge curve whose samples all coincide is a pole.
ParameterDomain nurbs_parameter_domain(const NurbsSurface& surface, double tolerance = 1e-10);

/// The NURBS surface as a ParametricSurface over nurbs_parameter_domain(surface), normals
/// NurbsSurface::unit_normal (its pole limit included).
ParametricSurface parametric_surface(const NurbsSurface& surface);
/// The same over a given domain (closures set by the caller; the rectangle may be a part of
/// the knot domain).
ParametricSurface parametric_surface(const NurbsSurface& surface, const ParameterDomain& domain);

/// The superquadric's domain: u in [-pi/2, pi/2] with poles at both ends, v in [-pi, pi)
/// periodic.
ParameterDomain superquadric_parameter_domain();

/// The superquadric reference shape s(u, v) as a ParametricSurface over
/// superquadric_parameter_domain(), normals DeformableSuperquadricShape::unit_normal (outward,
/// s_v x s_u, with its pole limit).
ParametricSurface parametric_surface(const DeformableSuperquadricShape& shape);

}  // namespace dnurbs
