#include "dnurbs/dynamics/triangular/triangular_dnurbs_surface.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/triangular/triangular_free_weight_terms.h"
#include "dnurbs/dynamics/triangular/triangular_local_sculpting.h"

namespace dnurbs {

namespace {

// Element matrices of one domain triangle (local count squared entries, or 16 times that in
// 4 x 4 blocks for free weights), cleared per element.
struct ElementMatrices {
  explicit ElementMatrices(size_t size) : mass(size), damping(size), stiffness(size) {}
  void clear() {
    std::fill(mass.begin(), mass.end(), 0.0);
    std::fill(damping.begin(), damping.end(), 0.0);
    std::fill(stiffness.begin(), stiffness.end(), 0.0);
  }
  std::vector<double> mass;
  std::vector<double> damping;
  std::vector<double> stiffness;
};

// The view of the rational basis that RationalControlNetModel works with.
RationalPoint rational_point(const TriangularBasisValues& values,
                             const TriangularRationalJacobian& jacobian, bool weight_columns) {
  static_assert(decltype(TriangularBasisValues::value)::RowsAtCompileTime ==
                    RationalPoint::kQuantityRows &&
                decltype(TriangularRationalJacobian::rational)::RowsAtCompileTime ==
                    RationalPoint::kQuantityRows);
  return {values.count,
          values.function.data(),
          values.value.data(),
          jacobian.rational.data(),
          weight_columns ? jacobian.weight_column[0].data() : nullptr,
          jacobian.weight_sum,
          jacobian.point[0]};
}

}  // namespace

TriangularDNurbsSurface::TriangularDNurbsSurface(const TriangularNurbsSurface& surface,
                                                 const DNurbsSurfaceMaterial& material,
                                                 const TriangularDNurbsSettings& settings)
    : RationalControlNetModel(settings.weight_mode, surface.control_point_count(),
                              settings.minimum_weight),
      surface_(surface),
      settings_(settings) {
  // Validate the settings and the weights -------------------------------------------------
  if (!(minimum_weight_ > 0.0) || !std::isfinite(minimum_weight_)) {
    throw make_error("minimum weight ", minimum_weight_, " is not a positive finite number");
  }
  if (!(settings.weight_inertia >= 0.0) || !std::isfinite(settings.weight_inertia)) {
    throw make_error("weight inertia ", settings.weight_inertia,
                     " is not a non-negative finite number");
  }
  if (settings.quadrature_degree < 0 || settings.quadrature_degree > kMaxDunavantDegree) {
    throw make_error("quadrature degree ", settings.quadrature_degree, " is outside 0..",
                     kMaxDunavantDegree, " (0 = 2 n)");
  }
  if (settings.quadrature_subdivisions < 0 || settings.quadrature_subdivisions > 64) {
    throw make_error("quadrature subdivisions ", settings.quadrature_subdivisions,
                     " is outside 0..64 (0 = exact polynomial cells)");
  }
  if (settings.tessellation_subdivisions < 0 || settings.tessellation_subdivisions > 1024) {
    throw make_error("tessellation subdivisions ", settings.tessellation_subdivisions,
                     " is outside 0..1024 (0 = from the requested resolution)");
  }
  if (!(settings.tessellation_max_error >= 0.0) ||
      !std::isfinite(settings.tessellation_max_error)) {
    throw make_error("tessellation max error ", settings.tessellation_max_error,
                     " is not a non-negative finite number (0 = uniform)");
  }
  if (settings.tessellation_max_level < 1 || settings.tessellation_max_level > 40) {
    throw make_error("tessellation max level ", settings.tessellation_max_level,
                     " is outside 1..40");
  }
  const Eigen::VectorXd& weights = surface.weights();
  if (mode_ == WeightMode::kFree) {
    for (int i = 0; i < control_point_count_; ++i) {
      if (weights[i] < minimum_weight_) {
        throw make_error("free weight ", i, " is ", weights[i], ", below the minimum weight ",
                         minimum_weight_);
      }
    }
  }

  // Quadrature points with the cached B-splines (derivatives up to the stiffness order) -----
  // Stiffness weights of x_u, x_v, x_uu, x_uv, x_vv: the mixed term enters the thin plate
  // under tension as 2 b11 |x_uv|^2.
  const std::array<const MaterialFunction*, 6> stiffness = {
      nullptr, &material.a10, &material.a01, &material.b20, &material.b11, &material.b02};
  const std::array<double, 6> factor = {0.0, 1.0, 1.0, 1.0, 2.0, 1.0};
  has_damping_ = !material.damping_density.is_zero();
  for (int alpha = 1; alpha < 6; ++alpha) {
    has_stiffness_[static_cast<size_t>(alpha)] = !stiffness[static_cast<size_t>(alpha)]->is_zero();
  }
  const int n = surface.basis().degree();
  const int degree = settings.quadrature_degree > 0 ? settings.quadrature_degree
                                                    : std::min(2 * n, kMaxDunavantDegree);
  const int subdivisions = settings.quadrature_subdivisions;
  // Order 1 is always cached: distributed forces need the tangents.
  quadrature_ = std::make_shared<const TriangularQuadrature>(
      surface.shared_basis(), degree, subdivisions, std::max(1, stiffness_order()));

  // Material values at every quadrature point, checked once --------------------------------
  const std::array<const char*, 6> names = {"", "a10", "a01", "b20", "b11", "b02"};
  material_.assign(static_cast<size_t>(quadrature_->point_count()) * kMaterialStride, 0.0);
  for (int p = 0; p < quadrature_->point_count(); ++p) {
    const Eigen::Vector2d& u = quadrature_->parameter(p);
    double* m = &material_[static_cast<size_t>(p) * kMaterialStride];
    m[0] = material.mass_density.checked(u, "mass density", true);
    m[1] = material.damping_density.checked(u, "damping density", true);
    for (int alpha = 1; alpha < 6; ++alpha) {
      if (has_stiffness_[static_cast<size_t>(alpha)]) {
        const auto k = static_cast<size_t>(alpha);
        m[1 + alpha] = factor[k] * stiffness[k]->checked(u, names[k], true);
      }
    }
  }
  pattern_ = quadrature_->assembly_pattern();

  // Coordinates: q = [P_0, P_1, ...] or [P_0, w_0, P_1, w_1, ...], the constant matrices of
  // fixed weights or the block pattern of free ones ------------------------------------------
  build_coordinates(surface.control_points(), weights, pattern_.scalar, settings.weight_inertia,
                    0.0, settings.fix_weight_gauge);
  if (settings.initial_shape_at_rest) {
    set_rest_shape(initial_coordinates_);
  }
  set_plastic_flow(settings.plastic_flow);
}

std::unique_ptr<Model> TriangularDNurbsSurface::clone() const {
  return std::make_unique<TriangularDNurbsSurface>(*this);
}

// ---------------------------------------------------------------------------------------------
// Points and Jacobians

TriangularControlNet TriangularDNurbsSurface::control_net(const ConstVectorRef& q) const {
  check_coordinates(q);
  // Free weights sit after each point's position in q; fixed ones in their own vector.
  const bool free = mode_ == WeightMode::kFree;
  return {q.data(), per_control_point_, free ? q.data() + 3 : fixed_weights_.data(), free ? 4 : 1};
}

int TriangularDNurbsSurface::stiffness_order() const {
  int order = 0;
  for (int alpha = 1; alpha < 6; ++alpha) {
    if (has_stiffness_[static_cast<size_t>(alpha)]) {
      order = alpha >= 3 ? 2 : std::max(order, 1);
    }
  }
  return order;
}

template <typename Visit>
void TriangularDNurbsSurface::for_each_point_of(int e, const TriangularControlNet& net, int order,
                                                bool weight_columns, Visit&& visit) const {
  TriangularBasisValues values;
  TriangularRationalJacobian jacobian;
  std::vector<int> local;
  for (int p = quadrature_->element_begin(e); p < quadrature_->element_begin(e + 1); ++p) {
    quadrature_->basis_at(p, values, local);
    triangular_rational_jacobian(values, order, net, weight_columns, jacobian);
    visit(p, values, jacobian, local);
  }
}

template <typename Visit>
void TriangularDNurbsSurface::for_each_point(const TriangularControlNet& net, int order,
                                             bool weight_columns, Visit&& visit) const {
  for (int e = 0; e < quadrature_->element_count(); ++e) {
    for_each_point_of(e, net, order, weight_columns, visit);
  }
}

void TriangularDNurbsSurface::jacobian_at(const Eigen::Vector2d& u, const TriangularControlNet& net,
                                          int order, bool weight_columns,
                                          TriangularRationalJacobian& jacobian,
                                          TriangularBasisValues& values) const {
  surface_.basis().evaluate(u, order, values);
  triangular_rational_jacobian(values, order, net, weight_columns, jacobian);
}

void TriangularDNurbsSurface::visit_rational_point(
    ConstVectorRef q, const Eigen::Vector2d& u, bool weight_columns,
    const std::function<void(const RationalPoint&)>& visit) const {
  TriangularBasisValues values;
  TriangularRationalJacobian jacobian;
  jacobian_at(u, control_net(q), 0, weight_columns, jacobian, values);
  visit(rational_point(values, jacobian, weight_columns));
}

// ---------------------------------------------------------------------------------------------
// Matrices

void TriangularDNurbsSurface::assemble_scalar(ModelMatrices& scalar) const {
  // Qin & Terzopoulos 1997, section 4, with fixed weights: S_M = integral mu R_a R_b,
  // S_D = integral gamma R_a R_b, S_K = integral sum_alpha k_alpha R_a^alpha R_b^alpha, each
  // a sum over the quadrature points of every domain triangle.
  const int local = pattern_.local_count;
  ElementMatrices element(static_cast<size_t>(local) * static_cast<size_t>(local));
  scalar.mass = pattern_.scalar;
  scalar.stiffness = pattern_.scalar;
  scalar.damping =
      has_damping_ ? pattern_.scalar : SparseMatrix(control_point_count_, control_point_count_);
  const TriangularControlNet net = control_net(initial_coordinates_);
  for (int e = 0; e < quadrature_->element_count(); ++e) {
    element.clear();
    for_each_point_of(e, net, stiffness_order(), false,
                      [&](int p, const TriangularBasisValues& values,
                          const TriangularRationalJacobian& jacobian, const std::vector<int>& at) {
                        const double weight = quadrature_->weight(p);
                        const double* m = material_at(p);
                        const auto& rational = jacobian.rational;
                        for (int i = 0; i < values.count; ++i) {
                          const auto row = static_cast<size_t>(at[static_cast<size_t>(i)]) *
                                           static_cast<size_t>(local);
                          for (int j = 0; j < values.count; ++j) {
                            const size_t index =
                                row + static_cast<size_t>(at[static_cast<size_t>(j)]);
                            // Products of two basis values first: exactly symmetric matrices.
                            const double product = weight * (rational(0, i) * rational(0, j));
                            element.mass[index] += m[0] * product;
                            element.damping[index] += m[1] * product;
                            double k = 0.0;
                            for (int alpha = 1; alpha < 6; ++alpha) {
                              if (has_stiffness_[static_cast<size_t>(alpha)]) {
                                k += m[1 + alpha] * (rational(alpha, i) * rational(alpha, j));
                              }
                            }
                            element.stiffness[index] += weight * k;
                          }
                        }
                      });
    // Scatter the element matrices (only the element's own local pairs) into the pattern.
    const int element_local = static_cast<int>(quadrature_->element_functions(e).size());
    const int* to_value = &pattern_.local_to_value[static_cast<size_t>(e) * element.mass.size()];
    for (int a = 0; a < element_local; ++a) {
      for (int b = 0; b < element_local; ++b) {
        const auto i = static_cast<size_t>(a) * static_cast<size_t>(local) + static_cast<size_t>(b);
        scalar.mass.valuePtr()[to_value[i]] += element.mass[i];
        scalar.stiffness.valuePtr()[to_value[i]] += element.stiffness[i];
        if (has_damping_) {
          scalar.damping.valuePtr()[to_value[i]] += element.damping[i];
        }
      }
    }
  }
}

void TriangularDNurbsSurface::assemble_free(ConstVectorRef q, ModelMatrices& matrices) const {
  // Free weights: 4 x 4 blocks [[R_a R_b I_3, R_a E_b], [E_a^T R_b, E_a . E_b]] per quantity.
  const int local = pattern_.local_count;
  ElementMatrices element(16 * static_cast<size_t>(local) * static_cast<size_t>(local));
  reset_to_pattern(block_pattern_, true, matrices.mass);
  reset_to_pattern(block_pattern_, has_damping_, matrices.damping);
  reset_to_pattern(block_pattern_, true, matrices.stiffness);
  const TriangularControlNet net = control_net(q);
  for (int e = 0; e < quadrature_->element_count(); ++e) {
    element.clear();
    for_each_point_of(
        e, net, stiffness_order(), true,
        [&](int p, const TriangularBasisValues& values, const TriangularRationalJacobian& jacobian,
            const std::vector<int>& at) {
          const double weight = quadrature_->weight(p);
          const double* m = material_at(p);
          std::array<double, 6> coefficient{};
          coefficient[0] = weight * m[0];
          add_free_weight_terms(jacobian, coefficient, values.count, at, local, element.mass);
          if (has_damping_) {
            coefficient[0] = weight * m[1];
            add_free_weight_terms(jacobian, coefficient, values.count, at, local, element.damping);
          }
          coefficient[0] = 0.0;
          for (int alpha = 1; alpha < 6; ++alpha) {
            coefficient[static_cast<size_t>(alpha)] =
                has_stiffness_[static_cast<size_t>(alpha)] ? weight * m[1 + alpha] : 0.0;
          }
          add_free_weight_terms(jacobian, coefficient, values.count, at, local, element.stiffness);
        });
    const int element_local = static_cast<int>(quadrature_->element_functions(e).size());
    scatter_free_weight_block(pattern_, block_pattern_, e, element_local, element.mass,
                              matrices.mass);
    scatter_free_weight_block(pattern_, block_pattern_, e, element_local, element.stiffness,
                              matrices.stiffness);
    if (has_damping_) {
      scatter_free_weight_block(pattern_, block_pattern_, e, element_local, element.damping,
                                matrices.damping);
    }
  }
  for (const int index : weight_diagonal_) {
    matrices.mass.valuePtr()[index] += weight_inertia_;
  }
}

// ---------------------------------------------------------------------------------------------
// Forces and energy

void TriangularDNurbsSurface::add_internal_force(ConstVectorRef q, VectorRef force) const {
  if (mode_ == WeightMode::kFixed) {
    // f_int = -K (q - q_r) = -K q + K q_r
    force.noalias() -= expanded_.stiffness * q;
    if (has_rest_shape()) {
      force += rest_force_;
    }
    return;
  }
  // f_int = -dE/dq = -integral sum_alpha k_alpha J_alpha^T (x^alpha - x^alpha_rest).
  if (stiffness_order() == 0) {
    return;
  }
  for_each_point(control_net(q), stiffness_order(), true,
                 [&](int p, const TriangularBasisValues& values,
                     const TriangularRationalJacobian& jacobian, const std::vector<int>&) {
                   const double* m = material_at(p);
                   for (int alpha = 1; alpha < 6; ++alpha) {
                     if (has_stiffness_[static_cast<size_t>(alpha)]) {
                       const Eigen::Vector3d x = quadrature_->weight(p) * m[1 + alpha] *
                                                 rest_difference(p, jacobian, alpha);
                       add_transposed_jacobian_times(values, jacobian, alpha, true, -x, force);
                     }
                   }
                 });
}

Eigen::Vector3d TriangularDNurbsSurface::rest_difference(int p,
                                                         const TriangularRationalJacobian& jacobian,
                                                         int alpha) const {
  const Eigen::Vector3d& x = jacobian.point[static_cast<size_t>(alpha)];
  if (rest_derivatives_.empty()) {
    return x;
  }
  return x - Eigen::Map<const Eigen::Vector3d>(
                 &rest_derivatives_[static_cast<size_t>(p * kRestStride + 3 * (alpha - 1))]);
}

void TriangularDNurbsSurface::store_rest_derivatives(ConstVectorRef q_rest) {
  // x^alpha(q_r) at every quadrature point of the energy (rest_difference)
  std::vector<double> rest(static_cast<size_t>(quadrature_->point_count() * kRestStride), 0.0);
  if (stiffness_order() > 0) {
    for_each_point(
        control_net(q_rest), stiffness_order(), false,
        [&](int p, const TriangularBasisValues&, const TriangularRationalJacobian& jacobian,
            const std::vector<int>&) {
          for (int alpha = 1; alpha < 6; ++alpha) {
            if (has_stiffness_[static_cast<size_t>(alpha)]) {
              Eigen::Vector3d::Map(&rest[static_cast<size_t>(p * kRestStride + 3 * (alpha - 1))]) =
                  jacobian.point[static_cast<size_t>(alpha)];
            }
          }
        });
  }
  rest_derivatives_ = std::move(rest);
}

double TriangularDNurbsSurface::quadrature_potential_energy(ConstVectorRef q) const {
  // E = (1/2) integral sum_alpha k_alpha |x^alpha|^2 at the quadrature points.
  double energy = 0.0;
  if (stiffness_order() == 0) {
    return energy;
  }
  for_each_point(control_net(q), stiffness_order(), false,
                 [&](int p, const TriangularBasisValues&,
                     const TriangularRationalJacobian& jacobian, const std::vector<int>&) {
                   const double* m = material_at(p);
                   double density = 0.0;
                   for (int alpha = 1; alpha < 6; ++alpha) {
                     if (has_stiffness_[static_cast<size_t>(alpha)]) {
                       density += m[1 + alpha] * rest_difference(p, jacobian, alpha).squaredNorm();
                     }
                   }
                   energy += 0.5 * quadrature_->weight(p) * density;
                 });
  return energy;
}

void TriangularDNurbsSurface::add_inertial_force(ConstVectorRef q, ConstVectorRef qd,
                                                 VectorRef force) const {
  if (mode_ == WeightMode::kFixed) {
    return;
  }
  // g = -integral mu J^T (Jdot qd).
  check_velocity(qd);
  for_each_point(control_net(q), 0, true,
                 [&](int p, const TriangularBasisValues& values,
                     const TriangularRationalJacobian& jacobian, const std::vector<int>&) {
                   const double mu = material_at(p)[0] * quadrature_->weight(p);
                   const Eigen::Vector3d h =
                       mu * free_weight_acceleration(rational_point(values, jacobian, true), qd);
                   add_transposed_jacobian_times(values, jacobian, 0, true, -h, force);
                 });
}

void TriangularDNurbsSurface::add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                                                    VectorRef force) const {
  // f_q = integral J^T f(u) du by the model's quadrature rule.
  const bool free = mode_ == WeightMode::kFree;
  MaterialSample sample;
  for_each_point(control_net(q), 1, free,
                 [&](int p, const TriangularBasisValues& values,
                     const TriangularRationalJacobian& jacobian, const std::vector<int>&) {
                   sample.parameter = quadrature_->parameter(p);
                   sample.position = jacobian.point[0];
                   sample.tangent_u = jacobian.point[1];
                   sample.tangent_v = jacobian.point[2];
                   sample.mass_density = material_at(p)[0];
                   const Eigen::Vector3d f = quadrature_->weight(p) * density(sample);
                   add_transposed_jacobian_times(values, jacobian, 0, free, f, force);
                 });
}

void TriangularDNurbsSurface::fix_border() {
  for (const int i : border_control_points(surface_.basis())) {
    fix_control_point(i);
  }
}

int TriangularDNurbsSurface::freeze_outside(const SculptedRegion& region, int margin) {
  const std::vector<int> kept =
      triangular_sculpted_control_points(surface_.basis(), region, margin);
  int frozen = 0;
  for (int i = 0; i < control_point_count_; ++i) {
    if (!std::binary_search(kept.begin(), kept.end(), i)) {
      fix_control_point(i);
      ++frozen;
    }
  }
  return frozen;
}

TriangularNurbsSurface TriangularDNurbsSurface::surface(ConstVectorRef q) const {
  return {surface_.shared_basis(), control_points(q), weights(q)};
}

double TriangularDNurbsSurface::parametric_measure() const {
  return surface_.basis().triangulation().domain_area();
}

}  // namespace dnurbs
