#include "dnurbs/dynamics/dnurbs/rational_control_net_model.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/core/error.h"
#include "dnurbs/core/kronecker.h"
#include "dnurbs/dynamics/core/quadrature_assembly.h"

namespace dnurbs {

RationalControlNetModel::RationalControlNetModel(WeightMode mode, int control_point_count,
                                                 double minimum_weight)
    : mode_(mode),
      per_control_point_(coordinates_per_control_point(mode)),
      control_point_count_(control_point_count),
      minimum_weight_(minimum_weight) {}

namespace {

// The default weight regularization (rational_control_net_model.h, "Well-posed free weights"):
// m_w and k_w as multiples of the mean diagonal of the weight rows of M and K at the initial state.
constexpr double kWeightInertiaScale = 10.0;
constexpr double kWeightStiffnessScale = 2.0;

double checked_regularization(const char* name, double value) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw make_error(name, " ", value, " is not a non-negative finite number");
  }
  return value;
}

// The mean of the entries of `values` at `indices` (0 for none).
double mean_at(const double* values, const std::vector<int>& indices) {
  double sum = 0.0;
  for (const int index : indices) {
    sum += values[index];
  }
  return indices.empty() ? 0.0 : sum / static_cast<double>(indices.size());
}

}  // namespace

void RationalControlNetModel::build_coordinates(const Eigen::MatrixX3d& control_points,
                                                const Eigen::VectorXd& weights,
                                                const SparseMatrix& scalar_pattern,
                                                std::optional<double> weight_inertia,
                                                std::optional<double> weight_stiffness,
                                                bool fix_weight_gauge) {
  initial_coordinates_.resize(coordinate_count());
  for (int i = 0; i < control_point_count_; ++i) {
    initial_coordinates_.segment<3>(i * per_control_point_) = control_points.row(i).transpose();
    if (mode_ == WeightMode::kFree) {
      initial_coordinates_[i * 4 + 3] = weights[i];
    }
  }
  if (mode_ == WeightMode::kFixed) {
    // Fixed weights: the scalar matrices and their S (x) I_3 expansion, once
    fixed_weights_ = weights;
    assemble_scalar(scalar_);
    expanded_.mass = kronecker_identity(scalar_.mass, 3);
    expanded_.damping = kronecker_identity(scalar_.damping, 3);
    expanded_.stiffness = kronecker_identity(scalar_.stiffness, 3);
    reference_gradient_ = expanded_.stiffness * initial_coordinates_;
    reference_energy_ = quadrature_potential_energy(initial_coordinates_);
    return;
  }
  // Free weights: the anchor of the weights, the 4 x 4 block pattern and the value index of each
  // weight's diagonal entry
  anchor_weights_ = weights;
  block_pattern_ = dense_block_pattern(scalar_pattern, 4);
  const auto* outer = scalar_pattern.outerIndexPtr();
  const auto* inner = scalar_pattern.innerIndexPtr();
  for (int i = 0; i < control_point_count_; ++i) {
    const auto* found = std::lower_bound(inner + outer[i], inner + outer[i + 1], i);
    weight_diagonal_.push_back(dense_block_value_index(
        block_pattern_, scalar_pattern, static_cast<int>(found - inner), i, 3, 3, 4));
  }
  // The weight regularization (file comment): explicit values, or scale-aware ones from the
  // mean weight diagonals of M and K at the initial state (assembled without regularization)
  if (weight_inertia) {
    weight_inertia_ = checked_regularization("weight inertia", *weight_inertia);
    weight_stiffness_ = checked_regularization("weight stiffness", weight_stiffness.value_or(0.0));
  } else {
    ModelMatrices natural;
    assemble_free(initial_coordinates_, natural);
    weight_inertia_ = kWeightInertiaScale * mean_at(natural.mass.valuePtr(), weight_diagonal_);
    weight_stiffness_ =
        weight_stiffness
            ? checked_regularization("weight stiffness", *weight_stiffness)
            : kWeightStiffnessScale * mean_at(natural.stiffness.valuePtr(), weight_diagonal_);
  }
  if (fix_weight_gauge) {
    fix_weight(0);
  }
}

void RationalControlNetModel::add_weight_regularization(ModelMatrices& matrices) const {
  for (const int index : weight_diagonal_) {
    matrices.mass.valuePtr()[index] += weight_inertia_;
    matrices.stiffness.valuePtr()[index] += weight_stiffness_;
  }
}

void RationalControlNetModel::add_weight_anchor_force(ConstVectorRef q, VectorRef force) const {
  if (mode_ != WeightMode::kFree) {
    return;
  }
  for (int i = 0; i < control_point_count_; ++i) {
    force[4 * i + 3] -= weight_stiffness_ * (q[4 * i + 3] - anchor_weights_[i]);
  }
}

double RationalControlNetModel::weight_anchor_energy(ConstVectorRef q) const {
  double energy = 0.0;
  if (mode_ != WeightMode::kFree) {
    return energy;
  }
  for (int i = 0; i < control_point_count_; ++i) {
    const double stretch = q[4 * i + 3] - anchor_weights_[i];
    energy += 0.5 * weight_stiffness_ * stretch * stretch;
  }
  return energy;
}

double RationalControlNetModel::potential_energy(ConstVectorRef q) const {
  if (mode_ == WeightMode::kFree) {
    return quadrature_potential_energy(q) + weight_anchor_energy(q);
  }
  check_coordinates(q);
  // With d = q - q0: E(q) = E(q0) + d^T K q0 + (1/2) d^T K d exactly, K = S_K (x) I_3 constant.
  return reference_energy_ + (q - initial_coordinates_).dot(reference_gradient_) +
         0.5 *
             kronecker_quadratic_form_of_difference(scalar_.stiffness, q, initial_coordinates_, 3);
}

void RationalControlNetModel::start_tangent_columns(int active_count,
                                                    TangentKinematics& tangents) const {
  const int count = active_count * per_control_point_;
  tangents.columns.resize(static_cast<size_t>(count));
  tangents.ju.setZero(3, count);
  tangents.jv.setZero(3, count);
  tangents.su_rate.setZero();
  tangents.sv_rate.setZero();
  tangents.su_bias.setZero();
  tangents.sv_bias.setZero();
}

void RationalControlNetModel::add_tangent_columns(int slot, int point, double basis_u,
                                                  double basis_v, const Eigen::Vector3d& weight_u,
                                                  const Eigen::Vector3d& weight_v,
                                                  ConstVectorRef qd,
                                                  TangentKinematics& tangents) const {
  const int offset = point * per_control_point_;
  const int column = slot * per_control_point_;
  const Eigen::Vector3d point_rate = qd.segment<3>(offset);
  tangents.su_rate += basis_u * point_rate;
  tangents.sv_rate += basis_v * point_rate;
  for (int r = 0; r < 3; ++r) {
    tangents.columns[static_cast<size_t>(column + r)] = offset + r;
    tangents.ju(r, column + r) = basis_u;
    tangents.jv(r, column + r) = basis_v;
  }
  if (mode_ == WeightMode::kFree) {
    tangents.columns[static_cast<size_t>(column + 3)] = offset + 3;
    tangents.ju.col(column + 3) = weight_u;
    tangents.jv.col(column + 3) = weight_v;
    tangents.su_rate += weight_u * qd[offset + 3];
    tangents.sv_rate += weight_v * qd[offset + 3];
  }
}

void RationalControlNetModel::check_coordinates(ConstVectorRef q) const {
  if (q.size() != coordinate_count()) {
    throw make_error("coordinate vector has ", q.size(), " entries, the model has ",
                     coordinate_count());
  }
}

void RationalControlNetModel::check_velocity(ConstVectorRef qd) const {
  if (qd.size() != velocity_count()) {
    throw make_error("velocity vector has ", qd.size(), " entries, the model has ",
                     velocity_count());
  }
}

Eigen::Vector3d free_weight_acceleration(const RationalPoint& point, ConstVectorRef qd) {
  double weight_rate = 0.0;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d mixed = Eigen::Vector3d::Zero();
  for (int a = 0; a < point.count; ++a) {
    const int offset = point.control_point[a] * 4;
    const Eigen::Vector3d point_rate = qd.segment<3>(offset);
    const double w_rate = qd[offset + 3];
    weight_rate += point.value(a) * w_rate;
    velocity += point.rational_value(a) * point_rate + point.weight_column_of(a) * w_rate;
    mixed += point.value(a) * w_rate * point_rate;
  }
  return 2.0 / point.weight_sum * (mixed - weight_rate * velocity);
}

// ---------------------------------------------------------------------------------------------
// Point kinematics and point forces (Terzopoulos 2003, eqs. 1.22-1.23: x = J q with the rational
// basis as J, and f_q = J^T f)

Eigen::Vector3d RationalControlNetModel::position(ConstVectorRef q,
                                                  const Eigen::Vector2d& u) const {
  Eigen::Vector3d x;
  visit_rational_point(q, u, false, [&](const RationalPoint& point) { x = point.point; });
  return x;
}

SparseMatrix RationalControlNetModel::position_jacobian(ConstVectorRef q,
                                                        const Eigen::Vector2d& u) const {
  const bool free = mode_ == WeightMode::kFree;
  std::vector<Eigen::Triplet<double>> triplets;
  visit_rational_point(q, u, free, [&](const RationalPoint& point) {
    triplets.reserve(static_cast<size_t>(point.count * (free ? 6 : 3)));
    for (int a = 0; a < point.count; ++a) {
      const int offset = point.control_point[a] * per_control_point_;
      for (int r = 0; r < 3; ++r) {
        triplets.emplace_back(r, offset + r, point.rational_value(a));
        if (free) {
          triplets.emplace_back(r, offset + 3, point.weight_column_of(a)[r]);
        }
      }
    }
  });
  SparseMatrix L(3, velocity_count());
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

Eigen::Vector3d RationalControlNetModel::jacobian_rate_times_velocity(
    ConstVectorRef q, ConstVectorRef qd, const Eigen::Vector2d& u) const {
  if (mode_ == WeightMode::kFixed) {
    return Eigen::Vector3d::Zero();
  }
  check_velocity(qd);
  Eigen::Vector3d rate;
  visit_rational_point(
      q, u, true, [&](const RationalPoint& point) { rate = free_weight_acceleration(point, qd); });
  return rate;
}

void RationalControlNetModel::add_point_force(ConstVectorRef q, const Eigen::Vector2d& u,
                                              const Eigen::Vector3d& f, VectorRef force) const {
  const bool free = mode_ == WeightMode::kFree;
  visit_rational_point(q, u, free, [&](const RationalPoint& point) {
    for (int a = 0; a < point.count; ++a) {
      const int offset = point.control_point[a] * per_control_point_;
      force.segment<3>(offset) += point.rational_value(a) * f;
      if (free) {
        force[offset + 3] += point.weight_column_of(a).dot(f);
      }
    }
  });
}

// ---------------------------------------------------------------------------------------------
// Matrices

const ModelMatrices* RationalControlNetModel::constant_matrices() const {
  return mode_ == WeightMode::kFixed ? &expanded_ : nullptr;
}

const ModelMatrices* RationalControlNetModel::scalar_matrices() const {
  return mode_ == WeightMode::kFixed ? &scalar_ : nullptr;
}

void RationalControlNetModel::assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const {
  if (mode_ == WeightMode::kFixed) {
    matrices = expanded_;
    return;
  }
  assemble_free(q, matrices);
}

void RationalControlNetModel::project_state(Eigen::Ref<Eigen::VectorXd> q,
                                            Eigen::Ref<Eigen::VectorXd> qd) const {
  if (mode_ == WeightMode::kFixed) {
    return;
  }
  for (int i = 0; i < control_point_count_; ++i) {
    double& w = q[4 * i + 3];
    if (w < minimum_weight_) {
      w = minimum_weight_;
      qd[4 * i + 3] = std::max(qd[4 * i + 3], 0.0);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Control points

int RationalControlNetModel::control_point_offset(int i) const {
  if (i < 0 || i >= control_point_count_) {
    throw make_error("control point index ", i, " is outside 0..", control_point_count_ - 1);
  }
  return i * per_control_point_;
}

int RationalControlNetModel::weight_offset(int i) const {
  if (mode_ != WeightMode::kFree) {
    throw make_error("weight ", i, " is not a coordinate (weights are fixed)");
  }
  return control_point_offset(i) + 3;
}

void RationalControlNetModel::fix_control_point(int i) {
  const int offset = control_point_offset(i);
  for (int c = 0; c < 3; ++c) {
    fix_coordinate(offset + c);
  }
}

void RationalControlNetModel::fix_point(int i) {
  if (i < 0 || i >= control_point_count_) {
    throw make_error("control point ", i, " does not exist (the model has ", control_point_count_,
                     ")");
  }
  fix_control_point(i);
}

void RationalControlNetModel::coordinate_lower_bounds(VectorRef lower) const {
  if (mode_ != WeightMode::kFree) {
    return;
  }
  for (int c = 0; c < control_point_count_; ++c) {
    lower[weight_offset(c)] = minimum_weight_;
  }
}

void RationalControlNetModel::fix_weight(int i) {
  fix_coordinate(weight_offset(i));
}

Eigen::MatrixX3d RationalControlNetModel::control_points(ConstVectorRef q) const {
  check_coordinates(q);
  Eigen::MatrixX3d points(control_point_count_, 3);
  for (int i = 0; i < control_point_count_; ++i) {
    points.row(i) = q.segment<3>(i * per_control_point_).transpose();
  }
  return points;
}

Eigen::VectorXd RationalControlNetModel::weights(ConstVectorRef q) const {
  check_coordinates(q);
  if (mode_ == WeightMode::kFixed) {
    return fixed_weights_;
  }
  Eigen::VectorXd result(control_point_count_);
  for (int i = 0; i < control_point_count_; ++i) {
    result[i] = q[4 * i + 3];
  }
  return result;
}

void RationalControlNetModel::set_rest_shape(ConstVectorRef q_rest) {
  check_coordinates(q_rest);
  for (Eigen::Index i = 0; i < q_rest.size(); ++i) {
    if (!std::isfinite(q_rest[i])) {
      throw make_error("rest shape: coordinate ", i, " is ", q_rest[i], " (not finite)");
    }
  }
  if (mode_ == WeightMode::kFree) {
    for (int i = 0; i < control_point_count_; ++i) {
      if (q_rest[4 * i + 3] < minimum_weight_) {
        throw make_error("rest shape: weight ", i, " is ", q_rest[4 * i + 3],
                         ", below the minimum weight ", minimum_weight_);
      }
    }
  }
  store_rest_derivatives(q_rest);
  rest_coordinates_ = q_rest;
  if (mode_ == WeightMode::kFixed) {
    // f_int = -K (q - q_r) and E(q) expanded about q0 with gradient K (q0 - q_r)
    rest_force_ = expanded_.stiffness * q_rest;
    reference_gradient_ = expanded_.stiffness * initial_coordinates_ - rest_force_;
    reference_energy_ = quadrature_potential_energy(initial_coordinates_);
  } else {
    for (int i = 0; i < control_point_count_; ++i) {
      anchor_weights_[i] = q_rest[4 * i + 3];
    }
  }
}

void RationalControlNetModel::set_plastic_flow(const std::optional<PlasticFlow>& flow) {
  if (flow) {
    check_plastic_flow(*flow);
    if (!has_rest_shape()) {
      set_rest_shape(initial_coordinates_);
    }
  }
  plastic_flow_ = flow;
}

int RationalControlNetModel::flow_rest_shape(ConstVectorRef q, double dt) {
  if (!plastic_flow_) {
    return 0;
  }
  check_coordinates(q);
  Eigen::VectorXd rest = rest_coordinates_;
  const int yielded = flow_rest_positions(*plastic_flow_, dt, per_control_point_, q, rest);
  if (yielded > 0) {
    set_rest_shape(rest);
  }
  return yielded;
}

Eigen::VectorXd RationalControlNetModel::flowing_rest_coordinates() const {
  return plastic_flow_ ? rest_coordinates_ : Eigen::VectorXd();
}

void RationalControlNetModel::restore_flowing_rest_coordinates(ConstVectorRef rest) {
  if (!plastic_flow_) {
    Model::restore_flowing_rest_coordinates(rest);
  }
  set_rest_shape(rest);
}

}  // namespace dnurbs
