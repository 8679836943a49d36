// The D-NURBS model's matrices and forces by Gauss quadrature over the non-empty knot spans
// (Terzopoulos, "Deformable Models: Classic, Topology-Adaptive and Generalized Formulations",
// eqs. 1.25-1.26; the generalized inertial force of free weights, below eq. 1.24).

#include "dnurbs/dynamics/dnurbs/dnurbs_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/core/kronecker.h"

namespace dnurbs {

namespace {

// The local matrices of free weights hold the upper pairs a <= b of an element's active control
// points, in the order (0, 0), (0, 1), ..., (0, n-1), (1, 1), ...: for each, the distinct entries
// of the 4 x 4 block of the coordinates (P_a, w_a) against (P_b, w_b), summed over quantities
// alpha with coefficients c_alpha,
//   [[s I_3, u], [l^T, e]]:  s = sum c R_a R_b,  u = sum c R_a E_b,  l = sum c E_a R_b,
//   e = sum c E_a . E_b,
// stored as [s, u (3), l (3), e]. The lower pairs are the transposed blocks.
constexpr int kPairEntries = 8;

int pair_count(int n) {
  return n * (n + 1) / 2;
}

// The coefficients of one Gauss point: quadrature weight times mu, gamma (0: no damping) and the
// k_alpha of the quantities with stiffness.
struct PointCoefficients {
  double mass = 0.0;
  double damping = 0.0;
  int stiffness_count = 0;
  std::array<int, kQuantityCount> quantity{};
  std::array<double, kQuantityCount> stiffness{};
};

// Adds one Gauss point's J^T c J terms of M (quantity 0, mu), D (quantity 0, gamma) and K (the
// stiffness quantities) to the local pairs. `scaled` is workspace of 4 n per stiffness quantity.
void add_free_point(const RationalJacobian& jacobian, const PointCoefficients& c, int n,
                    double* mass, double* damping, double* stiffness, double* scaled) {
  const auto rows = static_cast<int>(jacobian.rational.rows());
  const double* R = jacobian.rational.data();  // R(alpha, a) at R[a * rows + alpha]
  // c_alpha R_a and c_alpha E_a of the stiffness quantities, per a: scaled[(k n + a) 4 + 0..3]
  for (int k = 0; k < c.stiffness_count; ++k) {
    const int alpha = c.quantity[static_cast<size_t>(k)];
    const double ck = c.stiffness[static_cast<size_t>(k)];
    const double* E = jacobian.weight_column[static_cast<size_t>(alpha)].data();
    for (int a = 0; a < n; ++a) {
      double* at = scaled + 4 * (k * n + a);
      at[0] = ck * R[a * rows + alpha];
      for (int r = 0; r < 3; ++r) {
        at[1 + r] = ck * E[3 * a + r];
      }
    }
  }
  const double* E0 = jacobian.weight_column[0].data();
  size_t pair = 0;
  for (int a = 0; a < n; ++a) {
    const double Ra = R[a * rows];
    const double* Ea = E0 + 3 * a;
    for (int b = a; b < n; ++b, pair += kPairEntries) {
      const double Rb = R[b * rows];
      const double* Eb = E0 + 3 * b;
      // Quantity 0: M and D
      const std::array<double, kPairEntries> p{
          Ra * Rb,    Ra * Eb[0], Ra * Eb[1], Ra * Eb[2],
          Ea[0] * Rb, Ea[1] * Rb, Ea[2] * Rb, Ea[0] * Eb[0] + Ea[1] * Eb[1] + Ea[2] * Eb[2]};
      for (int e = 0; e < kPairEntries; ++e) {
        mass[pair + static_cast<size_t>(e)] += c.mass * p[static_cast<size_t>(e)];
      }
      if (c.damping != 0.0) {
        for (int e = 0; e < kPairEntries; ++e) {
          damping[pair + static_cast<size_t>(e)] += c.damping * p[static_cast<size_t>(e)];
        }
      }
      // The stiffness quantities, summed in registers
      std::array<double, kPairEntries> k_sum{};
      for (int k = 0; k < c.stiffness_count; ++k) {
        const int alpha = c.quantity[static_cast<size_t>(k)];
        const double* sa = scaled + 4 * (k * n + a);
        const double rb = R[b * rows + alpha];
        const double* eb = jacobian.weight_column[static_cast<size_t>(alpha)].data() + 3 * b;
        k_sum[0] += sa[0] * rb;
        for (int r = 0; r < 3; ++r) {
          k_sum[static_cast<size_t>(1 + r)] += sa[0] * eb[r];
          k_sum[static_cast<size_t>(4 + r)] += sa[1 + r] * rb;
        }
        k_sum[7] += sa[1] * eb[0] + sa[2] * eb[1] + sa[3] * eb[2];
      }
      for (int e = 0; e < kPairEntries; ++e) {
        stiffness[pair + static_cast<size_t>(e)] += k_sum[static_cast<size_t>(e)];
      }
    }
  }
}

// The element buffers of free-weight assembly, kept per thread so that a step allocates nothing
// once they have grown to the model's size.
struct FreeElementBuffers {
  std::vector<double> mass;
  std::vector<double> damping;
  std::vector<double> stiffness;
  std::vector<double> scaled;

  void reset(size_t size, size_t scaled_size) {
    for (std::vector<double>* buffer : {&mass, &damping, &stiffness}) {
      buffer->assign(size, 0.0);
    }
    scaled.resize(scaled_size);
  }
};

FreeElementBuffers& free_element_buffers() {
  thread_local FreeElementBuffers buffers;
  return buffers;
}

}  // namespace

void DNurbsModel::assemble_scalar(ModelMatrices& scalar) const {
  // Terzopoulos 2003, eqs. 1.25-1.26 with fixed weights: S_M = integral mu R_a R_b,
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
  for_each_quadrature_point(
      control_net(initial_coordinates_), stiffness_order(), false,
      [&](int /*element*/, int /*point*/, double weight, const double* m,
          const PointBasis& /*basis*/, const RationalJacobian& jacobian) {
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
      },
      [&](int element) {
        // Scatter the element matrices into the pre-sized pattern, then start the next one.
        const int* to_value = &pattern_.local_to_value[static_cast<size_t>(element) * local_size];
        for (size_t i = 0; i < local_size; ++i) {
          scalar.mass.valuePtr()[to_value[i]] += mass[i];
          scalar.stiffness.valuePtr()[to_value[i]] += stiffness[i];
          if (has_damping_) {
            scalar.damping.valuePtr()[to_value[i]] += damping[i];
          }
        }
        std::fill(mass.begin(), mass.end(), 0.0);
        std::fill(damping.begin(), damping.end(), 0.0);
        std::fill(stiffness.begin(), stiffness.end(), 0.0);
      });
}

void DNurbsModel::reset_block_matrix(SparseMatrix& matrix, bool used) const {
  if (!used) {
    matrix = SparseMatrix(block_pattern_.rows(), block_pattern_.cols());
  } else if (matrix.nonZeros() != block_pattern_.nonZeros() ||
             matrix.rows() != block_pattern_.rows() || !matrix.isCompressed()) {
    matrix = block_pattern_;
  } else {
    std::fill(matrix.valuePtr(), matrix.valuePtr() + matrix.nonZeros(), 0.0);
  }
}

void DNurbsModel::scatter_free_element(int element, const FreeElementMatrices& local,
                                       ModelMatrices& matrices) const {
  // Local upper pair (a, b) -> scalar entries (node_a, node_b) and, mirrored, (node_b, node_a)
  // -> the non-zero entries of their 4 x 4 blocks in the full pattern: s on the position
  // diagonal, u in the weight column, l in the weight row, e in the corner (transposed for the
  // mirror; a diagonal pair takes u for both, its block being symmetric).
  const int n = pattern_.local_count;
  const int* to_value =
      &pattern_.local_to_value[static_cast<size_t>(element) * static_cast<size_t>(n * n)];
  const int* nodes = &pattern_.element_nodes[static_cast<size_t>(element * n)];
  double* mass = matrices.mass.valuePtr();
  double* damping = has_damping_ ? matrices.damping.valuePtr() : nullptr;
  double* stiffness = matrices.stiffness.valuePtr();
  auto add = [&](int scalar_index, int column_node, int r, int c, size_t l) {
    const int index = dense_block_value_index(block_pattern_, pattern_.scalar, scalar_index,
                                              column_node, r, c, 4);
    mass[index] += local.mass[l];
    stiffness[index] += local.stiffness[l];
    if (damping != nullptr) {
      damping[index] += local.damping[l];
    }
  };
  size_t pair = 0;
  for (int a = 0; a < n; ++a) {
    for (int b = a; b < n; ++b, pair += kPairEntries) {
      const int upper = to_value[a * n + b];
      for (int r = 0; r < 3; ++r) {
        add(upper, nodes[b], r, r, pair);
        add(upper, nodes[b], r, 3, pair + 1 + static_cast<size_t>(r));
        add(upper, nodes[b], 3, r, pair + (a == b ? 1 : 4) + static_cast<size_t>(r));
      }
      add(upper, nodes[b], 3, 3, pair + 7);
      if (a == b) {
        continue;
      }
      const int lower = to_value[b * n + a];
      for (int r = 0; r < 3; ++r) {
        add(lower, nodes[a], r, r, pair);
        add(lower, nodes[a], 3, r, pair + 1 + static_cast<size_t>(r));
        add(lower, nodes[a], r, 3, pair + 4 + static_cast<size_t>(r));
      }
      add(lower, nodes[a], 3, 3, pair + 7);
    }
  }
}

void DNurbsModel::free_pass(ConstVectorRef q, const double* qd, ModelMatrices& matrices,
                            double* force) const {
  // Terzopoulos 2003, eqs. 1.25-1.26 with free weights: 4 x 4 blocks per control point pair,
  // [[R_a R_b I_3, R_a E_b], [E_a^T R_b, E_a . E_b]] for each quantity; with `force`, the
  // internal force f_int = -integral sum_alpha k_alpha J_alpha^T x^alpha and, with `qd`, the
  // inertial force g at the same points from the same Jacobian.
  const int local = pattern_.local_count;
  const auto local_size = static_cast<size_t>(kPairEntries * pair_count(local));
  PointCoefficients coefficients;
  for (int alpha = 1; alpha < kQuantityCount; ++alpha) {
    if (has_stiffness_[static_cast<size_t>(alpha)]) {
      coefficients.quantity[static_cast<size_t>(coefficients.stiffness_count++)] = alpha;
    }
  }
  FreeElementBuffers& buffers = free_element_buffers();
  buffers.reset(local_size, static_cast<size_t>(4 * local * coefficients.stiffness_count));
  const FreeElementMatrices element_matrices{buffers.mass.data(), buffers.damping.data(),
                                             buffers.stiffness.data()};
  reset_block_matrix(matrices.mass, true);
  reset_block_matrix(matrices.damping, has_damping_);
  reset_block_matrix(matrices.stiffness, true);
  if (force != nullptr) {
    add_weight_anchor_force(q, Eigen::Map<Eigen::VectorXd>(force, coordinate_count()));
  }
  for_each_quadrature_point(
      control_net(q), stiffness_order(), true,
      [&](int element, int point, double weight, const double* m, const PointBasis& basis,
          const RationalJacobian& jacobian) {
        coefficients.mass = weight * m[0];
        coefficients.damping = has_damping_ ? weight * m[1] : 0.0;
        for (int k = 0; k < coefficients.stiffness_count; ++k) {
          coefficients.stiffness[static_cast<size_t>(k)] =
              weight * m[2 + coefficients.quantity[static_cast<size_t>(k)]];
        }
        add_free_point(jacobian, coefficients, local, buffers.mass.data(), buffers.damping.data(),
                       buffers.stiffness.data(), buffers.scaled.data());
        if (qd != nullptr) {
          subtract_inertial_force(weight, m, basis, jacobian, qd, force);
        }
        if (force != nullptr) {
          subtract_elastic_force(weight, m, rest_at(element, point), basis, jacobian, force);
        }
      },
      [&](int element) {
        scatter_free_element(element, element_matrices, matrices);
        std::fill(buffers.mass.begin(), buffers.mass.end(), 0.0);
        std::fill(buffers.damping.begin(), buffers.damping.end(), 0.0);
        std::fill(buffers.stiffness.begin(), buffers.stiffness.end(), 0.0);
      });
  add_weight_regularization(matrices);
}

void DNurbsModel::assemble_free(ConstVectorRef q, ModelMatrices& matrices) const {
  free_pass(q, nullptr, matrices, nullptr);
}

void DNurbsModel::assemble_step(ConstVectorRef q, ConstVectorRef qd, bool inertial,
                                ModelMatrices& matrices, VectorRef force) const {
  if (mode_ == WeightMode::kFixed) {
    Model::assemble_step(q, qd, inertial, matrices, force);
    return;
  }
  check_velocity(qd);
  if (force.size() != velocity_count()) {
    throw make_error("force vector has ", force.size(), " entries, the model has ",
                     velocity_count());
  }
  free_pass(q, inertial ? qd.data() : nullptr, matrices, force.data());
}

const double* DNurbsModel::rest_at(int element, int point) const {
  if (rest_derivatives_.empty()) {
    return nullptr;
  }
  return &rest_derivatives_[static_cast<size_t>((element * points_per_element() + point) *
                                                kRestStride)];
}

Eigen::Vector3d DNurbsModel::rest_difference(const Eigen::Vector3d& x, int alpha,
                                             const double* rest) {
  if (rest == nullptr) {
    return x;
  }
  return x - Eigen::Map<const Eigen::Vector3d>(rest + 3 * (alpha - 1));
}

void DNurbsModel::subtract_elastic_force(double weight, const double* m, const double* rest,
                                         const PointBasis& basis, const RationalJacobian& jacobian,
                                         double* force) const {
  // -J_alpha^T (w k_alpha (x^alpha - x^alpha_rest)) at one point, for each quantity with
  // stiffness (class comment of dnurbs_model.h)
  for (int alpha = 1; alpha < kQuantityCount; ++alpha) {
    if (!has_stiffness_[static_cast<size_t>(alpha)]) {
      continue;
    }
    const Eigen::Vector3d x =
        weight * m[2 + alpha] *
        rest_difference(jacobian.point[static_cast<size_t>(alpha)], alpha, rest);
    for (int a = 0; a < basis.active_count; ++a) {
      double* f = force + basis.node[static_cast<size_t>(a)] * 4;
      Eigen::Map<Eigen::Vector3d>(f) -= jacobian.rational(alpha, a) * x;
      f[3] -= jacobian.weight_column[static_cast<size_t>(alpha)].col(a).dot(x);
    }
  }
}

void DNurbsModel::subtract_inertial_force(double weight, const double* m, const PointBasis& basis,
                                          const RationalJacobian& jacobian, const double* qd,
                                          double* force) {
  // -mu J^T (Jdot qd) at one point, Jdot qd = (2 / W) (sum_a N_a wdot_a Pdot_a - Wdot xdot)
  double weight_rate = 0.0;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d mixed = Eigen::Vector3d::Zero();
  for (int a = 0; a < basis.active_count; ++a) {
    const int offset = basis.node[static_cast<size_t>(a)] * 4;
    const Eigen::Map<const Eigen::Vector3d> point_rate(qd + offset);
    const double w_rate = qd[offset + 3];
    weight_rate += basis.value(0, a) * w_rate;
    velocity += jacobian.rational(0, a) * point_rate + jacobian.weight_column[0].col(a) * w_rate;
    mixed += basis.value(0, a) * w_rate * point_rate;
  }
  const double mu = m[0] * weight;
  const Eigen::Vector3d h = (2.0 * mu / jacobian.weight_sum) * (mixed - weight_rate * velocity);
  for (int a = 0; a < basis.active_count; ++a) {
    double* f = force + basis.node[static_cast<size_t>(a)] * 4;
    Eigen::Map<Eigen::Vector3d>(f) -= jacobian.rational(0, a) * h;
    f[3] -= jacobian.weight_column[0].col(a).dot(h);
  }
}

void DNurbsModel::add_internal_force(ConstVectorRef q, VectorRef force) const {
  if (mode_ == WeightMode::kFixed) {
    // f_int = -K (q - q_r) = -K q + K q_r
    force.noalias() -= expanded_.stiffness * q;
    if (has_rest_shape()) {
      force += rest_force_;
    }
    return;
  }
  // f_int = -dE/dq = -integral sum_alpha k_alpha J_alpha^T (x^alpha - x^alpha_rest) (x^alpha =
  // J_alpha q), and the weight anchor -k_w (w - w_0) (rational_control_net_model.h).
  add_weight_anchor_force(q, force);
  const int order = stiffness_order();
  if (order == 0) {
    return;
  }
  for_each_quadrature_point(
      control_net(q), order, true,
      [&](int element, int point, double weight, const double* m, const PointBasis& basis,
          const RationalJacobian& jacobian) {
        subtract_elastic_force(weight, m, rest_at(element, point), basis, jacobian, force.data());
      },
      [](int /*element*/) {});
}

double DNurbsModel::quadrature_potential_energy(ConstVectorRef q) const {
  double energy = 0.0;
  const int order = stiffness_order();
  if (order == 0) {
    return energy;
  }
  for_each_quadrature_point(
      control_net(q), order, false,
      [&](int element, int point, double weight, const double* m, const PointBasis& /*basis*/,
          const RationalJacobian& jacobian) {
        const double* rest = rest_at(element, point);
        double density = 0.0;
        for (int alpha = 1; alpha < kQuantityCount; ++alpha) {
          if (has_stiffness_[static_cast<size_t>(alpha)]) {
            density += m[2 + alpha] *
                       rest_difference(jacobian.point[static_cast<size_t>(alpha)], alpha, rest)
                           .squaredNorm();
          }
        }
        energy += 0.5 * weight * density;
      },
      [](int /*element*/) {});
  return energy;
}

void DNurbsModel::store_rest_derivatives(ConstVectorRef q_rest) {
  // x^alpha(q_r) at every Gauss point of the energy (rest_at)
  std::vector<double> rest(
      static_cast<size_t>(element_count() * points_per_element() * kRestStride), 0.0);
  for_each_quadrature_point(
      control_net(q_rest), stiffness_order(), false,
      [&](int element, int point, double /*weight*/, const double* /*m*/,
          const PointBasis& /*basis*/, const RationalJacobian& jacobian) {
        double* slot =
            &rest[static_cast<size_t>((element * points_per_element() + point) * kRestStride)];
        for (int alpha = 1; alpha < kQuantityCount; ++alpha) {
          if (has_stiffness_[static_cast<size_t>(alpha)]) {
            Eigen::Map<Eigen::Vector3d>(slot + 3 * (alpha - 1)) =
                jacobian.point[static_cast<size_t>(alpha)];
          }
        }
      },
      [](int /*element*/) {});
  rest_derivatives_ = std::move(rest);
}

void DNurbsModel::add_inertial_force(ConstVectorRef q, ConstVectorRef qd, VectorRef force) const {
  if (mode_ == WeightMode::kFixed) {
    return;
  }
  // g = -integral mu J^T (Jdot qd), Jdot qd = (2 / W) (sum_a N_a wdot_a Pdot_a - Wdot xdot).
  for_each_quadrature_point(
      control_net(q), 0, true,
      [&](int /*element*/, int /*point*/, double weight, const double* m, const PointBasis& basis,
          const RationalJacobian& jacobian) {
        subtract_inertial_force(weight, m, basis, jacobian, qd.data(), force.data());
      },
      [](int /*element*/) {});
}

void DNurbsModel::add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                                        VectorRef force) const {
  // f_q = integral J^T f(u) du (Terzopoulos 2003, below eq 1.26) by the model's Gauss rule.
  const bool free = mode_ == WeightMode::kFree;
  MaterialSample sample;
  for_each_quadrature_point(
      control_net(q), 1, free,
      [&](int element, int point, double weight, const double* m, const PointBasis& basis,
          const RationalJacobian& jacobian) {
        sample.parameter = quadrature_parameter(element, point);
        sample.position = jacobian.point[0];
        sample.tangent_u = jacobian.point[1];
        sample.tangent_v = jacobian.point[2];
        sample.mass_density = m[0];
        const Eigen::Vector3d f = weight * density(sample);
        for (int a = 0; a < basis.active_count; ++a) {
          const int offset = basis.node[static_cast<size_t>(a)] * per_control_point_;
          force.segment<3>(offset) += jacobian.rational(0, a) * f;
          if (free) {
            force[offset + 3] += jacobian.weight_column[0].col(a).dot(f);
          }
        }
      },
      [](int /*element*/) {});
}

}  // namespace dnurbs
