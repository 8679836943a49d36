#pragma once
// Shapes and states shared by the superquadric dynamics tests.

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"

namespace dnurbs::test {

using Shape = SuperquadricShapeParameter;

/// q_s of the undeformed superellipsoid a (a1, a2, a3) with exponents e1, e2.
inline SuperquadricShapeParameters superellipsoid(double a, double a1, double a2, double a3,
                                                  double e1, double e2) {
  SuperquadricShapeParameters q = SuperquadricShapeParameters::Zero();
  q << a, a1, a2, a3, e1, e2, 0, 0, 0, 0, 0, 0, 0, 0;
  return q;
}

/// A shape with every global deformation switched on (small values).
inline SuperquadricShapeParameters deformed_shape(double e1, double e2) {
  SuperquadricShapeParameters q = superellipsoid(1.3, 1.1, 0.8, 1.2, e1, e2);
  q[Shape::kTaper1] = 0.2;
  q[Shape::kTaper2] = -0.15;
  q[Shape::kBendAmplitude] = 0.1;
  q[Shape::kBendOffset] = 0.3;
  q[Shape::kBendFrequency] = 0.4;
  q[Shape::kTwist] = 0.3;
  q[Shape::kShearX] = 0.1;
  q[Shape::kShearY] = -0.05;
  return q;
}

/// Parts with every coordinate free: rigid motion, all 14 q_s entries and q_d.
inline DeformableSuperquadricParts every_part() {
  DeformableSuperquadricParts parts = DeformableSuperquadricParts::full();
  parts.shape.fill(true);
  return parts;
}

inline Eigen::Quaterniond some_rotation() {
  return Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()));
}

/// A deterministic pseudo-random vector in [-1, 1]^n.
inline Eigen::VectorXd pattern_vector(int n, double seed) {
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) {
    v[i] = std::sin(12.9898 * (i + 1) + seed * 78.233);
  }
  return v;
}

}  // namespace dnurbs::test
