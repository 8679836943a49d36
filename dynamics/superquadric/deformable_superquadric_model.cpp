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
#include "dnurbs/dynamics/superquadric/superquadric_quadrature.h"
#include "dnurbs/surface/signed_power.h"

namespace dnurbs {

using namespace superquadric_detail;  // NOLINT(google-build-using-namespace): internal names

namespace {

void check_finite(double value, const char* name) {
  if (!std::isfinite(value)) {
    throw make_error("deformable superquadric ", name, " ", value, " is not finite");
  }
}

}  // namespace

// Construction ----------------------------------------------------------------------------------

DeformableSuperquadricModel::DeformableSuperquadricModel(const SuperquadricShapeParameters& shape,
                                                         const Eigen::Vector3d& centre,
                                                         const Eigen::Quaterniond& orientation,
                                                         DeformableSuperquadricSettings settings)
    : settings_(std::move(settings)),
      initial_shape_(shape),
      initial_centre_(centre),
      mesh_(settings_.mesh_cells_u, settings_.mesh_cells_v) {
  validate(shape, centre, orientation);
  lay_out(shape, centre);
  // Quadrature tables: Terzopoulos 2003, eq. 1.38, M = integral mu L^T L dA with dA = |s_u x s_v|
  // du dv of the reference shape
  points_ = superquadric_quadrature_points(mesh_, shape, settings_.quadrature_points,
                                           settings_.graded_quadrature);
  build_point_tables(shape);
  build_constant_matrices();
  build_shape_regularization(shape);
  if (constant_) {
    assemble_matrices(initial_coordinates_, constant_matrices_);
  }
}

void DeformableSuperquadricModel::validate(const SuperquadricShapeParameters& shape,
                                           const Eigen::Vector3d& centre,
                                           const Eigen::Quaterniond& orientation) {
  for (int k = 0; k < kShapeCount; ++k) {
    check_finite(shape[k], superquadric_parameter_name(k));
  }
  for (int k = Parameter::kScale; k <= Parameter::kAspect3; ++k) {
    if (!(shape[k] > 0.0)) {
      throw make_error("deformable superquadric ", superquadric_parameter_name(k), " = ", shape[k],
                       " must be positive");
    }
  }
  for (int k = Parameter::kSquareness1; k <= Parameter::kSquareness2; ++k) {
    if (!(shape[k] >= kMinSquareness && shape[k] <= kMaxSquareness)) {
      throw make_error("deformable superquadric ", superquadric_parameter_name(k), " = ", shape[k],
                       " is outside [", kMinSquareness, ", ", kMaxSquareness, "]");
    }
  }
  for (int i = 0; i < 3; ++i) {
    check_finite(centre[i], "centre coordinate");
  }
  const double norm = orientation.norm();
  if (!std::isfinite(norm) || std::abs(norm - 1.0) > 1e-6) {
    throw make_error("deformable superquadric orientation quaternion (", orientation.w(), ", ",
                     orientation.x(), ", ", orientation.y(), ", ", orientation.z(), ") has norm ",
                     norm, ", not 1 (to 1e-6)");
  }
  initial_orientation_ = orientation.normalized();
  // (the quadrature order and the FE stiffness are validated by ParametricFeMesh)
  validate_superquadric_settings(settings_);
  rest_shape_ = settings_.rest_shape.value_or(shape);
}

void DeformableSuperquadricModel::lay_out(const SuperquadricShapeParameters& shape,
                                          const Eigen::Vector3d& centre) {
  const DeformableSuperquadricParts& parts = settings_.parts;
  for (int k = 0; k < kShapeCount; ++k) {
    if (parts.shape[static_cast<size_t>(k)]) {
      free_shape_.push_back(k);
    }
  }
  const int shape_free = static_cast<int>(free_shape_.size());
  const int local_count = parts.local ? mesh_.coordinate_count() : 0;
  rigid_ = shape_free == 0 && !parts.local;
  constant_ = !parts.rotation && shape_free == 0;
  int coordinate = parts.translation ? 3 : 0;
  int velocity = coordinate;
  if (parts.rotation) {
    quaternion_offset_ = coordinate;
    rotation_velocity_offset_ = velocity;
    coordinate += 4;
    velocity += 3;
  }
  if (shape_free > 0) {
    shape_coordinate_offset_ = coordinate;
    shape_velocity_offset_ = velocity;
    coordinate += shape_free;
    velocity += shape_free;
  }
  rigid_count_ = velocity;
  if (parts.local) {
    local_coordinate_offset_ = coordinate;
    local_velocity_offset_ = velocity;
    coordinate += local_count;
    velocity += local_count;
  }
  coordinate_count_ = coordinate;
  velocity_count_ = velocity;
  if (velocity_count_ == 0) {
    throw make_error(
        "deformable superquadric has no free part (translation, rotation, shape and "
        "local deformations are all switched off)");
  }
  initial_coordinates_ = Eigen::VectorXd::Zero(coordinate_count_);
  if (parts.translation) {
    initial_coordinates_.head<3>() = centre;
  }
  if (parts.rotation) {
    initial_coordinates_.segment<4>(quaternion_offset_) << initial_orientation_.w(),
        initial_orientation_.x(), initial_orientation_.y(), initial_orientation_.z();
  }
  for (int i = 0; i < shape_free; ++i) {
    initial_coordinates_[shape_coordinate_offset_ + i] = shape[free_shape_[static_cast<size_t>(i)]];
  }
}

void DeformableSuperquadricModel::build_point_tables(const SuperquadricShapeParameters& shape) {
  const bool local = settings_.parts.local;
  const bool cache_reference = free_shape_.empty();
  const DeformableSuperquadricShape reference(shape);
  point_mass_.resize(points_.size());
  if (local) {
    point_shape_values_.resize(points_.size());
  }
  if (cache_reference) {
    point_reference_.resize(points_.size());
  }
  RigidMassProperties& props = rigid_properties_;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < points_.size(); ++k) {
    const ParameterQuadraturePoint& point = points_[k];
    const SuperquadricShapeEvaluation e = reference.evaluate(point.u, point.v);
    const double area = e.d_u.cross(e.d_v).norm();
    point_mass_[k] = point.weight * settings_.mass_density * area;
    if (!std::isfinite(point_mass_[k])) {
      throw make_error("deformable superquadric area element at (u, v) = (", point.u, ", ", point.v,
                       ") is not finite");
    }
    if (local) {
      point_shape_values_[k] = mesh_.shape_values(point.u, point.v);
    }
    if (cache_reference) {
      point_reference_[k].col(0) = e.point;
      point_reference_[k].col(1) = e.d_u;
      point_reference_[k].col(2) = e.d_v;
    }
    // Rigid mass properties of the reference shape (body frame).
    const Eigen::Matrix3d px = cross_matrix(e.point);
    props.mass += point_mass_[k];
    first_moment += point_mass_[k] * e.point;
    props.inertia_about_origin.noalias() += point_mass_[k] * px.transpose() * px;
  }
  props.centre_of_mass = first_moment / props.mass;
  const Eigen::Matrix3d cx = cross_matrix(props.centre_of_mass);
  props.inertia_about_centre = props.inertia_about_origin - props.mass * cx.transpose() * cx;
}

void DeformableSuperquadricModel::build_constant_matrices() {
  const int local_count = settings_.parts.local ? mesh_.coordinate_count() : 0;
  // Local mass M_dd = integral mu S^T S dA = m_ab (x) I3 (constant: R^T R = I), regularized
  if (settings_.parts.local) {
    std::vector<Eigen::Triplet<double>> triplets;
    for (size_t k = 0; k < points_.size(); ++k) {
      const FeShapeValues& fe = point_shape_values_[k];
      for (int a = 0; a < fe.active_count; ++a) {
        for (int b = 0; b < fe.active_count; ++b) {
          const double value = point_mass_[k] * fe.value[a] * fe.value[b];
          for (int i = 0; i < 3; ++i) {
            triplets.emplace_back(3 * fe.node[static_cast<size_t>(a)] + i,
                                  3 * fe.node[static_cast<size_t>(b)] + i, value);
          }
        }
      }
    }
    local_mass_.resize(local_count, local_count);
    local_mass_.setFromTriplets(triplets.begin(), triplets.end());
    for (int i = 0; i < local_count; ++i) {
      local_mass_.coeffRef(i, i) *= 1.0 + settings_.regularization;
    }
    local_mass_.makeCompressed();
  }
  // Stiffness K: diagonal on the free q_s, the FE membrane + spring on q_d
  std::vector<Eigen::Triplet<double>> triplets;
  for (size_t i = 0; i < free_shape_.size(); ++i) {
    const double k = settings_.shape_stiffness[free_shape_[i]];
    const int row = shape_velocity_offset_ + static_cast<int>(i);
    triplets.emplace_back(row, row, k);
  }
  if (settings_.parts.local) {
    local_stiffness_ = mesh_.stiffness_matrix(settings_.local_stiffness);
    for (Eigen::Index j = 0; j < local_stiffness_.outerSize(); ++j) {
      for (SparseMatrix::InnerIterator it(local_stiffness_, j); it; ++it) {
        triplets.emplace_back(local_velocity_offset_ + static_cast<int>(it.row()),
                              local_velocity_offset_ + static_cast<int>(it.col()), it.value());
      }
    }
  }
  stiffness_.resize(velocity_count_, velocity_count_);
  stiffness_.setFromTriplets(triplets.begin(), triplets.end());
  stiffness_.makeCompressed();
  // The structure of M: a dense block over (c, w, q_s), dense coupling rows to q_d, M_dd
  const int nr = rigid_count_;
  Eigen::VectorXi sizes(velocity_count_);
  for (int j = 0; j < velocity_count_; ++j) {
    sizes[j] = j < nr ? velocity_count_ : nr + static_cast<int>(local_mass_.col(j - nr).nonZeros());
  }
  mass_pattern_.resize(velocity_count_, velocity_count_);
  mass_pattern_.reserve(sizes);
  for (int j = 0; j < velocity_count_; ++j) {
    for (int i = 0; i < nr; ++i) {
      mass_pattern_.insert(i, j) = 0.0;
    }
    if (j < nr) {
      for (int i = nr; i < velocity_count_; ++i) {
        mass_pattern_.insert(i, j) = 0.0;
      }
    } else {
      for (SparseMatrix::InnerIterator it(local_mass_, j - nr); it; ++it) {
        mass_pattern_.insert(nr + static_cast<int>(it.row()), j) = it.value();
      }
    }
  }
  mass_pattern_.makeCompressed();
}

void DeformableSuperquadricModel::build_shape_regularization(
    const SuperquadricShapeParameters& shape) {
  // Regularization of the free q_s (constant, from the reference state)
  const auto shape_free = static_cast<int>(free_shape_.size());
  shape_regularization_ = Eigen::VectorXd::Zero(shape_free);
  if (shape_free == 0) {
    return;
  }
  Eigen::MatrixXd mass_rr;
  Eigen::MatrixXd coupling;
  assemble_dense_mass(decode(initial_coordinates_), mass_rr, coupling);
  const double h =
      shape[Parameter::kScale] * std::max({shape[Parameter::kAspect1], shape[Parameter::kAspect2],
                                           shape[Parameter::kAspect3]});
  for (int i = 0; i < shape_free; ++i) {
    const int row = shape_velocity_offset_ + i;
    shape_regularization_[i] =
        settings_.regularization * (mass_rr(row, row) + rigid_properties_.mass * h * h);
  }
}

std::unique_ptr<Model> DeformableSuperquadricModel::clone() const {
  return std::make_unique<DeformableSuperquadricModel>(*this);
}

// State decoding ---------------------------------------------------------------------------------

DeformableSuperquadricModel::State DeformableSuperquadricModel::decode(ConstVectorRef q) const {
  if (q.size() != coordinate_count_) {
    throw make_error("deformable superquadric coordinate vector has ", q.size(),
                     " entries, expected ", coordinate_count_);
  }
  State state;
  state.centre = centre(q);
  state.rotation = orientation(q).toRotationMatrix();
  state.shape = shape_parameters(q);
  state.local = settings_.parts.local ? q.data() + local_coordinate_offset_ : nullptr;
  return state;
}

Eigen::Vector3d DeformableSuperquadricModel::centre(ConstVectorRef q) const {
  return settings_.parts.translation ? Eigen::Vector3d(q.head<3>()) : initial_centre_;
}

Eigen::Quaterniond DeformableSuperquadricModel::orientation(ConstVectorRef q) const {
  if (!settings_.parts.rotation) {
    return initial_orientation_;
  }
  return unit_quaternion(q.segment<4>(quaternion_offset_));
}

SuperquadricShapeParameters DeformableSuperquadricModel::shape_parameters(ConstVectorRef q) const {
  SuperquadricShapeParameters shape = initial_shape_;
  for (size_t i = 0; i < free_shape_.size(); ++i) {
    shape[free_shape_[i]] = q[shape_coordinate_offset_ + static_cast<int>(i)];
  }
  return shape;
}

// Coordinates ------------------------------------------------------------------------------------

void DeformableSuperquadricModel::advance_coordinates(ConstVectorRef q, ConstVectorRef dv,
                                                      Eigen::Ref<Eigen::VectorXd> q_out) const {
  // Everything but the quaternion is a vector space: the velocity block adds to its coordinates.
  int coordinate = 0;
  int velocity = 0;
  if (settings_.parts.translation) {
    q_out.head<3>() = q.head<3>() + dv.head<3>();
    coordinate = velocity = 3;
  }
  if (settings_.parts.rotation) {
    // R <- R exp([dw]_x): the quaternion product q (x) exp(dw), renormalized.
    const auto w = q.segment<4>(quaternion_offset_);
    const Eigen::Quaterniond current(w[0], w[1], w[2], w[3]);
    const Eigen::Quaterniond next =
        (current * quaternion_exp(dv.segment<3>(rotation_velocity_offset_))).normalized();
    q_out.segment<4>(quaternion_offset_) << next.w(), next.x(), next.y(), next.z();
    coordinate += 4;
    velocity += 3;
  }
  const int rest = coordinate_count_ - coordinate;
  q_out.tail(rest) = q.tail(rest) + dv.tail(rest);
}

void DeformableSuperquadricModel::project_state(Eigen::Ref<Eigen::VectorXd> q,
                                                Eigen::Ref<Eigen::VectorXd> qd) const {
  if (settings_.parts.rotation) {
    auto w = q.segment<4>(quaternion_offset_);
    const double norm = w.norm();
    if (norm > 0.0 && std::isfinite(norm)) {
      w /= norm;
    }
  }
  for (size_t i = 0; i < free_shape_.size(); ++i) {
    const int k = free_shape_[i];
    double lower = -std::numeric_limits<double>::infinity();
    double upper = std::numeric_limits<double>::infinity();
    if (k == Parameter::kSquareness1 || k == Parameter::kSquareness2) {
      lower = kMinSquareness;
      upper = kMaxSquareness;
    } else if (k <= Parameter::kAspect3) {
      lower = 1e-3 * initial_shape_[k];
    }
    double& value = q[shape_coordinate_offset_ + static_cast<int>(i)];
    double& rate = qd[shape_velocity_offset_ + static_cast<int>(i)];
    if (value < lower) {
      value = lower;
      rate = std::max(rate, 0.0);
    } else if (value > upper) {
      value = upper;
      rate = std::min(rate, 0.0);
    }
  }
}

// Contract ---------------------------------------------------------------------------------------

int DeformableSuperquadricModel::velocity_coordinate(int velocity) const {
  if (velocity < 0 || velocity >= velocity_count_) {
    throw make_error("velocity index ", velocity, " is outside 0..", velocity_count_ - 1);
  }
  const int translation = translation_velocity_offset();
  if (translation >= 0 && velocity < translation + 3) {
    return translation_coordinate_offset() + velocity - translation;
  }
  if (rotation_velocity_offset_ >= 0 && velocity >= rotation_velocity_offset_ &&
      velocity < rotation_velocity_offset_ + 3) {
    return -1;
  }
  if (local_velocity_offset_ >= 0 && velocity >= local_velocity_offset_) {
    return local_coordinate_offset_ + velocity - local_velocity_offset_;
  }
  return shape_coordinate_offset_ + velocity - shape_velocity_offset_;
}

std::optional<RigidBodyProperties> DeformableSuperquadricModel::rigid_body() const {
  if (!rigid_ || !settings_.parts.translation || !settings_.parts.rotation) {
    return std::nullopt;
  }
  return RigidBodyProperties{rigid_properties_, settings_.damping_alpha};
}

ParameterDomain DeformableSuperquadricModel::parameter_domain(ConstVectorRef /*q*/) const {
  return superquadric_parameter_domain();
}

void DeformableSuperquadricModel::fix_point(int i) {
  throw make_error("point ", i,
                   " cannot be fixed: a superquadric has no control points or nodes (constrain a "
                   "material point instead)");
}

}  // namespace dnurbs
