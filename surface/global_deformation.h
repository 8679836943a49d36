#pragma once
// Global deformations T of deformable superquadrics (Terzopoulos 2003, eq. 1.30, s = T(e);
// DESIGN.md "Deformable superquadrics"; Metaxas & Terzopoulos 1993): tapering, bending, twisting
// and shearing along the body z axis, applied in that fixed order,
//   T = shear o twist o bend o taper.
// Each step gives its value and analytic derivatives with respect to the point it deforms
// (3 by 3), its own parameters (3 by k) and the half height h = a a3 that normalizes z
// (3 by 1), so that the chain rule composes them and carries d/da, d/da3 through h.
// No step changes z, so every step sees the superellipsoid's z = e3. A step whose parameters
// are all zero is the identity exactly (value, and I_3 as point derivative).
// Evaluation uses fixed-size Eigen types and never allocates.

#include <Eigen/Core>

namespace dnurbs {

/// Number of global deformation parameters.
inline constexpr int kGlobalDeformationParameterCount = 8;

/// The global deformation parameters in this order: 8-vector
/// (t1, t2, b1, b2, b3, tau, sx, sy):
///   t1, t2      tapering of x and y along z (dimensionless; 0 = none)
///   b1, b2, b3  bending: amplitude (length), offset along z (length), frequency (dimensionless)
///   tau         twist angle (radians) at z = h
///   sx, sy      shear of x and y by z (dimensionless)
using GlobalDeformationParameters = Eigen::Matrix<double, kGlobalDeformationParameterCount, 1>;

/// The positions of the global deformation parameters in a vector that holds them from index
/// Offset on: GlobalDeformationParameter (Offset 0) for GlobalDeformationParameters, and entries
/// 6..13 of the deformable superquadric's q_s (SuperquadricShapeParameter).
template <int Offset>
struct GlobalDeformationParameterIndices {
  enum : int {
    kTaper1 = Offset,
    kTaper2,
    kBendAmplitude,
    kBendOffset,
    kBendFrequency,
    kTwist,
    kShearX,
    kShearY,
  };
};

/// Indices into GlobalDeformationParameters.
using GlobalDeformationParameter = GlobalDeformationParameterIndices<0>;

/// One deformation step p' = T(p; theta, h) with its k parameters theta.
template <int ParameterCount>
struct DeformationStep {
  Eigen::Vector3d point;                                  ///< T(p)
  Eigen::Matrix3d d_point;                                ///< dT/dp, 3 by 3
  Eigen::Matrix<double, 3, ParameterCount> d_parameters;  ///< dT/dtheta, 3 by k
  Eigen::Vector3d d_half_height;                          ///< dT/dh, 3 by 1
};

/// How the arguments of a step move: the rates (time derivatives) of its point p, its k
/// parameters theta and the half height h.
template <int ParameterCount>
struct DeformationMotion {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< dp/dt
  Eigen::Matrix<double, ParameterCount, 1> parameters =
      Eigen::Matrix<double, ParameterCount, 1>::Zero();  ///< dtheta/dt
  double half_height = 0.0;                              ///< dh/dt
};

/// The rates of a step's value and derivatives along a DeformationMotion: the time derivatives
/// of T, dT/dp, dT/dtheta and dT/dh (second derivatives of T contracted with the motion). The
/// dynamic model needs them for Ldot, i.e. the rate of J = ds/dq_s.
template <int ParameterCount>
struct DeformationStepRate {
  Eigen::Vector3d point;                                  ///< dT/dt
  Eigen::Matrix3d d_point;                                ///< d(dT/dp)/dt, 3 by 3
  Eigen::Matrix<double, 3, ParameterCount> d_parameters;  ///< d(dT/dtheta)/dt, 3 by k
  Eigen::Vector3d d_half_height;                          ///< d(dT/dh)/dt, 3 by 1
};

/// Tapering: x' = (t1 z/h + 1) x, y' = (t2 z/h + 1) y, z' = z. Parameters (t1, t2).
DeformationStep<2> taper(const Eigen::Vector3d& p, double t1, double t2, double half_height);

/// Bending: x' = x + b1 cos((z + b2)/h * pi * b3), y' = y, z' = z. Parameters (b1, b2, b3).
DeformationStep<3> bend(const Eigen::Vector3d& p, double b1, double b2, double b3,
                        double half_height);

/// Twisting about z by the angle phi = tau z/h: (x', y') = R(phi) (x, y), z' = z.
/// Parameter (tau).
DeformationStep<1> twist(const Eigen::Vector3d& p, double tau, double half_height);

/// Linear shear by z: x' = x + sx z, y' = y + sy z, z' = z. Parameters (sx, sy); d_half_height
/// is zero.
DeformationStep<2> shear(const Eigen::Vector3d& p, double sx, double sy);

/// The rates of taper, bend, twist and shear (same arguments) along a motion of (p, theta, h).
DeformationStepRate<2> taper_rate(const Eigen::Vector3d& p, double t1, double t2,
                                  double half_height, const DeformationMotion<2>& motion);
DeformationStepRate<3> bend_rate(const Eigen::Vector3d& p, double b1, double b2, double b3,
                                 double half_height, const DeformationMotion<3>& motion);
DeformationStepRate<1> twist_rate(const Eigen::Vector3d& p, double tau, double half_height,
                                  const DeformationMotion<1>& motion);
DeformationStepRate<2> shear_rate(const Eigen::Vector3d& p, double sx, double sy,
                                  const DeformationMotion<2>& motion);

/// Throws Error naming the value unless every parameter is finite.
void validate_global_deformation_parameters(const GlobalDeformationParameters& parameters);

/// The composite T = shear o twist o bend o taper at p with its derivatives:
/// d_point = dT/dp (3 by 3), d_parameters = dT/d(t1, t2, b1, b2, b3, tau, sx, sy) (3 by 8),
/// d_half_height = dT/dh (3 by 1). h = a a3 must be positive (not checked here).
DeformationStep<kGlobalDeformationParameterCount> apply_global_deformation(
    const GlobalDeformationParameters& parameters, double half_height, const Eigen::Vector3d& p);

/// The composite together with its rates along a motion of (p, theta (8), h): `value` is what
/// apply_global_deformation returns, `rate` the time derivatives of all of it.
struct GlobalDeformationWithRate {
  DeformationStep<kGlobalDeformationParameterCount> value;
  DeformationStepRate<kGlobalDeformationParameterCount> rate;
};
GlobalDeformationWithRate apply_global_deformation_with_rate(
    const GlobalDeformationParameters& parameters, double half_height, const Eigen::Vector3d& p,
    const DeformationMotion<kGlobalDeformationParameterCount>& motion);

}  // namespace dnurbs
