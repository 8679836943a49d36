#pragma once
// The superellipsoid of deformable superquadrics (Terzopoulos 2003, eq. 1.30, the primitive e;
// DESIGN.md "Deformable superquadrics"):
//   e(u, v) = a [a1 C(u)^e1 C(v)^e2, a2 C(u)^e1 S(v)^e2, a3 S(u)^e1],
// u in [-pi/2, pi/2] (latitude), v in [-pi, pi) (longitude), with the signed powers of
// surface/signed_power.h. Evaluation uses fixed-size Eigen types and never allocates.

#include <Eigen/Core>

namespace dnurbs {

/// Number of superellipsoid parameters.
inline constexpr int kSuperellipsoidParameterCount = 6;

/// The superellipsoid parameters in this order: 6-vector (a, a1, a2, a3, e1, e2).
///   a       scale (> 0)
///   a1..a3  aspect ratios along x, y, z (> 0)
///   e1      squareness in latitude u (> 0), e2 squareness in longitude v (> 0)
using SuperellipsoidParameters = Eigen::Matrix<double, kSuperellipsoidParameterCount, 1>;

/// The positions of the superellipsoid parameters in a vector that holds them from index
/// Offset on: SuperellipsoidParameter (Offset 0) for SuperellipsoidParameters, and the first six
/// entries of the deformable superquadric's q_s (SuperquadricShapeParameter).
template <int Offset>
struct SuperellipsoidParameterIndices {
  enum : int { kScale = Offset, kAspect1, kAspect2, kAspect3, kSquareness1, kSquareness2 };
};

/// Indices into SuperellipsoidParameters.
using SuperellipsoidParameter = SuperellipsoidParameterIndices<0>;

/// The parameters of the sphere of the given radius: (r, 1, 1, 1, 1, 1).
SuperellipsoidParameters sphere_superellipsoid_parameters(double radius);

/// Throws Error naming the value unless every parameter is finite and positive. Exponents outside
/// [kMinSquareness, kMaxSquareness] are accepted (all results stay finite for any e > 0) but
/// that range is where the derivatives are tested.
void validate_superellipsoid_parameters(const SuperellipsoidParameters& parameters);

/// A point of the superellipsoid, its parametric derivatives and its parameter Jacobian.
struct SuperellipsoidEvaluation {
  Eigen::Vector3d point;                                             ///< e(u, v)
  Eigen::Vector3d d_u;                                               ///< de/du
  Eigen::Vector3d d_v;                                               ///< de/dv
  Eigen::Matrix<double, 3, kSuperellipsoidParameterCount> jacobian;  ///< de/d(a,a1,a2,a3,e1,e2)
};

/// e(u, v). Parameters are not validated here (see validate_superellipsoid_parameters).
Eigen::Vector3d superellipsoid_point(const SuperellipsoidParameters& parameters, double u,
                                     double v);

/// e(u, v), de/du, de/dv and the 3 by 6 Jacobian de/dparameters, all analytic. The
/// u-derivative is floored where cos u or sin u vanish and the exponent is below 1, the
/// v-derivative likewise (see kSignedPowerFloor): finite everywhere, exact elsewhere.
SuperellipsoidEvaluation evaluate_superellipsoid(const SuperellipsoidParameters& parameters,
                                                 double u, double v);

/// The rate of the Jacobian when the parameters move at `parameters_dot` (u, v fixed):
/// d/dt (de/dparameters) = sum_k d^2 e/(dparameters dparameters_k) parameters_dot_k, 3 by 6.
/// The dynamic model needs it for Ldot (Terzopoulos 2003, eq. 1.36).
Eigen::Matrix<double, 3, kSuperellipsoidParameterCount> superellipsoid_jacobian_rate(
    const SuperellipsoidParameters& parameters, double u, double v,
    const SuperellipsoidParameters& parameters_dot);

/// The inside-outside function
///   F(x) = ((x/(a a1))^(2/e2) + (y/(a a2))^(2/e2))^(e2/e1) + (z/(a a3))^(2/e1)
/// (powers of absolute values): < 1 inside, 1 on the surface, > 1 outside.
double superellipsoid_inside_outside(const SuperellipsoidParameters& parameters,
                                     const Eigen::Vector3d& point);

}  // namespace dnurbs
