#pragma once
// What the swung-model tests share: a varying thin-plate material, random states and
// velocities from fixed seeds, the chain rule from swung coordinates to the tensor-product
// twin's, and the twin restricted to swung motions as a Model (the reference of the spring-pull
// test): every quantity of the tensor-product D-NURBS surface (dynamics/dnurbs/dnurbs_surface.h)
// composed with the map q -> Q(q) from swung coordinates to the twin's control points.

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/swung/dnurbs_swung_surface.h"
#include "dnurbs/nurbs/swung_shapes.h"
#include "tests/nurbs/swung_sample_shapes.h"

namespace dnurbs::testing {

inline DNurbsSurfaceMaterial plate_material() {
  DNurbsSurfaceMaterial material;
  material.mass_density =
      MaterialFunction([](const Eigen::Vector2d& u) { return 1.0 + 0.5 * u.x() * u.y(); });
  material.damping_density = 0.3;
  material.a10 = 1.0;
  material.a01 = 0.5;
  material.b20 = 0.02;
  material.b11 = 0.01;
  material.b02 = 0.03;
  return material;
}

inline DNurbsSwungSettings settings_for(WeightMode mode) {
  DNurbsSwungSettings settings;
  settings.weight_mode = mode;
  return settings;
}

inline Eigen::VectorXd random_vector(Eigen::Index size, unsigned seed) {
  std::srand(seed);
  return Eigen::VectorXd::Random(size);
}

/// A state away from the prototype: q moved by a smooth random perturbation.
inline Eigen::VectorXd perturbed(const DNurbsSwungSurface& model, unsigned seed) {
  Eigen::VectorXd q = model.initial_coordinates();
  q += 0.05 * random_vector(q.size(), seed);
  return q;
}

/// The shapes and weight modes the model tests run on.
struct ModelCase {
  const char* name;
  SwungSurface surface;
  WeightMode mode;
};

inline std::vector<ModelCase> model_cases() {
  return {{"random, fixed weights", random_swung_surface(3, 2, 61, true), WeightMode::kFixed},
          {"random, free weights", random_swung_surface(3, 2, 61, true), WeightMode::kFree},
          {"sphere, fixed weights", swung_sphere(1.2), WeightMode::kFixed},
          {"torus, free weights", swung_torus(2.0, 0.6), WeightMode::kFree}};
}

/// Largest |x_a(u) - x_b(u)| over a 21 x 21 grid of the parameter domain [0, 1]^2.
inline double largest_distance(const Model& a, const Eigen::VectorXd& qa, const Model& b,
                               const Eigen::VectorXd& qb) {
  double largest = 0.0;
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 20; ++j) {
      const Eigen::Vector2d u(i / 20.0, j / 20.0);
      largest = std::max(largest, (a.position(qa, u) - b.position(qb, u)).norm());
    }
  }
  return largest;
}

/// Largest spread over v of the distance from the z axis and of z, over the (u_count + 1) x
/// v_count parameters (i / u_count, j / v_count): zero for a surface of revolution about z.
inline double rotational_asymmetry(const Model& model, const Eigen::VectorXd& q, int u_count = 50,
                                   int v_count = 97) {
  double spread = 0.0;
  for (int i = 0; i <= u_count; ++i) {
    Eigen::Vector2d low(1e300, 1e300);
    Eigen::Vector2d high(-1e300, -1e300);
    for (int j = 0; j < v_count; ++j) {
      const Eigen::Vector3d x = model.position(
          q, Eigen::Vector2d(i / static_cast<double>(u_count), j / static_cast<double>(v_count)));
      const Eigen::Vector2d radius_height(x.head<2>().norm(), x.z());
      low = low.cwiseMin(radius_height);
      high = high.cwiseMax(radius_height);
    }
    spread = std::max(spread, (high - low).maxCoeff());
  }
  return spread;
}

/// The tensor-product twin's coordinates Q(q): control point (i, j) = (alpha x_i X_j,
/// alpha x_i Y_j, z_i) at 3 (i n + j) (fixed weights) or 4 (i n + j) with weight w_i W_j.
inline Eigen::VectorXd twin_coordinates(const DNurbsSwungSurface& model, const Eigen::VectorXd& q) {
  const SwungLayout& layout = model.layout();
  const double alpha = model.initial_surface().alpha();
  const bool free = layout.mode == WeightMode::kFree;
  const int per_node = free ? 4 : 3;
  const int n = layout.trajectory_count;
  Eigen::VectorXd twin(static_cast<Eigen::Index>(layout.profile_count) * n * per_node);
  for (int i = 0; i < layout.profile_count; ++i) {
    const int p = layout.profile_offset(i);
    for (int j = 0; j < n; ++j) {
      const int t = layout.trajectory_offset(j);
      const int row = (i * n + j) * per_node;
      twin.segment<3>(row) << alpha * q[p] * q[t], alpha * q[p] * q[t + 1], q[p + 1];
      if (free) {
        twin[row + 3] = q[p + 2] * q[t + 2];
      }
    }
  }
  return twin;
}

/// chain = dQ/dq, #twin coordinates by #swung coordinates.
inline Eigen::MatrixXd twin_chain_rule(const DNurbsSwungSurface& model, const Eigen::VectorXd& q) {
  const SwungLayout& layout = model.layout();
  const double alpha = model.initial_surface().alpha();
  const bool free = layout.mode == WeightMode::kFree;
  const int per_node = free ? 4 : 3;
  const int n = layout.trajectory_count;
  Eigen::MatrixXd chain = Eigen::MatrixXd::Zero(
      static_cast<Eigen::Index>(layout.profile_count) * n * per_node, q.size());
  for (int i = 0; i < layout.profile_count; ++i) {
    const int p = layout.profile_offset(i);
    for (int j = 0; j < n; ++j) {
      const int t = layout.trajectory_offset(j);
      const int row = (i * n + j) * per_node;
      chain(row, p) = alpha * q[t];
      chain(row + 1, p) = alpha * q[t + 1];
      chain(row + 2, p + 1) = 1.0;
      chain(row, t) = alpha * q[p];
      chain(row + 1, t + 1) = alpha * q[p];
      if (free) {
        chain(row + 3, p + 2) = q[t + 2];
        chain(row + 3, t + 2) = q[p + 2];
      }
    }
  }
  return chain;
}

/// The tensor-product twin restricted to swung motions, fixed weights: coordinates q of the swung
/// model, twin coordinates Q(q) (bilinear in the two curves), C = dQ/dq and
/// Qdd = C qdd + Cdot qd with Cdot qd = (2 alpha xd_i Xd_j, 2 alpha xd_i Yd_j, 0). The twin's L,
/// M, D, K do not depend on Q (fixed weights), so by the chain rule
///   x(q, u) = L_twin(u) Q(q),  L = L_twin C,  Ldot qd = L_twin (Cdot qd),
///   M = C^T M_twin C,  D = C^T D_twin C,  K (Gauss-Newton) = C^T K_twin C,
///   E = E_twin(Q),  f_int = C^T f_int,twin(Q),  g = -C^T M_twin (Cdot qd),
///   applied forces C^T f_twin.
/// It shares nothing with the swung model's own assembly (swung Jacobians, separable forms) but
/// the shape; the swung model's fixed coordinates are copied.
class RestrictedTwin : public Model {
 public:
  /// `material` must be the one the swung model was built with.
  RestrictedTwin(const DNurbsSwungSurface& swung, const DNurbsSurfaceMaterial& material)
      : swung_(swung), twin_(swung.initial_surface().to_nurbs_surface(), material) {
    for (const int k : swung.fixed_coordinates()) {
      fix_coordinate(k);
    }
  }

  std::unique_ptr<Model> clone() const override { return std::make_unique<RestrictedTwin>(*this); }
  int coordinate_count() const override { return swung_.coordinate_count(); }
  Eigen::VectorXd initial_coordinates() const override { return swung_.initial_coordinates(); }
  int parametric_dimension() const override { return 2; }
  Eigen::Vector3d position(ConstVectorRef q, const Eigen::Vector2d& u) const override {
    return twin_.position(twin_q(q), u);
  }
  SparseMatrix position_jacobian(ConstVectorRef q, const Eigen::Vector2d& u) const override {
    return (Eigen::MatrixXd(twin_.position_jacobian(twin_q(q), u)) * chain(q)).sparseView();
  }
  Eigen::Vector3d jacobian_rate_times_velocity(ConstVectorRef q, ConstVectorRef qd,
                                               const Eigen::Vector2d& u) const override {
    return twin_.position_jacobian(twin_q(q), u) * chain_rate(qd);
  }
  bool matrices_are_constant() const override { return false; }
  void assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const override {
    const ModelMatrices& twin = *twin_.constant_matrices();
    const Eigen::MatrixXd c = chain(q);
    matrices.mass = (c.transpose() * Eigen::MatrixXd(twin.mass) * c).sparseView();
    matrices.damping = (c.transpose() * Eigen::MatrixXd(twin.damping) * c).sparseView();
    matrices.stiffness = (c.transpose() * Eigen::MatrixXd(twin.stiffness) * c).sparseView();
  }
  void add_internal_force(ConstVectorRef q, VectorRef force) const override {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(twin_.coordinate_count());
    twin_.add_internal_force(twin_q(q), f);
    force += chain(q).transpose() * f;
  }
  double potential_energy(ConstVectorRef q) const override {
    return twin_.potential_energy(twin_q(q));
  }
  void add_inertial_force(ConstVectorRef q, ConstVectorRef qd, VectorRef force) const override {
    const ModelMatrices& twin = *twin_.constant_matrices();
    force -= chain(q).transpose() * (twin.mass * chain_rate(qd));
  }
  void add_point_force(ConstVectorRef q, const Eigen::Vector2d& u, const Eigen::Vector3d& f,
                       VectorRef force) const override {
    Eigen::VectorXd twin_force = Eigen::VectorXd::Zero(twin_.coordinate_count());
    twin_.add_point_force(twin_q(q), u, f, twin_force);
    force += chain(q).transpose() * twin_force;
  }
  void add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                             VectorRef force) const override {
    Eigen::VectorXd twin_force = Eigen::VectorXd::Zero(twin_.coordinate_count());
    twin_.add_distributed_force(twin_q(q), density, twin_force);
    force += chain(q).transpose() * twin_force;
  }

 private:
  Eigen::VectorXd twin_q(ConstVectorRef q) const { return twin_coordinates(swung_, q); }
  Eigen::MatrixXd chain(ConstVectorRef q) const { return twin_chain_rule(swung_, q); }
  // Cdot qd: the velocity-product part of Qdd, twice the bilinear term of the two curves' rates.
  Eigen::VectorXd chain_rate(ConstVectorRef qd) const {
    Eigen::VectorXd rate = twin_coordinates(swung_, qd);
    for (Eigen::Index k = 2; k < rate.size(); k += 3) {
      rate[k] = 0.0;  // z_i is linear in q
    }
    return 2.0 * rate;
  }

  DNurbsSwungSurface swung_;
  DNurbsSurface twin_;
};

}  // namespace dnurbs::testing
