// The D-NURBS model's matrices and forces by Gauss quadrature over the non-empty knot spans
// (Terzopoulos, "Deformable Models: Classic, Topology-Adaptive and Generalized Formulations",
// eqs. 1.25-1.26; the generalized inertial force of free weights, below eq. 1.24).

#include "dynamics/dnurbs/dnurbs_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/kronecker.h"

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

void DNurbsModel::assemble_free(ConstVectorRef q, ModelMatrices& matrices) const {
  // Terzopoulos 2003, eqs. 1.25-1.26 with free weights: 4 x 4 blocks per control point pair,
  // [[R_a R_b I_3, R_a E_b], [E_a^T R_b, E_a . E_b]] for each quantity.
  const int local = pattern_.local_count;
  const int block_local = 4 * local;
  const auto local_size = static_cast<size_t>(block_local * block_local);
  std::vector<double> mass(local_size);
  std::vector<double> damping(local_size);
  std::vector<double> stiffness(local_size);
  reset_block_matrix(matrices.mass, true);
  reset_block_matrix(matrices.damping, has_damping_);
  reset_block_matrix(matrices.stiffness, true);
  for_each_quadrature_point(
      control_net(q), stiffness_order(), true,
      [&](int /*element*/, int /*point*/, double weight, const double* m,
          const PointBasis& /*basis*/, const RationalJacobian& jacobian) {
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
      },
      [&](int element) {
        // Scatter: local pair (a, b) -> scalar entry s -> the 4 x 4 block of the full pattern.
        const int* to_value =
            &pattern_
                 .local_to_value[static_cast<size_t>(element) * static_cast<size_t>(local * local)];
        const int* nodes = &pattern_.element_nodes[static_cast<size_t>(element * local)];
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
        std::fill(mass.begin(), mass.end(), 0.0);
        std::fill(damping.begin(), damping.end(), 0.0);
        std::fill(stiffness.begin(), stiffness.end(), 0.0);
      });
  for (const int index : weight_diagonal_) {
    matrices.mass.valuePtr()[index] += weight_inertia_;
  }
}

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
  for_each_quadrature_point(
      control_net(q), order, true,
      [&](int /*element*/, int /*point*/, double weight, const double* m, const PointBasis& basis,
          const RationalJacobian& jacobian) {
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
      },
      [](int /*element*/) {});
}

double DNurbsModel::quadrature_potential_energy(ConstVectorRef q) const {
  const int order = stiffness_order();
  if (order == 0) {
    return 0.0;
  }
  double energy = 0.0;
  for_each_quadrature_point(
      control_net(q), order, false,
      [&](int /*element*/, int /*point*/, double weight, const double* m,
          const PointBasis& /*basis*/, const RationalJacobian& jacobian) {
        double density = 0.0;
        for (int alpha = 1; alpha < kQuantityCount; ++alpha) {
          if (has_stiffness_[static_cast<size_t>(alpha)]) {
            density += m[2 + alpha] * jacobian.point[static_cast<size_t>(alpha)].squaredNorm();
          }
        }
        energy += 0.5 * weight * density;
      },
      [](int /*element*/) {});
  return energy;
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
        const double mu = m[0] * weight;
        const Eigen::Vector3d h =
            (2.0 * mu / jacobian.weight_sum) * (mixed - weight_rate * velocity);
        for (int a = 0; a < basis.active_count; ++a) {
          const int offset = basis.node[static_cast<size_t>(a)] * 4;
          force.segment<3>(offset) -= jacobian.rational(0, a) * h;
          force[offset + 3] -= jacobian.weight_column[0].col(a).dot(h);
        }
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
