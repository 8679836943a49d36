// The deformable superquadric's dynamics (Terzopoulos, "Deformable Models", eqs. 1.37-1.38):
// M, D, K by quadrature, the internal and inertial forces and distributed applied forces.

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

// Matrices ---------------------------------------------------------------------------------------

const ModelMatrices* DeformableSuperquadricModel::constant_matrices() const {
  return constant_ ? &constant_matrices_ : nullptr;
}

void DeformableSuperquadricModel::assemble_dense_mass(const State& state, Eigen::MatrixXd& mass_rr,
                                                      Eigen::MatrixXd& coupling) const {
  const int nr = rigid_count_;
  const int nd = velocity_count_ - nr;
  mass_rr.setZero(nr, nr);
  coupling.setZero(nr, nd);
  const bool translation = settings_.parts.translation;
  const bool rotation = settings_.parts.rotation;
  if (rigid_) {
    // Precomputed mass properties (body frame): M = [[m I, -R [m c_m]_x], [[m c_m]_x R^T, I_o]].
    const RigidMassProperties& props = rigid_properties_;
    const Eigen::Matrix3d coupling_cw =
        -state.rotation * cross_matrix(props.mass * props.centre_of_mass);
    int w = 0;
    if (translation) {
      mass_rr.topLeftCorner<3, 3>() = props.mass * Eigen::Matrix3d::Identity();
      w = 3;
    }
    if (rotation) {
      mass_rr.block<3, 3>(w, w) = props.inertia_about_origin;
      if (translation) {
        mass_rr.block<3, 3>(0, 3) = coupling_cw;
        mass_rr.block<3, 3>(3, 0) = coupling_cw.transpose();
      }
    }
    return;
  }
  // Terzopoulos 2003, eq. 1.38: M = integral mu L^T L dA = integral mu (R^T L)^T (R^T L) dA
  // (accumulated in fixed-capacity storage: no allocation per point)
  BodyJacobian lb(3, nr);
  DenseBlock block = DenseBlock::Zero(nr, nr);
  for_each_point(state, true, [&](const PointKinematics& pt) {
    body_jacobian(state.rotation, pt.p, pt.jacobian, translation, rotation, free_shape_, lb);
    block.noalias() += pt.mass * (lb.transpose() * lb);
    if (pt.fe != nullptr) {
      for (int a = 0; a < pt.fe->active_count; ++a) {
        coupling.middleCols<3>(node_offset(*pt.fe, a)) +=
            (pt.mass * pt.fe->value[a]) * lb.transpose();
      }
    }
  });
  mass_rr = block;
}

void DeformableSuperquadricModel::assemble_matrices(ConstVectorRef q,
                                                    ModelMatrices& matrices) const {
  if (constant_ && constant_matrices_.mass.rows() == velocity_count_) {
    matrices = constant_matrices_;
    return;
  }
  const State state = decode(q);
  Eigen::MatrixXd mass_rr;
  Eigen::MatrixXd coupling;
  assemble_dense_mass(state, mass_rr, coupling);
  for (Eigen::Index i = 0; i < shape_regularization_.size(); ++i) {
    const Eigen::Index row = shape_velocity_offset_ + i;
    mass_rr(row, row) += shape_regularization_[i];
  }

  // Fill the values of the fixed pattern (M_dd is constant and already in it).
  SparseMatrix& mass = matrices.mass;
  const bool fits = mass.rows() == velocity_count_ && mass.cols() == velocity_count_ &&
                    mass.isCompressed() && mass.nonZeros() == mass_pattern_.nonZeros() &&
                    std::equal(mass.outerIndexPtr(), mass.outerIndexPtr() + velocity_count_ + 1,
                               mass_pattern_.outerIndexPtr()) &&
                    std::equal(mass.innerIndexPtr(), mass.innerIndexPtr() + mass.nonZeros(),
                               mass_pattern_.innerIndexPtr());
  if (!fits) {
    mass = mass_pattern_;
  }
  const int nr = rigid_count_;
  for (int j = 0; j < velocity_count_; ++j) {
    for (SparseMatrix::InnerIterator it(mass, j); it; ++it) {
      const auto i = static_cast<int>(it.row());
      if (i < nr && j < nr) {
        it.valueRef() = mass_rr(i, j);
      } else if (i < nr) {
        it.valueRef() = coupling(i, j - nr);
      } else if (j < nr) {
        it.valueRef() = coupling(j, i - nr);
      }
    }
  }

  // K is constant; D = alpha M + beta K (Terzopoulos 2003, below eq 1.38).
  matrices.stiffness = stiffness_;
  const double alpha = settings_.damping_alpha;
  const double beta = settings_.damping_beta;
  if (alpha == 0.0 && beta == 0.0) {
    matrices.damping.resize(velocity_count_, velocity_count_);
    matrices.damping.setZero();
  } else {
    matrices.damping = alpha * mass + beta * stiffness_;
  }
}

// Forces -----------------------------------------------------------------------------------------

void DeformableSuperquadricModel::add_internal_force(ConstVectorRef q, VectorRef force) const {
  // f_int = -K (q - q_rest): the q_s springs toward the rest shape, the q_d energy toward d = 0.
  for (size_t i = 0; i < free_shape_.size(); ++i) {
    const int k = free_shape_[i];
    const int index = shape_velocity_offset_ + static_cast<int>(i);
    force[index] -= settings_.shape_stiffness[k] *
                    (q[shape_coordinate_offset_ + static_cast<int>(i)] - rest_shape_[k]);
  }
  if (settings_.parts.local) {
    const int nd = mesh_.coordinate_count();
    force.segment(local_velocity_offset_, nd).noalias() -=
        local_stiffness_ * q.segment(local_coordinate_offset_, nd);
  }
}

double DeformableSuperquadricModel::potential_energy(ConstVectorRef q) const {
  double energy = 0.0;
  for (size_t i = 0; i < free_shape_.size(); ++i) {
    const int k = free_shape_[i];
    const double delta = q[shape_coordinate_offset_ + static_cast<int>(i)] - rest_shape_[k];
    energy += 0.5 * settings_.shape_stiffness[k] * delta * delta;
  }
  if (settings_.parts.local) {
    const int nd = mesh_.coordinate_count();
    const auto qd = q.segment(local_coordinate_offset_, nd);
    energy += 0.5 * qd.dot(local_stiffness_ * qd);
  }
  return energy;
}

void DeformableSuperquadricModel::add_inertial_force(ConstVectorRef q, ConstVectorRef qd,
                                                     VectorRef force) const {
  if (constant_) {
    return;  // L constant: Ldot = 0
  }
  const State state = decode(q);
  const bool translation = settings_.parts.translation;
  const bool rotation = settings_.parts.rotation;
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
  if (rotation) {
    omega = qd.segment<3>(rotation_velocity_offset_);
  }
  if (rigid_) {
    // g = -integral mu L^T R (w x (w x p)): -R (w x (w x m c_m)) and the gyroscopic -w x (I_o w).
    const RigidMassProperties& props = rigid_properties_;
    if (translation) {
      force.head<3>() -=
          state.rotation * omega.cross(omega.cross(props.mass * props.centre_of_mass));
    }
    force.segment<3>(rotation_velocity_offset_) -= omega.cross(props.inertia_about_origin * omega);
    return;
  }
  SuperquadricShapeParameters shape_rate = SuperquadricShapeParameters::Zero();
  for (size_t i = 0; i < free_shape_.size(); ++i) {
    shape_rate[free_shape_[i]] = qd[shape_velocity_offset_ + static_cast<int>(i)];
  }
  const double* local_rate = settings_.parts.local ? qd.data() + local_velocity_offset_ : nullptr;
  const DeformableSuperquadricShape shape = free_shape_.empty()
                                                ? DeformableSuperquadricShape()
                                                : DeformableSuperquadricShape(state.shape);
  BodyJacobian lb(3, rigid_count_);
  // Terzopoulos 2003, eq. 1.38: g = -integral mu L^T Ldot qd dA = -integral mu (R^T L)^T a_b dA
  for_each_point(state, true, [&](const PointKinematics& pt) {
    Eigen::Vector3d p_dot = pt.jacobian * shape_rate;
    if (pt.fe != nullptr) {
      for (int a = 0; a < pt.fe->active_count; ++a) {
        p_dot += pt.fe->value[a] *
                 Eigen::Map<const Eigen::Vector3d>(local_rate + node_offset(*pt.fe, a));
      }
    }
    Eigen::Vector3d body = omega.cross(omega.cross(pt.p)) + 2.0 * omega.cross(p_dot);
    if (!free_shape_.empty()) {
      const ParameterQuadraturePoint& point = points_[static_cast<size_t>(pt.index)];
      body += shape.jacobian_rate(point.u, point.v, shape_rate) * shape_rate;
    }
    body_jacobian(state.rotation, pt.p, pt.jacobian, translation, rotation, free_shape_, lb);
    force.head(rigid_count_).noalias() -= pt.mass * (lb.transpose() * body);
    if (pt.fe != nullptr) {
      for (int a = 0; a < pt.fe->active_count; ++a) {
        force.segment<3>(local_velocity_offset_ + node_offset(*pt.fe, a)) -=
            (pt.mass * pt.fe->value[a]) * body;
      }
    }
  });
}

void DeformableSuperquadricModel::add_distributed_force(ConstVectorRef q,
                                                        const ForceDensity& density,
                                                        VectorRef force) const {
  const State state = decode(q);
  const bool translation = settings_.parts.translation;
  const bool rotation = settings_.parts.rotation;
  BodyJacobian lb(3, rigid_count_);
  MaterialSample sample;
  // f_q = integral L^T f du dv (Terzopoulos 2003, below eq 1.38), f per unit parametric measure.
  for_each_point(state, !free_shape_.empty(), [&](const PointKinematics& pt) {
    const ParameterQuadraturePoint& point = points_[static_cast<size_t>(pt.index)];
    sample.parameter = Eigen::Vector2d(point.u, point.v);
    sample.position = state.centre + state.rotation * pt.p;
    sample.tangent_u = state.rotation * pt.p_u;
    sample.tangent_v = state.rotation * pt.p_v;
    sample.mass_density = pt.mass / point.weight;
    const Eigen::Vector3d body_force = state.rotation.transpose() * density(sample);
    body_jacobian(state.rotation, pt.p, pt.jacobian, translation, rotation, free_shape_, lb);
    force.head(rigid_count_).noalias() += point.weight * (lb.transpose() * body_force);
    if (pt.fe != nullptr) {
      for (int a = 0; a < pt.fe->active_count; ++a) {
        force.segment<3>(local_velocity_offset_ + node_offset(*pt.fe, a)) +=
            (point.weight * pt.fe->value[a]) * body_force;
      }
    }
  });
}

}  // namespace dnurbs
