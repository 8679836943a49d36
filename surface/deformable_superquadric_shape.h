#pragma once
// The reference shape of a deformable superquadric (Terzopoulos 2003, eqs. 1.30-1.31):
//   s(u, v) = T(e(u, v; a, a1, a2, a3, e1, e2); t1, t2, b1, b2, b3, tau, sx, sy)
// with the superellipsoid e of surface/superellipsoid.h and the global deformation
// T = shear o twist o bend o taper of surface/global_deformation.h, whose z is normalized by the
// half height h = a a3. It gives s, its tangents, its Jacobian J = ds/dq_s (the J of Terzopoulos
// 2003 eqs 1.34-1.36) and its outward unit normal. Evaluation never allocates.
//
// For the dynamic model, x = c + R (s + d) (eq 1.35) and L = [I, B, R J, R S] (eq 1.36):
// evaluate(u, v) gives s and J, ParametricFeMesh gives d and S,
// unit_normal(u, v, d_u, d_v) gives the normal of s + d, and jacobian_rate(u, v, q_s_dot)
// gives Jdot for Ldot in the inertial force g = -integral mu L^T Ldot qdot.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "dnurbs/surface/global_deformation.h"
#include "dnurbs/surface/superellipsoid.h"

namespace dnurbs {

/// Number of reference-shape parameters q_s.
inline constexpr int kSuperquadricShapeParameterCount =
    kSuperellipsoidParameterCount + kGlobalDeformationParameterCount;  // 14

/// q_s, the reference-shape coordinates of Terzopoulos 2003, eq. 1.31, in this order (14-vector):
///   0 a    1 a1   2 a2   3 a3   4 e1   5 e2        superellipsoid (SuperellipsoidParameters)
///   6 t1   7 t2                                    tapering
///   8 b1   9 b2  10 b3                             bending
///  11 tau                                          twisting
///  12 sx  13 sy                                    shearing
/// i.e. the superellipsoid's 6 followed by GlobalDeformationParameters' 8.
using SuperquadricShapeParameters = Eigen::Matrix<double, kSuperquadricShapeParameterCount, 1>;

/// Indices into SuperquadricShapeParameters: the superellipsoid's names at their own positions
/// (SuperquadricShapeParameter::kScale == SuperellipsoidParameter::kScale) and the global
/// deformation's shifted past them (SuperquadricShapeParameter::kTwist ==
/// kSuperellipsoidParameterCount + GlobalDeformationParameter::kTwist).
struct SuperquadricShapeParameter
    : SuperellipsoidParameterIndices<0>,
      GlobalDeformationParameterIndices<kSuperellipsoidParameterCount> {};
static_assert(SuperquadricShapeParameter::kShearY == kSuperquadricShapeParameterCount - 1);

/// A point of the reference shape with its derivatives.
struct SuperquadricShapeEvaluation {
  Eigen::Vector3d point;                                                ///< s(u, v), body frame
  Eigen::Vector3d d_u;                                                  ///< ds/du
  Eigen::Vector3d d_v;                                                  ///< ds/dv
  Eigen::Matrix<double, 3, kSuperquadricShapeParameterCount> jacobian;  ///< J = ds/dq_s, 3 by 14
};

/// The outward unit normal of a (u latitude, v longitude) parameterization from its tangents:
/// normalize(d_v x d_u) (for the sphere d_u x d_v points inwards). Returns false and leaves
/// `normal` untouched where the cross product is zero or not finite.
bool outward_unit_normal(const Eigen::Vector3d& d_u, const Eigen::Vector3d& d_v,
                         Eigen::Vector3d& normal);

/// True where u is a pole: |cos u| <= kSignedPowerZero, so every v gives the same point.
bool is_superquadric_pole(double u);

/// The deformable superquadric's reference shape s(u, v; q_s), a value type.
class DeformableSuperquadricShape {
 public:
  /// The unit sphere, no deformation.
  DeformableSuperquadricShape();
  /// Throws Error (naming the value) unless a, a1, a2, a3, e1, e2 are finite and positive and
  /// the deformation parameters are finite.
  explicit DeformableSuperquadricShape(const SuperquadricShapeParameters& parameters);

  /// The undeformed sphere of the given radius: q_s = (r, 1, 1, 1, 1, 1, 0, ..., 0).
  static DeformableSuperquadricShape sphere(double radius);
  /// q_s from its two parts.
  static SuperquadricShapeParameters combine(const SuperellipsoidParameters& superellipsoid,
                                             const GlobalDeformationParameters& deformation);

  const SuperquadricShapeParameters& parameters() const { return parameters_; }
  /// Replaces q_s after validating it as the constructor does (the object is unchanged if it
  /// throws).
  void set_parameters(const SuperquadricShapeParameters& parameters);
  SuperellipsoidParameters superellipsoid_parameters() const {
    return parameters_.head<kSuperellipsoidParameterCount>();
  }
  GlobalDeformationParameters global_deformation_parameters() const {
    return parameters_.tail<kGlobalDeformationParameterCount>();
  }
  /// h = a a3, the half height that normalizes z in the deformations.
  double half_height() const;

  /// s(u, v), 3-vector.
  Eigen::Vector3d point(double u, double v) const;
  /// s, ds/du, ds/dv and J = ds/dq_s (3 by 14), all analytic (chain rule through T, including
  /// the dependence of T on a and a3 through h). Finite for every u, v (see kSignedPowerFloor).
  SuperquadricShapeEvaluation evaluate(double u, double v) const;

  /// Jdot = d/dt J(u, v) when q_s moves at q_s_dot (u, v fixed):
  /// sum_k d^2 s/(dq_s dq_s_k) q_s_dot_k, 3 by 14, analytic. The dynamic model's Ldot
  /// (Terzopoulos 2003, eq. 1.36) has R Jdot + Rdot J in the q_s block; Jdot q_s_dot is the
  /// velocity-dependent acceleration of s.
  Eigen::Matrix<double, 3, kSuperquadricShapeParameterCount> jacobian_rate(
      double u, double v, const SuperquadricShapeParameters& q_s_dot) const;

  /// The outward unit normal of s at (u, v): normalize(s_v x s_u).
  ///
  /// At the poles (is_superquadric_pole(u)) s_v = 0 and the normal comes from the limit
  /// instead: the undeformed superellipsoid has the normal +-z there (it is symmetric under
  /// x -> -x and y -> -y), and T maps normals by its point derivative F: n = |det F| F^-T (+-z),
  /// computed as +-sign(det F) (F e_x x F e_y). This is the exact limit where a tangent plane
  /// exists (e1 < 2); for e1 >= 2 the pole is a cone point or spike and this is a convention.
  /// Throws Error where the normal is undefined (vanishing tangents off the poles, or a
  /// deformation that collapses the pole's tangent plane).
  Eigen::Vector3d unit_normal(double u, double v) const;

  /// The outward unit normal of p = s + d, for a displacement d with derivatives d_u, d_v (from
  /// ParametricFeMesh): normalize(p_v x p_u), with the pole fallback of unit_normal(u, v) (a
  /// C0 displacement has no tangent plane at a pole). Throws Error where undefined.
  Eigen::Vector3d unit_normal(double u, double v, const Eigen::Vector3d& displacement_d_u,
                              const Eigen::Vector3d& displacement_d_v) const;

 private:
  Eigen::Vector3d pole_normal(double u, double v) const;

  SuperquadricShapeParameters parameters_;
};

}  // namespace dnurbs
