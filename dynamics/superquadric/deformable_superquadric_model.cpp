#include "dynamics/superquadric/deformable_superquadric_model.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <utility>

#include "core/error.h"
#include "core/rotation.h"
#include "nurbs/gauss_legendre.h"
#include "surface/signed_power.h"

namespace dnurbs {

namespace {

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

void check_finite(double value, const char* name) {
  if (!std::isfinite(value)) {
    throw make_error("deformable superquadric ", name, " ", value, " is not finite");
  }
}

}  // namespace

struct DeformableSuperquadricModel::State {
  Eigen::Vector3d centre;
  Eigen::Matrix3d rotation;
  SuperquadricShapeParameters shape;
  const double* local = nullptr;  ///< q_d (3 #nodes) or nullptr
};

namespace {

/// Offset in q_d of the displacement of the a-th active node.
std::ptrdiff_t node_offset(const FeShapeValues& fe, int a) {
  return 3 * static_cast<std::ptrdiff_t>(fe.node[static_cast<size_t>(a)]);
}

/// A 1-D rule on [a, b] graded with exponent p toward the singular ends (seed 001 eq 1.38
/// integrands with the |cos w|^e singularities of the signed powers): x = a + (b - a) g(tau),
/// g = tau^p (singular at a), 1 - (1 - tau)^p (at b), tau^p / (tau^p + (1 - tau)^p) (both).
void graded_rule(const GaussLegendreRule& rule, double a, double b, bool singular_a,
                 bool singular_b, double p, std::vector<double>& nodes,
                 std::vector<double>& weights) {
  const auto n = static_cast<size_t>(rule.nodes.size());
  nodes.resize(n);
  weights.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const double tau = 0.5 * (rule.nodes[static_cast<Eigen::Index>(k)] + 1.0);
    const double w = 0.5 * rule.weights[static_cast<Eigen::Index>(k)];
    double g = tau;
    double dg = 1.0;
    if (singular_a && singular_b) {
      const double left = std::pow(tau, p);
      const double right = std::pow(1.0 - tau, p);
      g = left / (left + right);
      dg = p * std::pow(tau, p - 1.0) * std::pow(1.0 - tau, p - 1.0) /
           ((left + right) * (left + right));
    } else if (singular_a) {
      g = std::pow(tau, p);
      dg = p * std::pow(tau, p - 1.0);
    } else if (singular_b) {
      g = 1.0 - std::pow(1.0 - tau, p);
      dg = p * std::pow(1.0 - tau, p - 1.0);
    }
    nodes[k] = a + (b - a) * g;
    weights[k] = (b - a) * dg * w;
  }
}

/// True if w is a multiple of pi/2 (to 1e-12).
bool at_quarter_turn(double w) {
  const double turns = w / (0.5 * std::numbers::pi);
  return std::abs(turns - std::round(turns)) < 1e-12;
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

}  // namespace

// Parts -----------------------------------------------------------------------------------------

DeformableSuperquadricParts DeformableSuperquadricParts::rigid() {
  return {};
}

DeformableSuperquadricParts DeformableSuperquadricParts::global() {
  DeformableSuperquadricParts parts;
  for (const int k : {Parameter::kAspect1, Parameter::kAspect2, Parameter::kAspect3, Parameter::kSquareness1,
                      Parameter::kSquareness2, Parameter::kTaper1, Parameter::kTaper2, Parameter::kBendAmplitude,
                      Parameter::kTwist, Parameter::kShearX, Parameter::kShearY}) {
    parts.shape[static_cast<size_t>(k)] = true;
  }
  return parts;
}

DeformableSuperquadricParts DeformableSuperquadricParts::full() {
  DeformableSuperquadricParts parts = global();
  parts.local = true;
  return parts;
}

// Construction ----------------------------------------------------------------------------------

DeformableSuperquadricModel::DeformableSuperquadricModel(const SuperquadricShapeParameters& shape,
                                                         const Eigen::Vector3d& centre,
                                                         const Eigen::Quaterniond& orientation,
                                                         DeformableSuperquadricSettings settings)
    : settings_(std::move(settings)),
      initial_shape_(shape),
      initial_centre_(centre),
      mesh_(settings_.mesh_cells_u, settings_.mesh_cells_v) {
  // Validate the shape, the pose and the settings --------------------------------------------
  static const char* const shape_names[kShapeCount] = {
      "scale a",           "aspect a1", "aspect a2", "aspect a3",         "squareness e1",
      "squareness e2",     "taper t1",  "taper t2",  "bend amplitude b1", "bend offset b2",
      "bend frequency b3", "twist tau", "shear sx",  "shear sy"};
  for (int k = 0; k < kShapeCount; ++k) {
    check_finite(shape[k], shape_names[k]);
  }
  for (int k = Parameter::kScale; k <= Parameter::kAspect3; ++k) {
    if (!(shape[k] > 0.0)) {
      throw make_error("deformable superquadric ", shape_names[k], " = ", shape[k],
                       " must be positive");
    }
  }
  for (int k = Parameter::kSquareness1; k <= Parameter::kSquareness2; ++k) {
    if (!(shape[k] >= kMinSquareness && shape[k] <= kMaxSquareness)) {
      throw make_error("deformable superquadric ", shape_names[k], " = ", shape[k], " is outside [",
                       kMinSquareness, ", ", kMaxSquareness, "]");
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
  const DeformableSuperquadricSettings& s = settings_;
  if (!(s.mass_density > 0.0) || !std::isfinite(s.mass_density)) {
    throw make_error("deformable superquadric mass density ", s.mass_density,
                     " must be positive and finite");
  }
  if (!(s.damping_alpha >= 0.0) || !std::isfinite(s.damping_alpha) || !(s.damping_beta >= 0.0) ||
      !std::isfinite(s.damping_beta)) {
    throw make_error("deformable superquadric Rayleigh damping alpha = ", s.damping_alpha,
                     ", beta = ", s.damping_beta, " must be non-negative and finite");
  }
  for (int k = 0; k < kShapeCount; ++k) {
    if (!(s.shape_stiffness[k] >= 0.0) || !std::isfinite(s.shape_stiffness[k])) {
      throw make_error("deformable superquadric stiffness of ", shape_names[k], " = ",
                       s.shape_stiffness[k], " must be non-negative and finite");
    }
  }
  rest_shape_ = s.rest_shape.value_or(shape);
  for (int k = 0; k < kShapeCount; ++k) {
    check_finite(rest_shape_[k], "rest shape entry");
  }
  if (!(s.regularization >= 0.0) || !std::isfinite(s.regularization)) {
    throw make_error("deformable superquadric regularization ", s.regularization,
                     " must be non-negative and finite");
  }
  // (the quadrature order and the FE stiffness are validated by ParametricFeMesh below)

  // Layout --------------------------------------------------------------------------------------
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

  // Quadrature tables: seed 001 eq 1.38, M = integral mu L^T L dA with dA = |s_u x s_v| du dv of
  // the reference shape ---------------------------------------------------------------------
  if (settings_.graded_quadrature &&
      (shape[Parameter::kSquareness1] < 1.0 || shape[Parameter::kSquareness2] < 1.0)) {
    const GaussLegendreRule& rule = gauss_legendre_rule(settings_.quadrature_points);
    const double p_u = std::max(1.0, 1.0 / shape[Parameter::kSquareness1]);
    const double p_v = std::max(1.0, 1.0 / shape[Parameter::kSquareness2]);
    const bool grade_u = p_u > 1.0;
    const bool grade_v = p_v > 1.0;
    std::vector<double> nodes_u, weights_u, nodes_v, weights_v;
    for (int i = 0; i < mesh_.cells_u(); ++i) {
      for (int j = 0; j < mesh_.cells_v(); ++j) {
        const Eigen::Vector4d box = mesh_.cell_bounds(i, j);
        graded_rule(rule, box[0], box[1], grade_u && at_quarter_turn(box[0]),
                    grade_u && at_quarter_turn(box[1]), p_u, nodes_u, weights_u);
        graded_rule(rule, box[2], box[3], grade_v && at_quarter_turn(box[2]),
                    grade_v && at_quarter_turn(box[3]), p_v, nodes_v, weights_v);
        for (size_t a = 0; a < nodes_u.size(); ++a) {
          for (size_t b = 0; b < nodes_v.size(); ++b) {
            points_.push_back({nodes_u[a], nodes_v[b], weights_u[a] * weights_v[b], i, j});
          }
        }
      }
    }
  } else {
    points_ = mesh_.quadrature_points(settings_.quadrature_points);
  }
  const DeformableSuperquadricShape reference(shape);
  point_mass_.resize(points_.size());
  if (parts.local) {
    point_shape_values_.resize(points_.size());
  }
  if (shape_free == 0) {
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
    if (parts.local) {
      point_shape_values_[k] = mesh_.shape_values(point.u, point.v);
    }
    if (shape_free == 0) {
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

  // Local mass M_dd = integral mu S^T S dA = m_ab (x) I3 (constant: R^T R = I), regularised
  // --------
  if (parts.local) {
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

  // Stiffness K: diagonal on the free q_s, the FE membrane + spring on q_d ------------------------
  {
    std::vector<Eigen::Triplet<double>> triplets;
    for (int i = 0; i < shape_free; ++i) {
      const double k = settings_.shape_stiffness[free_shape_[static_cast<size_t>(i)]];
      triplets.emplace_back(shape_velocity_offset_ + i, shape_velocity_offset_ + i, k);
    }
    if (parts.local) {
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
  }

  // The structure of M: a dense block over (c, w, q_s), dense coupling rows to q_d, M_dd --------
  {
    const int nr = rigid_count_;
    Eigen::VectorXi sizes(velocity_count_);
    for (int j = 0; j < velocity_count_; ++j) {
      sizes[j] =
          j < nr ? velocity_count_ : nr + static_cast<int>(local_mass_.col(j - nr).nonZeros());
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

  // Regularisation of the free q_s (constant, from the reference state) ---------------------------
  shape_regularization_ = Eigen::VectorXd::Zero(shape_free);
  if (shape_free > 0) {
    Eigen::MatrixXd mass_rr;
    Eigen::MatrixXd coupling;
    assemble_dense_mass(decode(initial_coordinates_), mass_rr, coupling);
    const double h =
        shape[Parameter::kScale] *
        std::max({shape[Parameter::kAspect1], shape[Parameter::kAspect2], shape[Parameter::kAspect3]});
    for (int i = 0; i < shape_free; ++i) {
      const int row = shape_velocity_offset_ + i;
      shape_regularization_[i] =
          settings_.regularization * (mass_rr(row, row) + props.mass * h * h);
    }
  }

  if (constant_) {
    assemble_matrices(initial_coordinates_, constant_matrices_);
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

// Per-point kinematics ---------------------------------------------------------------------------

template <typename Visitor>
void DeformableSuperquadricModel::for_each_point(const State& state, bool need_jacobian,
                                                 Visitor&& visit) const {
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
    // seed 001 eq 1.32: d = S q_d
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

namespace {

/// The dense block of R^T L at a point (seed 001 eq 1.36 in the body frame):
/// [R^T (translation), -[p]_x (rotation), J_free (shape)].
void body_jacobian(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& p,
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

}  // namespace

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
  // seed 001 eq 1.35: x = c + R (s + d)
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
  // seed 001 eq 1.36: L = R [R^T, -[p]_x, J, S] = [I, B, R J, R S]
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
  // seed 001 eq 1.38: M = integral mu L^T L dA = integral mu (R^T L)^T (R^T L) dA
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

  // K is constant; D = alpha M + beta K (seed 001 below eq 1.38).
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
  // seed 001 eq 1.38: g = -integral mu L^T Ldot qd dA = -integral mu (R^T L)^T a_b dA
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
  // f_q = integral L^T f du dv (seed 001 below eq 1.38), f per unit parametric measure.
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
    // R <- R exp([dw]_x): the quaternion product q (x) exp(dw), renormalised.
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

Eigen::Vector3d DeformableSuperquadricModel::linear_momentum(ConstVectorRef q,
                                                             ConstVectorRef qd) const {
  const State state = decode(q);
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
  BodyJacobian lb(3, rigid_count_);
  for_each_point(state, !free_shape_.empty(), [&](const PointKinematics& pt) {
    body_jacobian(state.rotation, pt.p, pt.jacobian, settings_.parts.translation,
                  settings_.parts.rotation, free_shape_, lb);
    Eigen::Vector3d body = lb * qd.head(rigid_count_);
    if (pt.fe != nullptr) {
      for (int a = 0; a < pt.fe->active_count; ++a) {
        body += pt.fe->value[a] * qd.segment<3>(local_velocity_offset_ + node_offset(*pt.fe, a));
      }
    }
    momentum += pt.mass * (state.rotation * body);
  });
  return momentum;
}

Eigen::Vector3d DeformableSuperquadricModel::angular_momentum(ConstVectorRef q,
                                                              ConstVectorRef qd) const {
  const State state = decode(q);
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
  BodyJacobian lb(3, rigid_count_);
  for_each_point(state, !free_shape_.empty(), [&](const PointKinematics& pt) {
    body_jacobian(state.rotation, pt.p, pt.jacobian, settings_.parts.translation,
                  settings_.parts.rotation, free_shape_, lb);
    Eigen::Vector3d body = lb * qd.head(rigid_count_);
    if (pt.fe != nullptr) {
      for (int a = 0; a < pt.fe->active_count; ++a) {
        body += pt.fe->value[a] * qd.segment<3>(local_velocity_offset_ + node_offset(*pt.fe, a));
      }
    }
    const Eigen::Vector3d x = state.centre + state.rotation * pt.p;
    momentum += pt.mass * x.cross(state.rotation * body);
  });
  return momentum;
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
