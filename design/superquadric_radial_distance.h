#pragma once
// The radial distance of a point to a deformable superquadric's reference shape s = T(e)
// (Terzopoulos, "Deformable Models", eq. 1.30), the residual of the superquadric fit
// (design/superquadric_fitting.h). A body-frame point p is mapped back to the undeformed
// superellipsoid, e = T^-1(p), in closed form: every step of T = shear o twist o bend o taper
// (surface/global_deformation.h) keeps z, so each is undone at the point's own z:
//
//   unshear   x1 = p_x - sx z,           y1 = p_y - sy z
//   untwist   (x2, y2) = R(-tau z/h) (x1, y1)
//   unbend    x3 = x2 - b1 cos((z + b2)/h pi b3)
//   untaper   e = (x3 / (t1 z/h + 1), y2 / (t2 z/h + 1), z)          (h = A3, the half height)
//
// and the distance is measured along the ray from the body origin through e:
//
//   d = |e| (1 - F(e)^(-e1/2)),
//   F(e) = ((e_x/A1)^2/e2 + (e_y/A2)^2/e2)^(e2/e1) + (e_z/A3)^2/e1   (inside-outside function),
//
// positive outside. F is homogeneous of degree 2/e1, so e F^(-e1/2) is the point of the
// superellipsoid on that ray (superquadric_radial_projection).

#include <Eigen/Core>

#include "dnurbs/surface/deformable_superquadric_shape.h"

namespace dnurbs {

/// The partial derivatives of the body-frame radial distance.
struct SuperquadricRadialDistanceGradient {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< dd/dp, 3-vector
  Eigen::Vector3d size = Eigen::Vector3d::Zero();   ///< dd/d(A1, A2, A3)
  double e1 = 0.0;                                  ///< dd/de1
  double e2 = 0.0;                                  ///< dd/de2
  /// dd/d(t1, t2, b1, b2, b3, tau, sx, sy), 8-vector ordered like GlobalDeformationParameters.
  GlobalDeformationParameters deformation = GlobalDeformationParameters::Zero();
};

/// Radial distance of the body-frame point p to the superquadric with sizes `size` =
/// (A1, A2, A3) (all > 0, not checked), squareness e1, e2 and global deformation `deformation`
/// (8-vector, GlobalDeformationParameters), and, if `gradient` is not null, its analytic partial
/// derivatives (zero where the distance is a guard constant: a taper factor t z/h + 1 at or below
/// 1e-9 gives 10 max(A), a point at the origin -min(A)).
double superquadric_body_radial_distance(const Eigen::Vector3d& size, double e1, double e2,
                                         const GlobalDeformationParameters& deformation,
                                         const Eigen::Vector3d& p,
                                         SuperquadricRadialDistanceGradient* gradient = nullptr);

/// Radial distance of world point x to the superquadric (shape, centre, rotation), positive
/// outside, with p = rotation^T (x - centre) and sizes a (a1, a2, a3).
double superquadric_radial_distance(const SuperquadricShapeParameters& shape,
                                    const Eigen::Vector3d& centre, const Eigen::Matrix3d& rotation,
                                    const Eigen::Vector3d& x);

/// The material point (u, v) of the reference shape that the radial distance measures to: the
/// superellipsoid point e F(e)^(-e1/2) on the ray through e = T^-1(p), for the body-frame point p,
/// in the parameters of surface/superellipsoid.h,
///   sin u = S(u) = sign(e_z) |e_z/A3|^(1/e1),  cos u = ((|e_x|/A1)^(2/e2) +
///   (|e_y|/A2)^(2/e2))^(e2/2e1), v = atan2(sign(e_y) |e_y/A2|^(1/e2), sign(e_x) |e_x/A1|^(1/e2))
/// (evaluated at the projected point). s(u, v) is then that projected point mapped by T. Throws
/// Error where the ray is undefined (p maps to the body origin, or a taper factor is <= 0).
Eigen::Vector2d superquadric_radial_projection(const SuperquadricShapeParameters& shape,
                                               const Eigen::Vector3d& p);

}  // namespace dnurbs
