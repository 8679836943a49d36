// The deformable superquadric's kinematics (Terzopoulos, "Deformable Models", eqs. 1.34-1.36):
// points, Jacobians and their rates, mass properties and momenta at a state.

#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/core/rotation.h"
#include "dnurbs/dynamics/superquadric/superquadric_point_kinematics.h"

namespace dnurbs {

using namespace superquadric_detail;  // NOLINT(google-build-using-namespace): internal names

// Kinematics -------------------------------------------------------------------------------------

Eigen::Vector3d DeformableSuperquadricModel::position(ConstVectorRef q,
                                                      const Eigen::Vector2d& u) const {
  const State state = decode(q);
  Eigen::Vector3d p = DeformableSuperquadricShape(state.shape).point(u.x(), u.y());
  if (state.local != nullptr) {
    const FeShapeValues fe = mesh_.shape_values(u.x(), u.y());
    for (int a = 0; a < fe.active_count; ++a) {
      p += fe.value[a] * Eigen::Map<const Eigen::Vector3d>(state.local + node_offset(fe, a));
    }
  }
  // Terzopoulos 2003, eq. 1.35: x = c + R (s + d)
  return state.centre + state.rotation * p;
}

SparseMatrix DeformableSuperquadricModel::position_jacobian(ConstVectorRef q,
                                                            const Eigen::Vector2d& u) const {
  const State state = decode(q);
  const SuperquadricShapeEvaluation e =
      DeformableSuperquadricShape(state.shape).evaluate(u.x(), u.y());
  Eigen::Vector3d p = e.point;
  const FeShapeValues fe =
      state.local != nullptr ? mesh_.shape_values(u.x(), u.y()) : FeShapeValues{};
  if (state.local != nullptr) {
    for (int a = 0; a < fe.active_count; ++a) {
      p += fe.value[a] * Eigen::Map<const Eigen::Vector3d>(state.local + node_offset(fe, a));
    }
  }
  BodyJacobian lb(3, rigid_count_);
  body_jacobian(state.rotation, p, e.jacobian, settings_.parts.translation,
                settings_.parts.rotation, free_shape_, lb);
  // Terzopoulos 2003, eq. 1.36: L = R [R^T, -[p]_x, J, S] = [I, B, R J, R S]
  const Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxRigidCount> l = state.rotation * lb;
  SparseMatrix result(3, velocity_count_);
  result.reserve(Eigen::VectorXi::Constant(velocity_count_, 3));
  for (int j = 0; j < rigid_count_; ++j) {
    for (int i = 0; i < 3; ++i) {
      if (l(i, j) != 0.0) {
        result.insert(i, j) = l(i, j);
      }
    }
  }
  for (int a = 0; a < fe.active_count; ++a) {
    const int column = local_velocity_offset_ + node_offset(fe, a);
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) {
        const double value = fe.value[a] * state.rotation(i, j);
        if (value != 0.0) {
          result.coeffRef(i, column + j) += value;
        }
      }
    }
  }
  result.makeCompressed();
  return result;
}

Eigen::Vector3d DeformableSuperquadricModel::jacobian_rate_times_velocity(
    ConstVectorRef q, ConstVectorRef qd, const Eigen::Vector2d& u) const {
  const State state = decode(q);
  const DeformableSuperquadricShape shape(state.shape);
  const SuperquadricShapeEvaluation e = shape.evaluate(u.x(), u.y());
  Eigen::Vector3d p = e.point;
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
  if (settings_.parts.rotation) {
    omega = qd.segment<3>(rotation_velocity_offset_);
  }
  SuperquadricShapeParameters shape_rate = SuperquadricShapeParameters::Zero();
  for (size_t i = 0; i < free_shape_.size(); ++i) {
    shape_rate[free_shape_[i]] = qd[shape_velocity_offset_ + static_cast<int>(i)];
  }
  Eigen::Vector3d p_dot = e.jacobian * shape_rate;
  if (state.local != nullptr) {
    const FeShapeValues fe = mesh_.shape_values(u.x(), u.y());
    for (int a = 0; a < fe.active_count; ++a) {
      const int node = node_offset(fe, a);
      p += fe.value[a] * Eigen::Map<const Eigen::Vector3d>(state.local + node);
      p_dot += fe.value[a] * qd.segment<3>(local_velocity_offset_ + node);
    }
  }
  Eigen::Vector3d body = omega.cross(omega.cross(p)) + 2.0 * omega.cross(p_dot);
  if (!free_shape_.empty()) {
    body += shape.jacobian_rate(u.x(), u.y(), shape_rate) * shape_rate;
  }
  return state.rotation * body;
}

// Mass properties and momenta ---------------------------------------------------------------------

RigidMassProperties DeformableSuperquadricModel::mass_properties(ConstVectorRef q) const {
  const State state = decode(q);
  RigidMassProperties props;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  for_each_point(state, false, [&](const PointKinematics& pt) {
    const Eigen::Matrix3d px = cross_matrix(pt.p);
    props.mass += pt.mass;
    first_moment += pt.mass * pt.p;
    props.inertia_about_origin.noalias() += pt.mass * px.transpose() * px;
  });
  props.centre_of_mass = first_moment / props.mass;
  const Eigen::Matrix3d cx = cross_matrix(props.centre_of_mass);
  props.inertia_about_centre = props.inertia_about_origin - props.mass * cx.transpose() * cx;
  return props;
}

Eigen::Vector3d DeformableSuperquadricModel::centre_of_mass(ConstVectorRef q) const {
  const State state = decode(q);
  return state.centre + state.rotation * mass_properties(q).centre_of_mass;
}

template <typename Visitor>
void DeformableSuperquadricModel::for_each_point_motion(const State& state, ConstVectorRef qd,
                                                        Visitor&& visit) const {
  BodyJacobian lb(3, rigid_count_);
  for_each_point(state, !free_shape_.empty(), [&](const PointKinematics& pt) {
    // Terzopoulos 2003, eq. 1.36: xdot = L qd = R (R^T L) qd, the body-frame part from the
    // dense block [R^T, -[p]_x, J] and the local part from S q_d.
    body_jacobian(state.rotation, pt.p, pt.jacobian, settings_.parts.translation,
                  settings_.parts.rotation, free_shape_, lb);
    Eigen::Vector3d body = lb * qd.head(rigid_count_);
    if (pt.fe != nullptr) {
      for (int a = 0; a < pt.fe->active_count; ++a) {
        body += pt.fe->value[a] * qd.segment<3>(local_velocity_offset_ + node_offset(*pt.fe, a));
      }
    }
    visit(pt.mass, state.centre + state.rotation * pt.p, state.rotation * body);
  });
}

Eigen::Vector3d DeformableSuperquadricModel::linear_momentum(ConstVectorRef q,
                                                             ConstVectorRef qd) const {
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
  for_each_point_motion(
      decode(q), qd, [&](double mass, const Eigen::Vector3d& /*x*/, const Eigen::Vector3d& x_dot) {
        momentum += mass * x_dot;
      });
  return momentum;
}

Eigen::Vector3d DeformableSuperquadricModel::angular_momentum(ConstVectorRef q,
                                                              ConstVectorRef qd) const {
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
  for_each_point_motion(decode(q), qd,
                        [&](double mass, const Eigen::Vector3d& x, const Eigen::Vector3d& x_dot) {
                          momentum += mass * x.cross(x_dot);
                        });
  return momentum;
}

}  // namespace dnurbs
