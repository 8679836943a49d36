// The matrix-free step residual of free-weight D-NURBS, f_int + g - D qd - M a (Terzopoulos,
// "Deformable Models: Classic, Topology-Adaptive and Generalized Formulations", eqs. 1.24-1.26),
// evaluated in homogeneous form (homogeneous_point.h) by sum factorization over each element's
// tensor-product Gauss points: the homogeneous control points (w P, w) and their rates are
// contracted with the v basis, then the u basis, per point; the points' force densities go back
// the same way. An element of (p+1)(q+1) control points and G_u G_v points costs O((p+1) G (p+1 +
// G)) per component instead of O((p+1)^2 G^2).

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/homogeneous_point.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_model.h"

namespace dnurbs {

namespace {

// Per node, the homogeneous control point and rates the residual contracts: (w P, w), the
// acceleration's and the velocity's rates (w Pdot + wdot P, wdot) and the mixed term wdot Pdot.
constexpr int kNodeStride = 16;
constexpr int kPoint = 0;
constexpr int kAcceleration = 4;
constexpr int kVelocity = 8;
constexpr int kMixed = 12;
constexpr int kRateComponents = 11;  // acceleration, velocity, mixed
using NodeValues = Eigen::Matrix<double, kNodeStride, 1>;
using RateValues = Eigen::Matrix<double, kRateComponents, 1>;

// The sum-factorized contractions of one model's elements, with work arrays kept per thread (no
// allocation once grown to the model).
class ElementContraction {
 public:
  ElementContraction(const DirectionQuadrature& table_u, const DirectionQuadrature& table_v,
                     int count_v, int quantities, int order_v)
      : u_(table_u), v_(table_v), count_v_(count_v), quantities_(quantities), order_v_(order_v) {}

  // The node values of the homogeneous control points and rates (q, qd, a: 4 per node).
  void set_nodes(const double* q, const double* qd, const double* a, int count);

  // Element (su, sv): contracts the node values with the v basis at its points.
  void contract_v(int su, int sv);
  // v_sums[gv][kv][i] = sum_j N_j^(kv)(v_gv) X_ij over the first Width node values.
  template <int Width>
  void contract_row(int gv, int kv, int i, const double* nodes) const {
    using Values = Eigen::Matrix<double, Width, 1>;
    Eigen::Map<Values> sum(v_sum(gv, kv, i));
    sum.setZero();
    for (int j = 0; j < pv(); ++j) {
      sum += basis_v(gv, kv, j) *
             Eigen::Map<const Values>(nodes + static_cast<ptrdiff_t>(node(i, j)) * kNodeStride);
    }
  }
  // The sums S^alpha and the rates (acceleration, velocity, mixed: contract_v's element) at point
  // (gu, gv).
  void point_sums(int gu, int gv, HomogeneousSums& sums, RateValues& rates) const;
  // Stores the density of point (gu, gv).
  void set_density(int gu, int gv, const HomogeneousSums& density);
  // Adds the element's densities through the u, then the v basis to the homogeneous forces.
  void add_element_force();
  // force -= F on (P, w) from the homogeneous forces F^h (homogeneous_point.h), q as set_nodes.
  void subtract_force(const double* q, double* force) const;

 private:
  struct Buffers {
    std::vector<double> node;       // node * kNodeStride
    std::vector<double> force;      // node * 4: the homogeneous force
    std::vector<double> v_sums;     // [gv][kv][i][kNodeStride]: contracted with the v basis
    std::vector<double> density;    // [gu][gv][beta][4]: the points' force densities
    std::vector<double> u_density;  // [gv][kv][i][4]: densities contracted with the u basis
  };
  static Buffers& buffers() {
    thread_local Buffers buffers;
    return buffers;
  }
  // The element's bases (contract_v sets basis_u_ and basis_v_ to its spans' tables)
  double basis_u(int gu, int d, int i) const {
    return basis_u_[static_cast<size_t>((gu * 3 + d) * pu_ + i)];
  }
  double basis_v(int gv, int d, int j) const {
    return basis_v_[static_cast<size_t>((gv * 3 + d) * pv_ + j)];
  }
  int pu() const { return pu_; }
  int pv() const { return pv_; }
  int node(int i, int j) const { return nodes_[static_cast<size_t>(i * pv_ + j)]; }
  double* v_sum(int gv, int kv, int i) const {
    return v_sums_ + static_cast<size_t>(((gv * 3 + kv) * pu() + i) * kNodeStride);
  }
  double* density(int g, int beta) const {
    return density_ + static_cast<size_t>((g * kQuantityCount + beta) * 4);
  }
  double* u_density(int gv, int kv, int i) const {
    return u_density_ + static_cast<size_t>(((gv * 3 + kv) * pu() + i) * 4);
  }

  const DirectionQuadrature& u_;
  const DirectionQuadrature& v_;
  int count_v_;
  int quantities_;
  int order_v_;
  int pu_ = u_.degree + 1;
  int pv_ = v_.degree + 1;
  const double* basis_u_ = nullptr;
  const double* basis_v_ = nullptr;
  std::array<int, kMaxActiveControlPoints> nodes_{};  // node(i, j) of the element
  // The thread's buffers (set_nodes sizes them)
  Buffers& buffers_ = buffers();
  double* v_sums_ = nullptr;
  double* density_ = nullptr;
  double* u_density_ = nullptr;
};

void ElementContraction::set_nodes(const double* q, const double* qd, const double* a, int count) {
  Buffers& b = buffers_;
  const auto nodes = static_cast<size_t>(count);
  b.node.resize(nodes * kNodeStride);
  b.force.assign(nodes * 4, 0.0);
  b.v_sums.resize(static_cast<size_t>(v_.points_per_span * 3 * pu() * kNodeStride));
  b.density.resize(
      static_cast<size_t>(u_.points_per_span * v_.points_per_span * kQuantityCount * 4));
  b.u_density.resize(static_cast<size_t>(v_.points_per_span * 3 * pu() * 4));
  v_sums_ = b.v_sums.data();
  density_ = b.density.data();
  u_density_ = b.u_density.data();
  for (size_t i = 0; i < nodes; ++i) {
    const double* c = q + 4 * i;
    const double* da = a + 4 * i;
    const double* dv = qd + 4 * i;
    double* out = b.node.data() + i * kNodeStride;
    for (int r = 0; r < 3; ++r) {
      out[kPoint + r] = c[3] * c[r];
      out[kAcceleration + r] = c[3] * da[r] + da[3] * c[r];
      out[kVelocity + r] = c[3] * dv[r] + dv[3] * c[r];
      out[kMixed + r] = dv[3] * dv[r];
    }
    out[kPoint + 3] = c[3];
    out[kAcceleration + 3] = da[3];
    out[kVelocity + 3] = dv[3];
    out[kNodeStride - 1] = 0.0;
  }
}

void ElementContraction::contract_v(int su, int sv) {
  // v_sums[gv][kv][i] = sum_j N_j^(kv)(v_gv) X_ij (the rates only for kv = 0: the mass, damping
  // and inertia are quantity 0)
  basis_u_ = &u_.basis[static_cast<size_t>(su * u_.points_per_span * 3 * pu_)];
  basis_v_ = &v_.basis[static_cast<size_t>(sv * v_.points_per_span * 3 * pv_)];
  for (int i = 0; i < pu_; ++i) {
    for (int j = 0; j < pv_; ++j) {
      nodes_[static_cast<size_t>(i * pv_ + j)] =
          u_.control_point[static_cast<size_t>(su * pu_ + i)] * count_v_ +
          v_.control_point[static_cast<size_t>(sv * pv_ + j)];
    }
  }
  const std::vector<double>& nodes = buffers_.node;
  for (int gv = 0; gv < v_.points_per_span; ++gv) {
    for (int kv = 0; kv <= order_v_; ++kv) {
      for (int i = 0; i < pu(); ++i) {
        if (kv == 0) {
          contract_row<kNodeStride>(gv, kv, i, nodes.data());
        } else {
          contract_row<4>(gv, kv, i, nodes.data());  // (w P, w) only
        }
      }
    }
  }
}

void ElementContraction::point_sums(int gu, int gv, HomogeneousSums& sums,
                                    RateValues& rates) const {
  rates.setZero();
  for (int alpha = 0; alpha < quantities_; ++alpha) {
    auto& sum = sums[static_cast<size_t>(alpha)];
    sum.setZero();
    const int kv = kQuantityOrderV[static_cast<size_t>(alpha)];
    if (kv > order_v_) {
      continue;
    }
    const int ku = kQuantityOrderU[static_cast<size_t>(alpha)];
    for (int i = 0; i < pu(); ++i) {
      const double* x = v_sum(gv, kv, i);
      const double b = basis_u(gu, ku, i);
      sum += b * Eigen::Map<const Eigen::Vector4d>(x + kPoint);
      if (alpha == 0) {
        rates += b * Eigen::Map<const RateValues>(x + kAcceleration);
      }
    }
  }
}

void ElementContraction::set_density(int gu, int gv, const HomogeneousSums& density_values) {
  const int g = gu * v_.points_per_span + gv;
  for (int beta = 0; beta < quantities_; ++beta) {
    Eigen::Map<Eigen::Vector4d>(density(g, beta)) = density_values[static_cast<size_t>(beta)];
  }
}

void ElementContraction::add_element_force() {
  // F^h_ij += sum_points N_i^(ku)(u) N_j^(kv)(v) density: through the u basis, then the v basis
  Buffers& b = buffers_;
  std::fill(b.u_density.begin(), b.u_density.end(), 0.0);
  for (int beta = 0; beta < quantities_; ++beta) {
    const int kv = kQuantityOrderV[static_cast<size_t>(beta)];
    if (kv > order_v_) {
      continue;
    }
    const int ku = kQuantityOrderU[static_cast<size_t>(beta)];
    for (int gv = 0; gv < v_.points_per_span; ++gv) {
      for (int i = 0; i < pu(); ++i) {
        Eigen::Map<Eigen::Vector4d> out(u_density(gv, kv, i));
        for (int gu = 0; gu < u_.points_per_span; ++gu) {
          out += basis_u(gu, ku, i) *
                 Eigen::Map<const Eigen::Vector4d>(density(gu * v_.points_per_span + gv, beta));
        }
      }
    }
  }
  for (int i = 0; i < pu(); ++i) {
    for (int j = 0; j < pv(); ++j) {
      Eigen::Vector4d sum = Eigen::Vector4d::Zero();
      for (int gv = 0; gv < v_.points_per_span; ++gv) {
        for (int kv = 0; kv <= order_v_; ++kv) {
          sum += basis_v(gv, kv, j) * Eigen::Map<const Eigen::Vector4d>(u_density(gv, kv, i));
        }
      }
      Eigen::Map<Eigen::Vector4d>(&b.force[static_cast<size_t>(node(i, j) * 4)]) += sum;
    }
  }
}

void ElementContraction::subtract_force(const double* q, double* force) const {
  // (P, w) from (w P, w): F_P = w F^h_xyz, F_w = P . F^h_xyz + F^h_w
  const std::vector<double>& homogeneous = buffers_.force;
  const size_t nodes = homogeneous.size() / 4;
  for (size_t i = 0; i < nodes; ++i) {
    const Eigen::Map<const Eigen::Vector4d> f(&homogeneous[i * 4]);
    const Eigen::Map<const Eigen::Vector3d> position(q + 4 * i);
    Eigen::Map<Eigen::Vector3d>(force + 4 * i) -= q[4 * i + 3] * f.head<3>();
    force[4 * i + 3] -= position.dot(f.head<3>()) + f[3];
  }
}

}  // namespace

void DNurbsModel::add_step_residual(ConstVectorRef q, ConstVectorRef qd, ConstVectorRef a,
                                    bool inertial, VectorRef force) const {
  if (mode_ == WeightMode::kFixed) {
    Model::add_step_residual(q, qd, a, inertial, force);
    return;
  }
  check_velocity(qd);
  check_velocity(a);
  if (force.size() != velocity_count() || q.size() != coordinate_count()) {
    throw make_error("force and coordinate vectors have ", force.size(), " and ", q.size(),
                     " entries, the model has ", velocity_count());
  }
  // M a + D qd = integral J_0^T (mu J_0 a + gamma J_0 qd) + m_w a_w at the Gauss points of
  // assemble_step, with its forces, all as one J^T h per point in homogeneous form.
  add_weight_anchor_force(q, force);
  for (int i = 0; i < control_point_count_; ++i) {
    force[4 * i + 3] -= weight_inertia_ * a[4 * i + 3];
  }
  const int order = stiffness_order();
  const int order_v = surface_ ? std::min(order, 2) : 0;  // highest v derivative with a basis
  ElementContraction contraction(table_u_, table_v_, count_v_, quantity_count(order), order_v);
  contraction.set_nodes(q.data(), qd.data(), a.data(), control_point_count_);
  HomogeneousSums sums{};
  HomogeneousSums density{};
  HomogeneousPoint point;
  RateValues rates;
  std::array<Eigen::Vector3d, kQuantityCount> h{};
  for (int e = 0; e < element_count(); ++e) {
    contraction.contract_v(e / table_v_.span_count, e % table_v_.span_count);
    for (int gu = 0; gu < table_u_.points_per_span; ++gu) {
      for (int gv = 0; gv < table_v_.points_per_span; ++gv) {
        const int g = gu * table_v_.points_per_span + gv;
        contraction.point_sums(gu, gv, sums, rates);
        homogeneous_point(sums, order, order_v, point);
        const double weight = quadrature_weight(e, g);
        const double* m =
            &material_[static_cast<size_t>((e * points_per_element() + g) * kMaterialStride)];
        const Eigen::Vector3d velocity = rational_rate(point, rates.segment<4>(4));
        h[0] = weight * (m[0] * rational_rate(point, rates.segment<4>(0)) + m[1] * velocity);
        if (inertial) {
          // Jdot qd = (2 / W) (sum_a N_a wdot_a Pdot_a - Wdot xdot), as subtract_inertial_force
          h[0] += (2.0 * weight * m[0] * point.inverse_weight[0]) *
                  (rates.segment<3>(8) - rates[7] * velocity);
        }
        const double* rest = rest_at(e, g);
        for (int alpha = 1; alpha < point.quantities; ++alpha) {
          const auto index = static_cast<size_t>(alpha);
          h[index].setZero();
          if (has_stiffness_[index]) {
            h[index] = weight * m[2 + alpha] * rest_difference(point.point[index], alpha, rest);
          }
        }
        homogeneous_force_density(point, h, density);
        contraction.set_density(gu, gv, density);
      }
    }
    contraction.add_element_force();
  }
  contraction.subtract_force(q.data(), force.data());
}

}  // namespace dnurbs
