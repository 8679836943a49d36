#include "dynamics/dnurbs/dnurbs_model.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/kronecker.h"
#include "nurbs/gauss_legendre.h"

namespace dnurbs {

namespace {

// Adds sum_alpha c_alpha J_alpha^T J_alpha of a free-weight Jacobian into a local matrix laid
// out in 4 x 4 blocks: local[(4 a + r) * size + 4 b + s] for the coordinates (P_a, w_a) and
// (P_b, w_b). Every entry is c * (product of two factors), so the result is exactly symmetric.
void add_free_terms(const RationalJacobian& jacobian, const std::array<double, kQuantityCount>& c,
                    int n, std::vector<double>& local) {
  const int size = 4 * n;
  const int rows = static_cast<int>(jacobian.rational.rows());
  const double* R = jacobian.rational.data();  // R(alpha, a) at R[a * rows + alpha]
  for (int alpha = 0; alpha < kQuantityCount; ++alpha) {
    const double ca = c[static_cast<size_t>(alpha)];
    if (ca == 0.0) {
      continue;
    }
    const double* E = jacobian.weight_column[static_cast<size_t>(alpha)].data();  // E[3 a + r]
    for (int a = 0; a < n; ++a) {
      const double Ra = R[a * rows + alpha];
      const double* Ea = E + 3 * a;
      double* row = local.data() + static_cast<size_t>(4 * a * size);
      for (int b = 0; b < n; ++b) {
        const double Rb = R[b * rows + alpha];
        const double* Eb = E + 3 * b;
        const double s = ca * (Ra * Rb);
        for (int r = 0; r < 3; ++r) {
          row[r * size + 4 * b + r] += s;
          row[r * size + 4 * b + 3] += ca * (Ra * Eb[r]);
          row[3 * size + 4 * b + r] += ca * (Ea[r] * Rb);
        }
        row[3 * size + 4 * b + 3] += ca * (Ea[0] * Eb[0] + Ea[1] * Eb[1] + Ea[2] * Eb[2]);
      }
    }
  }
}

}  // namespace

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
  // Validate the settings and the weights ---------------------------------------------------
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
  if (knots_v != nullptr) {
    knots_v_.push_back(*knots_v);
  }

  // Quadrature tables of both directions (seed 001 eq 1.25: Gauss sums over non-empty spans) --
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

  // Material values at every quadrature point, checked once ---------------------------------
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

  // Element connectivity and the pattern sized once -------------------------------------------
  const int nu = table_u_.degree + 1;
  const int nv = table_v_.degree + 1;
  std::vector<int> element_nodes(static_cast<size_t>(elements * nu * nv));
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

  // Coordinates ----------------------------------------------------------------------------
  initial_coordinates_.resize(coordinate_count());
  for (int i = 0; i < control_point_count_; ++i) {
    initial_coordinates_.segment<3>(i * per_control_point_) = control_points.row(i).transpose();
    if (mode_ == WeightMode::kFree) {
      initial_coordinates_[i * 4 + 3] = weights[i];
    }
  }
  if (mode_ == WeightMode::kFixed) {
    fixed_weights_ = weights;
    assemble_scalar(scalar_);
    expanded_.mass = kronecker_identity(scalar_.mass, 3);
    expanded_.damping = kronecker_identity(scalar_.damping, 3);
    expanded_.stiffness = kronecker_identity(scalar_.stiffness, 3);
  } else {
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

// ---------------------------------------------------------------------------------------------
// Matrices

const ModelMatrices* DNurbsModel::constant_matrices() const {
  return mode_ == WeightMode::kFixed ? &expanded_ : nullptr;
}

const ModelMatrices* DNurbsModel::scalar_matrices() const {
  return mode_ == WeightMode::kFixed ? &scalar_ : nullptr;
}

void DNurbsModel::assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const {
  if (mode_ == WeightMode::kFixed) {
    matrices = expanded_;
    return;
  }
  assemble_free(q, matrices);
}

void DNurbsModel::assemble_scalar(ModelMatrices& scalar) const {
  // seed 001 eqs 1.25-1.26 with fixed weights: S_M = integral mu R_a R_b,
  // S_D = integral gamma R_a R_b, S_K = integral sum_alpha k_alpha R_a^alpha R_b^alpha.
  const int local = pattern_.local_count;
  const auto local_size = static_cast<size_t>(local * local);
  std::vector<double> mass(local_size);
  std::vector<double> damping(local_size);
  std::vector<double> stiffness(local_size);
  scalar.mass = pattern_.scalar;
  scalar.stiffness = pattern_.scalar;
  scalar.damping =
      has_damping_ ? pattern_.scalar : SparseMatrix(pattern_.node_count, pattern_.node_count);
  const int order = stiffness_order();
  const ControlNet net = control_net(initial_coordinates_);
  PointBasis basis;
  RationalJacobian jacobian;
  const int per_element = points_per_element();
  for (int e = 0; e < element_count(); ++e) {
    std::fill(mass.begin(), mass.end(), 0.0);
    std::fill(damping.begin(), damping.end(), 0.0);
    std::fill(stiffness.begin(), stiffness.end(), 0.0);
    for (int g = 0; g < per_element; ++g) {
      basis_at_quadrature(e, g, basis);
      rational_jacobian(basis, order, net, false, jacobian);
      const double weight = quadrature_weight(e, g);
      const double* m = &material_[static_cast<size_t>((e * per_element + g) * kMaterialStride)];
      const auto& R = jacobian.rational;
      for (int a = 0; a < local; ++a) {
        for (int b = 0; b < local; ++b) {
          const auto index = static_cast<size_t>(a * local + b);
          // Products of two basis values first: the element matrices are exactly symmetric.
          const double product = weight * (R(0, a) * R(0, b));
          mass[index] += m[0] * product;
          damping[index] += m[1] * product;
          double k = 0.0;
          for (int alpha = 1; alpha < kQuantityCount; ++alpha) {
            if (has_stiffness_[static_cast<size_t>(alpha)]) {
              k += m[2 + alpha] * (R(alpha, a) * R(alpha, b));
            }
          }
          stiffness[index] += weight * k;
        }
      }
    }
    // Scatter the element matrices into the pre-sized pattern.
    const int* to_value = &pattern_.local_to_value[static_cast<size_t>(e) * local_size];
    for (size_t i = 0; i < local_size; ++i) {
      scalar.mass.valuePtr()[to_value[i]] += mass[i];
      scalar.stiffness.valuePtr()[to_value[i]] += stiffness[i];
      if (has_damping_) {
        scalar.damping.valuePtr()[to_value[i]] += damping[i];
      }
    }
  }
}

void DNurbsModel::assemble_free(ConstVectorRef q, ModelMatrices& matrices) const {
  // seed 001 eqs 1.25-1.26 with free weights: 4 x 4 blocks per control point pair,
  // [[R_a R_b I_3, R_a E_b], [E_a^T R_b, E_a . E_b]] for each quantity.
  const int local = pattern_.local_count;
  const int block_local = 4 * local;
  const auto local_size = static_cast<size_t>(block_local * block_local);
  std::vector<double> mass(local_size);
  std::vector<double> damping(local_size);
  std::vector<double> stiffness(local_size);
  auto reset = [&](SparseMatrix& matrix, bool used) {
    if (!used) {
      matrix = SparseMatrix(block_pattern_.rows(), block_pattern_.cols());
    } else if (matrix.nonZeros() != block_pattern_.nonZeros() ||
               matrix.rows() != block_pattern_.rows() || !matrix.isCompressed()) {
      matrix = block_pattern_;
    } else {
      std::fill(matrix.valuePtr(), matrix.valuePtr() + matrix.nonZeros(), 0.0);
    }
  };
  reset(matrices.mass, true);
  reset(matrices.damping, has_damping_);
  reset(matrices.stiffness, true);

  const int order = stiffness_order();
  const ControlNet net = control_net(q);
  PointBasis basis;
  RationalJacobian jacobian;
  const int per_element = points_per_element();
  for (int e = 0; e < element_count(); ++e) {
    std::fill(mass.begin(), mass.end(), 0.0);
    std::fill(damping.begin(), damping.end(), 0.0);
    std::fill(stiffness.begin(), stiffness.end(), 0.0);
    for (int g = 0; g < per_element; ++g) {
      basis_at_quadrature(e, g, basis);
      rational_jacobian(basis, order, net, true, jacobian);
      const double weight = quadrature_weight(e, g);
      const double* m = &material_[static_cast<size_t>((e * per_element + g) * kMaterialStride)];
      std::array<double, kQuantityCount> coefficient{};
      coefficient[0] = weight * m[0];
      add_free_terms(jacobian, coefficient, local, mass);
      if (has_damping_) {
        coefficient[0] = weight * m[1];
        add_free_terms(jacobian, coefficient, local, damping);
      }
      coefficient[0] = 0.0;
      for (int alpha = 1; alpha < kQuantityCount; ++alpha) {
        coefficient[static_cast<size_t>(alpha)] =
            has_stiffness_[static_cast<size_t>(alpha)] ? weight * m[2 + alpha] : 0.0;
      }
      add_free_terms(jacobian, coefficient, local, stiffness);
    }
    // Scatter: local pair (a, b) -> scalar entry s -> the 4 x 4 block of the full pattern.
    const int* to_value =
        &pattern_.local_to_value[static_cast<size_t>(e) * static_cast<size_t>(local * local)];
    const int* nodes = &pattern_.element_nodes[static_cast<size_t>(e * local)];
    for (int a = 0; a < local; ++a) {
      for (int b = 0; b < local; ++b) {
        const int s = to_value[a * local + b];
        for (int r = 0; r < 4; ++r) {
          for (int c = 0; c < 4; ++c) {
            const int index =
                dense_block_value_index(block_pattern_, pattern_.scalar, s, nodes[b], r, c, 4);
            const auto l = static_cast<size_t>((4 * a + r) * block_local + 4 * b + c);
            matrices.mass.valuePtr()[index] += mass[l];
            matrices.stiffness.valuePtr()[index] += stiffness[l];
            if (has_damping_) {
              matrices.damping.valuePtr()[index] += damping[l];
            }
          }
        }
      }
    }
  }
  for (const int index : weight_diagonal_) {
    matrices.mass.valuePtr()[index] += weight_inertia_;
  }
}

// ---------------------------------------------------------------------------------------------
// Forces and energy

void DNurbsModel::add_internal_force(ConstVectorRef q, VectorRef force) const {
  if (mode_ == WeightMode::kFixed) {
    force.noalias() -= expanded_.stiffness * q;
    return;
  }
  // f_int = -dE/dq = -integral sum_alpha k_alpha J_alpha^T x^alpha (x^alpha = J_alpha q).
  const int order = stiffness_order();
  if (order == 0) {
    return;
  }
  const ControlNet net = control_net(q);
  PointBasis basis;
  RationalJacobian jacobian;
  const int per_element = points_per_element();
  for (int e = 0; e < element_count(); ++e) {
    for (int g = 0; g < per_element; ++g) {
      basis_at_quadrature(e, g, basis);
      rational_jacobian(basis, order, net, true, jacobian);
      const double weight = quadrature_weight(e, g);
      const double* m = &material_[static_cast<size_t>((e * per_element + g) * kMaterialStride)];
      for (int alpha = 1; alpha < kQuantityCount; ++alpha) {
        if (!has_stiffness_[static_cast<size_t>(alpha)]) {
          continue;
        }
        const Eigen::Vector3d x =
            weight * m[2 + alpha] * jacobian.point[static_cast<size_t>(alpha)];
        for (int a = 0; a < basis.active_count; ++a) {
          const int offset = basis.node[static_cast<size_t>(a)] * 4;
          force.segment<3>(offset) -= jacobian.rational(alpha, a) * x;
          force[offset + 3] -= jacobian.weight_column[static_cast<size_t>(alpha)].col(a).dot(x);
        }
      }
    }
  }
}

double DNurbsModel::potential_energy(ConstVectorRef q) const {
  const int order = stiffness_order();
  if (order == 0) {
    return 0.0;
  }
  const ControlNet net = control_net(q);
  PointBasis basis;
  RationalJacobian jacobian;
  const int per_element = points_per_element();
  double energy = 0.0;
  for (int e = 0; e < element_count(); ++e) {
    for (int g = 0; g < per_element; ++g) {
      basis_at_quadrature(e, g, basis);
      rational_jacobian(basis, order, net, false, jacobian);
      const double* m = &material_[static_cast<size_t>((e * per_element + g) * kMaterialStride)];
      double density = 0.0;
      for (int alpha = 1; alpha < kQuantityCount; ++alpha) {
        if (has_stiffness_[static_cast<size_t>(alpha)]) {
          density += m[2 + alpha] * jacobian.point[static_cast<size_t>(alpha)].squaredNorm();
        }
      }
      energy += 0.5 * quadrature_weight(e, g) * density;
    }
  }
  return energy;
}

void DNurbsModel::add_inertial_force(ConstVectorRef q, ConstVectorRef qd, VectorRef force) const {
  if (mode_ == WeightMode::kFixed) {
    return;
  }
  // g = -integral mu J^T (Jdot qd), Jdot qd = (2 / W) (sum_a N_a wdot_a Pdot_a - Wdot xdot).
  const ControlNet net = control_net(q);
  PointBasis basis;
  RationalJacobian jacobian;
  const int per_element = points_per_element();
  for (int e = 0; e < element_count(); ++e) {
    for (int g = 0; g < per_element; ++g) {
      basis_at_quadrature(e, g, basis);
      rational_jacobian(basis, 0, net, true, jacobian);
      double weight_rate = 0.0;
      Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
      Eigen::Vector3d mixed = Eigen::Vector3d::Zero();
      for (int a = 0; a < basis.active_count; ++a) {
        const int offset = basis.node[static_cast<size_t>(a)] * 4;
        const Eigen::Vector3d point_rate = qd.segment<3>(offset);
        const double w_rate = qd[offset + 3];
        weight_rate += basis.value(0, a) * w_rate;
        velocity +=
            jacobian.rational(0, a) * point_rate + jacobian.weight_column[0].col(a) * w_rate;
        mixed += basis.value(0, a) * w_rate * point_rate;
      }
      const double mu = material_[static_cast<size_t>((e * per_element + g) * kMaterialStride)] *
                        quadrature_weight(e, g);
      const Eigen::Vector3d h = (2.0 * mu / jacobian.weight_sum) * (mixed - weight_rate * velocity);
      for (int a = 0; a < basis.active_count; ++a) {
        const int offset = basis.node[static_cast<size_t>(a)] * 4;
        force.segment<3>(offset) -= jacobian.rational(0, a) * h;
        force[offset + 3] -= jacobian.weight_column[0].col(a).dot(h);
      }
    }
  }
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

void DNurbsModel::add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                                        VectorRef force) const {
  // f_q = integral J^T f(u) du (seed 001, below eq 1.26) by the model's Gauss rule.
  const bool free = mode_ == WeightMode::kFree;
  const ControlNet net = control_net(q);
  PointBasis basis;
  RationalJacobian jacobian;
  MaterialSample sample;
  const int per_element = points_per_element();
  for (int e = 0; e < element_count(); ++e) {
    for (int g = 0; g < per_element; ++g) {
      basis_at_quadrature(e, g, basis);
      rational_jacobian(basis, 1, net, free, jacobian);
      sample.parameter = quadrature_parameter(e, g);
      sample.position = jacobian.point[0];
      sample.tangent_u = jacobian.point[1];
      sample.tangent_v = jacobian.point[2];
      sample.mass_density = material_[static_cast<size_t>((e * per_element + g) * kMaterialStride)];
      const Eigen::Vector3d f = quadrature_weight(e, g) * density(sample);
      for (int a = 0; a < basis.active_count; ++a) {
        const int offset = basis.node[static_cast<size_t>(a)] * per_control_point_;
        force.segment<3>(offset) += jacobian.rational(0, a) * f;
        if (free) {
          force[offset + 3] += jacobian.weight_column[0].col(a).dot(f);
        }
      }
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
