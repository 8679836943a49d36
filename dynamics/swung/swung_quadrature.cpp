#include "dnurbs/dynamics/swung/swung_quadrature.h"

#include <algorithm>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// The table's cached basis of every Gauss point as a curve sample (rational parts unset).
std::vector<PlanarCurveSample> cached_bases(const DirectionQuadrature& table) {
  const int p = table.degree;
  std::vector<PlanarCurveSample> samples(table.parameter.size());
  for (int s = 0; s < table.span_count; ++s) {
    for (int g = 0; g < table.points_per_span; ++g) {
      const int i = s * table.points_per_span + g;
      PlanarCurveSample& sample = samples[static_cast<size_t>(i)];
      sample.degree = p;
      sample.basis.setZero();
      for (int a = 0; a <= p; ++a) {
        const int window = s * (p + 1) + a;
        sample.control_point[static_cast<size_t>(a)] =
            table.control_point[static_cast<size_t>(window)];
        for (int d = 0; d < 3; ++d) {
          const int entry = (i * 3 + d) * (p + 1) + a;
          sample.basis(d, a) = table.basis[static_cast<size_t>(entry)];
        }
      }
    }
  }
  return samples;
}

}  // namespace

SwungQuadrature::SwungQuadrature(const SwungSurface& surface, int points_per_span_u,
                                 int points_per_span_v, const DNurbsSurfaceMaterial& material)
    : table_u_(direction_quadrature(surface.profile().knots(), points_per_span_u)),
      table_v_(direction_quadrature(surface.trajectory().knots(), points_per_span_v)),
      profile_basis_(cached_bases(table_u_)),
      trajectory_basis_(cached_bases(table_v_)) {
  // Terzopoulos, eq. 1.20: the thin plate under tension weighs |S_uv|^2 with 2 b11.
  const std::array<const MaterialFunction*, kQuantityCount> stiffness = {
      nullptr, &material.a10, &material.a01, &material.b20, &material.b11, &material.b02};
  const std::array<const char*, kQuantityCount> names = {"", "a10", "a01", "b20", "b11", "b02"};
  has_damping_ = !material.damping_density.is_zero();
  for (int q = 1; q < kQuantityCount; ++q) {
    has_stiffness_[static_cast<size_t>(q)] = !stiffness[static_cast<size_t>(q)]->is_zero();
  }
  const int nu = profile_point_count();
  const int nv = trajectory_point_count();
  material_.assign(static_cast<size_t>(nu) * static_cast<size_t>(nv) * kSwungMaterialStride, 0.0);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Eigen::Vector2d u = parameter(i, j);
      const int point = i * nv + j;
      double* m = &material_[static_cast<size_t>(point) * kSwungMaterialStride];
      m[0] = material.mass_density.checked(u, "mass density", true);
      m[1] = material.damping_density.checked(u, "damping density", true);
      for (int q = 1; q < kQuantityCount; ++q) {
        if (has_stiffness_[static_cast<size_t>(q)]) {
          m[1 + q] = (q == 4 ? 2.0 : 1.0) * stiffness[static_cast<size_t>(q)]->checked(
                                                u, names[static_cast<size_t>(q)], true);
        }
      }
    }
  }
}

int SwungQuadrature::stiffness_order() const {
  int order = 0;
  for (int q = 1; q < kQuantityCount; ++q) {
    if (has_stiffness_[static_cast<size_t>(q)]) {
      order = std::max(order, q >= 3 ? 2 : 1);
    }
  }
  return order;
}

void SwungQuadrature::sample(const SwungLayout& layout, const double* q,
                             const double* profile_weights, const double* trajectory_weights,
                             std::vector<PlanarCurveSample>& profile,
                             std::vector<PlanarCurveSample>& trajectory) const {
  profile = profile_basis_;
  trajectory = trajectory_basis_;
  const PlanarControlNet profile_net = swung_profile_net(layout, q, profile_weights);
  const PlanarControlNet trajectory_net = swung_trajectory_net(layout, q, trajectory_weights);
  for (PlanarCurveSample& s : profile) {
    planar_curve_rational(profile_net, s);
  }
  for (PlanarCurveSample& s : trajectory) {
    planar_curve_rational(trajectory_net, s);
  }
}

}  // namespace dnurbs
