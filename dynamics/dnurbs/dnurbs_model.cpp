#include "dnurbs/dynamics/dnurbs/dnurbs_model.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/gauss_legendre.h"

namespace dnurbs {

DNurbsModel::DNurbsModel(const KnotVector& knots_u, const KnotVector* knots_v,
                         const Eigen::MatrixX3d& control_points, const Eigen::VectorXd& weights,
                         const MaterialFunction& mass_density,
                         const MaterialFunction& damping_density,
                         const std::array<MaterialFunction, kQuantityCount>& stiffness,
                         const std::array<const char*, kQuantityCount>& stiffness_names,
                         const DNurbsSettings& settings)
    : RationalControlNetModel(settings.weight_mode, static_cast<int>(control_points.rows()),
                              settings.minimum_weight),
      surface_(knots_v != nullptr),
      count_v_(knots_v != nullptr ? knots_v->control_point_count() : 1),
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
  build_coordinates(control_points, weights, pattern_.scalar, settings.weight_inertia,
                    settings.weight_stiffness, settings.fix_weight_gauge);
  if (settings.initial_shape_at_rest) {
    set_rest_shape(initial_coordinates_);
  }
  set_plastic_flow(settings.plastic_flow);
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

void DNurbsModel::visit_rational_point(
    ConstVectorRef q, const Eigen::Vector2d& u, bool weight_columns,
    const std::function<void(const RationalPoint&)>& visit) const {
  static_assert(decltype(PointBasis::value)::RowsAtCompileTime == RationalPoint::kQuantityRows &&
                decltype(RationalJacobian::rational)::RowsAtCompileTime ==
                    RationalPoint::kQuantityRows);
  PointBasis basis;
  basis_at(u, basis);
  RationalJacobian jacobian;
  rational_jacobian(basis, 0, control_net(q), weight_columns, jacobian);
  visit({basis.active_count, basis.node.data(), basis.value.data(), jacobian.rational.data(),
         weight_columns ? jacobian.weight_column[0].data() : nullptr, jacobian.weight_sum,
         jacobian.point[0]});
}

double DNurbsModel::parametric_measure() const {
  const double length_u = knots_u_.domain_end() - knots_u_.domain_start();
  if (!surface_) {
    return length_u;
  }
  return length_u * (knots_v_.front().domain_end() - knots_v_.front().domain_start());
}

}  // namespace dnurbs
