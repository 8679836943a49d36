#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"

#include "dnurbs/dynamics/dnurbs/local_sculpting.h"
#include "dnurbs/nurbs/jacobian.h"

namespace dnurbs {

namespace {

std::array<MaterialFunction, kQuantityCount> surface_stiffness(
    const DNurbsSurfaceMaterial& material) {
  // Quantity numbering of quadrature_assembly.h: 1 x_u, 2 x_v, 3 x_uu, 4 x_uv, 5 x_vv; the
  // mixed term enters Terzopoulos 2003, eq. 1.20 with the factor 2.
  std::array<MaterialFunction, kQuantityCount> stiffness;
  stiffness[1] = material.a10;
  stiffness[2] = material.a01;
  stiffness[3] = material.b20;
  if (material.b11.is_constant()) {
    stiffness[4] = MaterialFunction(2.0 * material.b11(Eigen::Vector2d::Zero()));
  } else {
    const MaterialFunction b11 = material.b11;
    stiffness[4] = MaterialFunction(std::function<double(const Eigen::Vector2d&)>(
        [b11](const Eigen::Vector2d& u) { return 2.0 * b11(u); }));
  }
  stiffness[5] = material.b02;
  return stiffness;
}

}  // namespace

DNurbsSurface::DNurbsSurface(const NurbsSurface& surface, const DNurbsSurfaceMaterial& material,
                             const DNurbsSettings& settings)
    : DNurbsModel(surface.knots_u(), &surface.knots_v(), surface.control_points(),
                  surface.weights(), material.mass_density, material.damping_density,
                  surface_stiffness(material), {"", "a10", "a01", "b20", "2 b11", "b02"}, settings),
      surface_(surface) {}

NurbsSurface DNurbsSurface::surface(ConstVectorRef q) const {
  return NurbsSurface(surface_.knots_u(), surface_.knots_v(), control_points(q), weights(q));
}

void DNurbsSurface::fix_border() {
  const int m = surface_.control_point_count_u();
  const int n = surface_.control_point_count_v();
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < n; ++j) {
      if (i == 0 || j == 0 || i == m - 1 || j == n - 1) {
        fix_control_point(surface_.control_point_index(i, j));
      }
    }
  }
}

ParameterDomain DNurbsSurface::parameter_domain(ConstVectorRef q) const {
  return nurbs_parameter_domain(surface(q));
}

ParametricSurface DNurbsSurface::parametric_surface(ConstVectorRef q) const {
  return dnurbs::parametric_surface(surface(q));
}

std::optional<Shape> DNurbsSurface::exact_shape(ConstVectorRef q) const {
  return Shape(surface(q));
}

int DNurbsSurface::freeze_outside(const SculptedRegion& region, int margin) {
  return freeze_outside_sculpted_region(*this, region, margin);
}

void DNurbsSurface::tangent_kinematics(ConstVectorRef q, ConstVectorRef qd,
                                       const Eigen::Vector2d& u,
                                       TangentKinematics& tangents) const {
  const NurbsSurface shape = surface(q);
  const WeightMode mode = weight_mode();
  const bool free = mode == WeightMode::kFree;
  SurfaceJacobian jacobian;
  surface_jacobian(shape, u.x(), u.y(), 1, mode, jacobian);
  const auto iu = static_cast<int>(SurfaceQuantity::kU);
  const auto iv = static_cast<int>(SurfaceQuantity::kV);
  tangents.su = jacobian.point_derivatives[static_cast<size_t>(iu)];
  tangents.sv = jacobian.point_derivatives[static_cast<size_t>(iv)];

  // The columns of J_u, J_v (N_u e_r for position coordinate r of an active control point, the
  // weight column for its weight) and the rates S_u' = J_u qd, S_v' = J_v qd
  check_velocity(qd);
  start_tangent_columns(jacobian.active_count, tangents);
  const Eigen::Vector3d no_weight_column = Eigen::Vector3d::Zero();
  const auto& weight_u = jacobian.weight_column[static_cast<size_t>(iu)];
  const auto& weight_v = jacobian.weight_column[static_cast<size_t>(iv)];
  for (int a = 0; a < jacobian.active_count; ++a) {
    add_tangent_columns(a, jacobian.control_point[static_cast<size_t>(a)], jacobian.basis(iu, a),
                        jacobian.basis(iv, a),
                        free ? Eigen::Vector3d(weight_u.col(a)) : no_weight_column,
                        free ? Eigen::Vector3d(weight_v.col(a)) : no_weight_column, qd, tangents);
  }
  if (free) {
    std::array<Eigen::Vector3d, 6> rates;
    surface_jacobian_rate(shape, u.x(), u.y(), 1, control_points(qd), weights(qd), rates);
    tangents.su_bias = rates[static_cast<size_t>(iu)];
    tangents.sv_bias = rates[static_cast<size_t>(iv)];
  }
}

}  // namespace dnurbs
