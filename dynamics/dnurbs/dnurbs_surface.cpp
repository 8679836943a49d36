#include "dynamics/dnurbs/dnurbs_surface.h"

namespace dnurbs {

namespace {

std::array<MaterialFunction, kQuantityCount> surface_stiffness(
    const DNurbsSurfaceMaterial& material) {
  // Quantity numbering of quadrature_assembly.h: 1 x_u, 2 x_v, 3 x_uu, 4 x_uv, 5 x_vv; the
  // mixed term enters seed 001 eq 1.20 with the factor 2.
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

}  // namespace dnurbs
