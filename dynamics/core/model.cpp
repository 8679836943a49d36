#include "dnurbs/dynamics/core/model.h"

#include <algorithm>

#include "dnurbs/core/error.h"
#include "dnurbs/core/kronecker.h"

namespace dnurbs {

Eigen::Vector3d Model::jacobian_rate_times_velocity(ConstVectorRef /*q*/, ConstVectorRef /*qd*/,
                                                    const Eigen::Vector2d& /*u*/) const {
  return Eigen::Vector3d::Zero();
}

void Model::add_internal_force(ConstVectorRef q, VectorRef force) const {
  ModelMatrices matrices;
  const ModelMatrices* used = constant_matrices();
  if (used == nullptr) {
    assemble_matrices(q, matrices);
    used = &matrices;
  }
  force.noalias() -= used->stiffness * q;
}

double Model::potential_energy(ConstVectorRef q) const {
  ModelMatrices matrices;
  const ModelMatrices* used = constant_matrices();
  if (used == nullptr) {
    assemble_matrices(q, matrices);
    used = &matrices;
  }
  return 0.5 * q.dot(used->stiffness * q);
}

double Model::kinetic_energy(ConstVectorRef q, ConstVectorRef qd) const {
  if (q.size() != coordinate_count() || qd.size() != velocity_count()) {
    throw make_error("kinetic energy: q has ", q.size(), " entries and qd ", qd.size(),
                     ", the model has ", coordinate_count(), " coordinates and ", velocity_count(),
                     " velocities");
  }
  const ModelMatrices* scalar = scalar_matrices();
  const int block = kronecker_block_size();
  if (scalar != nullptr && matrices_are_constant() && block > 0 &&
      qd.size() == scalar->mass.rows() * block) {
    // M = S_M (x) I_b: one pass over the scalar matrix (core/kronecker.h)
    return 0.5 * kronecker_quadratic_form(scalar->mass, qd, block);
  }
  if (const ModelMatrices* constant = constant_matrices()) {
    return 0.5 * qd.dot(constant->mass * qd);
  }
  ModelMatrices matrices;
  assemble_matrices(q, matrices);
  return 0.5 * qd.dot(matrices.mass * qd);
}

void Model::add_inertial_force(ConstVectorRef /*q*/, ConstVectorRef /*qd*/,
                               VectorRef /*force*/) const {}

void Model::assemble_step(ConstVectorRef q, ConstVectorRef qd, bool inertial,
                          ModelMatrices& matrices, VectorRef force) const {
  assemble_matrices(q, matrices);
  add_internal_force(q, force);
  if (inertial) {
    add_inertial_force(q, qd, force);
  }
}

void Model::add_step_residual(ConstVectorRef q, ConstVectorRef qd, ConstVectorRef a, bool inertial,
                              VectorRef force) const {
  ModelMatrices matrices;
  assemble_step(q, qd, inertial, matrices, force);
  if (matrices.damping.nonZeros() > 0) {
    force.noalias() -= matrices.damping * qd;
  }
  force.noalias() -= matrices.mass * a;
}

void Model::add_point_force(ConstVectorRef q, const Eigen::Vector2d& u, const Eigen::Vector3d& f,
                            VectorRef force) const {
  force += position_jacobian(q, u).transpose() * f;
}

void Model::advance_coordinates(ConstVectorRef q, ConstVectorRef dv,
                                Eigen::Ref<Eigen::VectorXd> q_out) const {
  q_out = q + dv;
}

void Model::project_state(Eigen::Ref<Eigen::VectorXd> /*q*/,
                          Eigen::Ref<Eigen::VectorXd> /*qd*/) const {}

int Model::control_point_offset(int i) const {
  throw make_error("control point ", i, " requested from a model without control points");
}

void Model::tangent_kinematics(ConstVectorRef /*q*/, ConstVectorRef /*qd*/,
                               const Eigen::Vector2d& /*u*/,
                               TangentKinematics& /*tangents*/) const {
  throw make_error("this model (parametric dimension ", parametric_dimension(),
                   ") gives no surface tangents and their Jacobians");
}

void Model::semi_implicit_matrices(ConstVectorRef q, bool scalar, ModelMatrices& matrices) const {
  if (scalar) {
    if (scalar_matrices() == nullptr) {
      throw make_error("this model has no scalar (node by node) matrices");
    }
    matrices = *scalar_matrices();
  } else {
    assemble_matrices(q, matrices);
  }
}

int Model::velocity_coordinate(int velocity) const {
  return coordinate_count() == velocity_count() ? velocity : -1;
}

void Model::coordinate_lower_bounds(VectorRef /*lower*/) const {}

ParameterDomain Model::parameter_domain(ConstVectorRef /*q*/) const {
  throw make_error("this model (parametric dimension ", parametric_dimension(),
                   ") has no known parameter domain");
}

std::optional<Shape> Model::exact_shape(ConstVectorRef /*q*/) const {
  return std::nullopt;
}

int Model::flow_rest_shape(ConstVectorRef /*q*/, double /*dt*/) {
  return 0;
}

bool Model::set_material_parameters(ConstVectorRef values) {
  throw make_error("material parameters: ", values.size(),
                   " given, but this model's material is fixed (it has no keyable parameters)");
}

void Model::restore_flowing_rest_coordinates(ConstVectorRef rest) {
  throw make_error("rest coordinates: ", rest.size(),
                   " given, but this model's rest shape does not flow (it has none to restore)");
}

void Model::fix_point(int i) {
  const int nodes = coordinate_count() / 3;
  if (i < 0 || i >= nodes) {
    throw make_error("node ", i, " does not exist (the model has ", nodes, ")");
  }
  const int offset = control_point_offset(i);
  for (int k = 0; k < 3; ++k) {
    fix_coordinate(offset + k);
  }
}

void Model::fix_border() {
  throw make_error("this model has no border to fix (parametric dimension ", parametric_dimension(),
                   ")");
}

int Model::freeze_outside(const SculptedRegion& /*region*/, int /*margin*/) {
  throw make_error("this model does not support local sculpting");
}

void Model::fix_coordinate(int index) {
  if (index < 0 || index >= velocity_count()) {
    throw make_error("fixed coordinate index ", index, " is outside 0..", velocity_count() - 1);
  }
  const auto position =
      std::lower_bound(fixed_coordinates_.begin(), fixed_coordinates_.end(), index);
  if (position == fixed_coordinates_.end() || *position != index) {
    fixed_coordinates_.insert(position, index);
  }
}

}  // namespace dnurbs
