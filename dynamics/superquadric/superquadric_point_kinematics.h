#pragma once
// Internal to the deformable superquadric's implementation files
// (dynamics/superquadric/deformable_superquadric_*.cpp): the decoded state, the body-frame
// kinematics of one quadrature point and the loop over the quadrature points that matrices,
// forces and momenta share. Not part of the public API.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/core/rotation.h"
#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"

namespace dnurbs {
namespace superquadric_detail {

using Parameter = SuperquadricShapeParameter;
constexpr int kShapeCount = kSuperquadricShapeParameterCount;
/// Largest number of velocities in the dense block of M: c (3), w (3), q_s (14).
constexpr int kMaxRigidCount = 6 + kShapeCount;
/// The body-frame Jacobian R^T L restricted to the dense block: [R^T, -[p]_x, J_free].
using BodyJacobian = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxRigidCount>;
using ShapeJacobian = Eigen::Matrix<double, 3, kShapeCount>;
/// The dense (c, w, q_s) block of M.
using DenseBlock =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxRigidCount, kMaxRigidCount>;

/// Offset in q_d of the displacement of the a-th active node.
inline std::ptrdiff_t node_offset(const FeShapeValues& fe, int a) {
  return 3 * static_cast<std::ptrdiff_t>(fe.node[static_cast<size_t>(a)]);
}

/// One quadrature point's body-frame kinematics.
struct PointKinematics {
  int index = 0;
  double mass = 0.0;
  Eigen::Vector3d p;       ///< s + d
  Eigen::Vector3d p_u;     ///< dp/du
  Eigen::Vector3d p_v;     ///< dp/dv
  ShapeJacobian jacobian;  ///< J = ds/dq_s (only where q_s has free entries)
  const FeShapeValues* fe = nullptr;
};

/// The dense block of R^T L at a point (Terzopoulos 2003, eq. 1.36 in the body frame):
/// [R^T (translation), -[p]_x (rotation), J_free (shape)].
inline void body_jacobian(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& p,
                          const ShapeJacobian& jacobian, bool translation, bool rotation_on,
                          const std::vector<int>& free_shape, BodyJacobian& lb) {
  int column = 0;
  if (translation) {
    lb.middleCols<3>(column) = rotation.transpose();
    column += 3;
  }
  if (rotation_on) {
    lb.middleCols<3>(column) = -cross_matrix(p);
    column += 3;
  }
  for (const int k : free_shape) {
    lb.col(column++) = jacobian.col(k);
  }
}

}  // namespace superquadric_detail

struct DeformableSuperquadricModel::State {
  Eigen::Vector3d centre;
  Eigen::Matrix3d rotation;
  SuperquadricShapeParameters shape;
  const double* local = nullptr;  ///< q_d (3 #nodes) or nullptr
};

// Per-point kinematics (the definition every implementation file of the model shares)
// ---------------------------------------------------------------------------

template <typename Visitor>
void DeformableSuperquadricModel::for_each_point(const State& state, bool need_jacobian,
                                                 Visitor&& visit) const {
  using superquadric_detail::node_offset;
  using superquadric_detail::PointKinematics;
  const bool cached = !point_reference_.empty();
  const DeformableSuperquadricShape shape =
      cached ? DeformableSuperquadricShape() : DeformableSuperquadricShape(state.shape);
  PointKinematics point;
  point.jacobian.setZero();
  for (size_t k = 0; k < points_.size(); ++k) {
    point.index = static_cast<int>(k);
    point.mass = point_mass_[k];
    if (cached) {
      point.p = point_reference_[k].col(0);
      point.p_u = point_reference_[k].col(1);
      point.p_v = point_reference_[k].col(2);
    } else {
      const SuperquadricShapeEvaluation e = shape.evaluate(points_[k].u, points_[k].v);
      point.p = e.point;
      point.p_u = e.d_u;
      point.p_v = e.d_v;
      if (need_jacobian) {
        point.jacobian = e.jacobian;
      }
    }
    // Terzopoulos 2003, eq. 1.32: d = S q_d
    if (state.local != nullptr) {
      const FeShapeValues& fe = point_shape_values_[k];
      point.fe = &fe;
      for (int a = 0; a < fe.active_count; ++a) {
        const Eigen::Map<const Eigen::Vector3d> node(state.local + node_offset(fe, a));
        point.p += fe.value[a] * node;
        point.p_u += fe.d_u[a] * node;
        point.p_v += fe.d_v[a] * node;
      }
    }
    visit(point);
  }
}

}  // namespace dnurbs
