#include "dynamics/dnurbs/dnurbs_model.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/kronecker.h"
#include "nurbs/gauss_legendre.h"

namespace dnurbs {

DNurbsModel::DNurbsModel(const KnotVector& knots_u, const KnotVector* knots_v,
                         const Eigen::MatrixX3d& control_points, const Eigen::VectorXd& weights,
                         const MaterialFunction& mass_density,
                         const MaterialFunction& damping_density,
                         const std::array<MaterialFunction, kQuantityCount>& stiffness,
                         const std::array<const char*, kQuantityCount>& stiffness_names,
                         const DNurbsSettings& settings)
    : surface_(knots_v != nullptr),
      mode_(settings.weight_mode),
      per_control_point_(coordinates_per_control_point(settings.weight_mode)),
      control_point_count_(static_cast<int>(control_points.rows())),
      count_v_(knots_v != nullptr ? knots_v->control_point_count() : 1),
      minimum_weight_(settings.minimum_weight),
      knots_u_(knots_u) {
  validate(weights, settings);
  if (knots_v != nullptr) {
    knots_v_.push_back(*knots_v);
  }
  // Quadrature tables of both directions (Terzopoulos 2003, eq. 1.25: Gauss sums over non-empty
  // spans)
  const int points_u =
      settings.quadrature_points > 0 ? settings.quadrature_points : knots_u.degree() + 1;
  table_u_ = direction_quadrature(knots_u, points_u);
  if (knots_v != nullptr) {
    const int points_v =
        settings.quadrature_points > 0 ? settings.quadrature_points : knots_v->degree() + 1;
    table_v_ = direction_quadrature(*knots_v, points_v);
  } else {
    table_v_ = trivial_direction_quadrature();
  }
  build_material_table(mass_density, damping_density, stiffness, stiffness_names);
  build_pattern();
  build_coordinates(control_points, weights, settings);
}

void DNurbsModel::validate(const Eigen::VectorXd& weights, const DNurbsSettings& settings) const {
  if (!(minimum_weight_ > 0.0) || !std::isfinite(minimum_weight_)) {
    throw make_error("minimum weight ", minimum_weight_, " is not a positive finite number");
  }
  if (settings.quadrature_points < 0 || settings.quadrature_points > kMaxGaussPoints) {
    throw make_error("quadrature points per span ", settings.quadrature_points, " is outside 0..",
                     kMaxGaussPoints, " (0 = degree + 1)");
  }
  for (int i = 0; i < control_point_count_; ++i) {
    const double w = weights[i];
    if (!(w > 0.0) || !std::isfinite(w)) {
      throw make_error("weight ", i, " is ", w, " (weights must be positive and finite)");
    }
    if (mode_ == WeightMode::kFree && w < minimum_weight_) {
      throw make_error("free weight ", i, " is ", w, ", below the minimum weight ",
                       minimum_weight_);
    }
  }
}

void DNurbsModel::build_material_table(
    const MaterialFunction& mass_density, const MaterialFunction& damping_density,
    const std::array<MaterialFunction, kQuantityCount>& stiffness,
    const std::array<const char*, kQuantityCount>& stiffness_names) {
  // Material values at every quadrature point, checked once
  has_damping_ = !damping_density.is_zero();
  for (int alpha = 1; alpha < kQuantityCount; ++alpha) {
    has_stiffness_[static_cast<size_t>(alpha)] = !stiffness[static_cast<size_t>(alpha)].is_zero();
  }
  const int elements = element_count();
  const int per_element = points_per_element();
  material_.assign(static_cast<size_t>(elements * per_element * kMaterialStride), 0.0);
  for (int e = 0; e < elements; ++e) {
    for (int g = 0; g < per_element; ++g) {
      const Eigen::Vector2d u = quadrature_parameter(e, g);
      double* m = &material_[static_cast<size_t>((e * per_element + g) * kMaterialStride)];
      m[0] = mass_density.checked(u, "mass density", true);
      m[1] = damping_density.checked(u, "damping density", true);
      for (int alpha = 1; alpha < kQuantityCount; ++alpha) {
        if (has_stiffness_[static_cast<size_t>(alpha)]) {
          m[2 + alpha] = stiffness[static_cast<size_t>(alpha)].checked(
              u, stiffness_names[static_cast<size_t>(alpha)], true);
        }
      }
    }
  }
}

void DNurbsModel::build_pattern() {
  // Element connectivity and the pattern sized once
  const int nu = table_u_.degree + 1;
  const int nv = table_v_.degree + 1;
  std::vector<int> element_nodes(static_cast<size_t>(element_count() * nu * nv));
  for (int su = 0; su < table_u_.span_count; ++su) {
    for (int sv = 0; sv < table_v_.span_count; ++sv) {
      const int e = su * table_v_.span_count + sv;
      for (int a = 0; a < nu; ++a) {
        for (int b = 0; b < nv; ++b) {
          element_nodes[static_cast<size_t>((e * nu + a) * nv + b)] =
              table_u_.control_point[static_cast<size_t>(su * nu + a)] * count_v_ +
              table_v_.control_point[static_cast<size_t>(sv * nv + b)];
        }
      }
    }
  }
  pattern_ = make_assembly_pattern(control_point_count_, nu * nv, element_nodes);
}

void DNurbsModel::build_coordinates(const Eigen::MatrixX3d& control_points,
                                    const Eigen::VectorXd& weights,
                                    const DNurbsSettings& settings) {
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
    return;
  }
  // Free weights: the 4 x 4 block pattern and the value index of each weight's diagonal entry
  block_pattern_ = dense_block_pattern(pattern_.scalar, 4);
  weight_inertia_ = settings.weight_inertia;
  if (!(weight_inertia_ >= 0.0) || !std::isfinite(weight_inertia_)) {
    throw make_error("weight inertia ", weight_inertia_, " is not a non-negative finite number");
  }
  const auto* outer = pattern_.scalar.outerIndexPtr();
  const auto* inner = pattern_.scalar.innerIndexPtr();
  for (int i = 0; i < control_point_count_; ++i) {
    const auto* found = std::lower_bound(inner + outer[i], inner + outer[i + 1], i);
    weight_diagonal_.push_back(dense_block_value_index(
        block_pattern_, pattern_.scalar, static_cast<int>(found - inner), i, 3, 3, 4));
  }
  if (settings.fix_weight_gauge) {
    fix_weight(0);
  }
}

// ---------------------------------------------------------------------------------------------
// Points and bases

double DNurbsModel::quadrature_weight(int element, int point) const {
  const int su = element / table_v_.span_count;
  const int sv = element % table_v_.span_count;
  const int gu = point / table_v_.points_per_span;
  const int gv = point % table_v_.points_per_span;
  return table_u_.weight[static_cast<size_t>(su * table_u_.points_per_span + gu)] *
         table_v_.weight[static_cast<size_t>(sv * table_v_.points_per_span + gv)];
}

Eigen::Vector2d DNurbsModel::quadrature_parameter(int element, int point) const {
  const int su = element / table_v_.span_count;
  const int sv = element % table_v_.span_count;
  const int gu = point / table_v_.points_per_span;
  const int gv = point % table_v_.points_per_span;
  const double u = table_u_.parameter[static_cast<size_t>(su * table_u_.points_per_span + gu)];
  const double v =
      surface_ ? table_v_.parameter[static_cast<size_t>(sv * table_v_.points_per_span + gv)] : 0.0;
  return {u, v};
}

void DNurbsModel::basis_at(const Eigen::Vector2d& u, PointBasis& basis) const {
  DirectionBasis basis_u;
  DirectionBasis basis_v;
  direction_basis(knots_u_, u.x(), basis_u);
  if (surface_) {
    direction_basis(knots_v_.front(), u.y(), basis_v);
  } else {
    trivial_direction_basis(basis_v);
  }
  tensor_product_basis(basis_u, basis_v, count_v_, basis);
}

void DNurbsModel::basis_at_quadrature(int element, int point, PointBasis& basis) const {
  const int su = element / table_v_.span_count;
  const int sv = element % table_v_.span_count;
  const int gu = point / table_v_.points_per_span;
  const int gv = point % table_v_.points_per_span;
  DirectionBasis basis_u;
  DirectionBasis basis_v;
  direction_basis(table_u_, su, gu, basis_u);
  direction_basis(table_v_, sv, gv, basis_v);
  tensor_product_basis(basis_u, basis_v, count_v_, basis);
}

ControlNet DNurbsModel::control_net(ConstVectorRef q) const {
  if (q.size() != coordinate_count()) {
    throw make_error("coordinate vector has ", q.size(), " entries, the model has ",
                     coordinate_count());
  }
  ControlNet net;
  net.positions = q.data();
  net.position_stride = per_control_point_;
  if (mode_ == WeightMode::kFree) {
    net.weights = q.data() + 3;
    net.weight_stride = 4;
  } else {
    net.weights = fixed_weights_.data();
    net.weight_stride = 1;
  }
  return net;
}

int DNurbsModel::stiffness_order() const {
  int order = 0;
  for (int alpha = 1; alpha < kQuantityCount; ++alpha) {
    if (has_stiffness_[static_cast<size_t>(alpha)]) {
      order = alpha >= 3 ? 2 : std::max(order, 1);
    }
  }
  return order;
}

Eigen::Vector3d DNurbsModel::position(ConstVectorRef q, const Eigen::Vector2d& u) const {
  PointBasis basis;
  basis_at(u, basis);
  RationalJacobian jacobian;
  rational_jacobian(basis, 0, control_net(q), false, jacobian);
  return jacobian.point[0];
}

SparseMatrix DNurbsModel::position_jacobian(ConstVectorRef q, const Eigen::Vector2d& u) const {
  PointBasis basis;
  basis_at(u, basis);
  RationalJacobian jacobian;
  const bool free = mode_ == WeightMode::kFree;
  rational_jacobian(basis, 0, control_net(q), free, jacobian);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(basis.active_count * (free ? 6 : 3)));
  for (int a = 0; a < basis.active_count; ++a) {
    const int offset = basis.node[static_cast<size_t>(a)] * per_control_point_;
    for (int r = 0; r < 3; ++r) {
      triplets.emplace_back(r, offset + r, jacobian.rational(0, a));
      if (free) {
        triplets.emplace_back(r, offset + 3, jacobian.weight_column[0](r, a));
      }
    }
  }
  SparseMatrix L(3, velocity_count());
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

Eigen::Vector3d DNurbsModel::jacobian_rate_times_velocity(ConstVectorRef q, ConstVectorRef qd,
                                                          const Eigen::Vector2d& u) const {
  if (mode_ == WeightMode::kFixed) {
    return Eigen::Vector3d::Zero();
  }
  PointBasis basis;
  basis_at(u, basis);
  RationalJacobian jacobian;
  rational_jacobian(basis, 0, control_net(q), true, jacobian);
  // xdd - J qdd = (2 / W) (sum_a N_a wdot_a Pdot_a - Wdot xdot), from A = x W with A the
  // homogeneous point sum_a N_a w_a P_a.
  double weight_rate = 0.0;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d mixed = Eigen::Vector3d::Zero();
  for (int a = 0; a < basis.active_count; ++a) {
    const int offset = basis.node[static_cast<size_t>(a)] * 4;
    const Eigen::Vector3d point_rate = qd.segment<3>(offset);
    const double w_rate = qd[offset + 3];
    weight_rate += basis.value(0, a) * w_rate;
    velocity += jacobian.rational(0, a) * point_rate + jacobian.weight_column[0].col(a) * w_rate;
    mixed += basis.value(0, a) * w_rate * point_rate;
  }
  return 2.0 / jacobian.weight_sum * (mixed - weight_rate * velocity);
}

void DNurbsModel::add_point_force(ConstVectorRef q, const Eigen::Vector2d& u,
                                  const Eigen::Vector3d& f, VectorRef force) const {
  PointBasis basis;
  basis_at(u, basis);
  RationalJacobian jacobian;
  const bool free = mode_ == WeightMode::kFree;
  rational_jacobian(basis, 0, control_net(q), free, jacobian);
  for (int a = 0; a < basis.active_count; ++a) {
    const int offset = basis.node[static_cast<size_t>(a)] * per_control_point_;
    force.segment<3>(offset) += jacobian.rational(0, a) * f;
    if (free) {
      force[offset + 3] += jacobian.weight_column[0].col(a).dot(f);
    }
  }
}

void DNurbsModel::project_state(Eigen::Ref<Eigen::VectorXd> q,
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

int DNurbsModel::control_point_offset(int i) const {
  if (i < 0 || i >= control_point_count_) {
    throw make_error("control point index ", i, " is outside 0..", control_point_count_ - 1);
  }
  return i * per_control_point_;
}

int DNurbsModel::weight_offset(int i) const {
  if (mode_ != WeightMode::kFree) {
    throw make_error("weight ", i, " is not a coordinate (weights are fixed)");
  }
  return control_point_offset(i) + 3;
}

void DNurbsModel::fix_control_point(int i) {
  const int offset = control_point_offset(i);
  for (int c = 0; c < 3; ++c) {
    fix_coordinate(offset + c);
  }
}

void DNurbsModel::fix_point(int i) {
  if (i < 0 || i >= control_point_count_) {
    throw make_error("control point ", i, " does not exist (the model has ", control_point_count_,
                     ")");
  }
  fix_control_point(i);
}

void DNurbsModel::coordinate_lower_bounds(VectorRef lower) const {
  if (mode_ != WeightMode::kFree) {
    return;
  }
  for (int c = 0; c < control_point_count_; ++c) {
    lower[weight_offset(c)] = minimum_weight_;
  }
}

void DNurbsModel::fix_weight(int i) {
  fix_coordinate(weight_offset(i));
}

Eigen::MatrixX3d DNurbsModel::control_points(ConstVectorRef q) const {
  const ControlNet net = control_net(q);
  Eigen::MatrixX3d points(control_point_count_, 3);
  for (int i = 0; i < control_point_count_; ++i) {
    points.row(i) = Eigen::Map<const Eigen::RowVector3d>(net.positions + i * per_control_point_);
  }
  return points;
}

Eigen::VectorXd DNurbsModel::weights(ConstVectorRef q) const {
  const ControlNet net = control_net(q);
  Eigen::VectorXd result(control_point_count_);
  for (int i = 0; i < control_point_count_; ++i) {
    result[i] = net.weights[i * net.weight_stride];
  }
  return result;
}

double DNurbsModel::parametric_measure() const {
  const double length_u = knots_u_.domain_end() - knots_u_.domain_start();
  if (!surface_) {
    return length_u;
  }
  return length_u * (knots_v_.front().domain_end() - knots_v_.front().domain_start());
}

}  // namespace dnurbs
