// Tests of dynamics/swung/swung_element_assembly.h: the element-by-element assembly (stacked
// rank updates, one cross product per element, curve second derivatives grouped per Gauss point)
// equals the plain sum over Gauss points of the point Jacobians and add_swung_hessian.

#include "dnurbs/dynamics/swung/swung_element_assembly.h"

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "dnurbs/nurbs/swung_shapes.h"
#include "tests/nurbs/swung_sample_shapes.h"

namespace dnurbs {
namespace {

DNurbsSurfaceMaterial material() {
  DNurbsSurfaceMaterial m;
  m.mass_density = MaterialFunction([](const Eigen::Vector2d& u) { return 1.0 + u.x() * u.y(); });
  m.damping_density = 0.4;
  m.a10 = 1.0;
  m.a01 = 0.5;
  m.b20 = 0.02;
  m.b11 = 0.01;
  m.b02 = 0.03;
  return m;
}

// M, D, K summed point by point from the point Jacobians, as the definitions read.
void reference(const SwungSurface& surface, const SwungQuadrature& quadrature,
               const SwungLayout& layout, const std::vector<PlanarCurveSample>& profile,
               const std::vector<PlanarCurveSample>& trajectory, Eigen::MatrixXd& mass,
               Eigen::MatrixXd& damping, Eigen::MatrixXd& stiffness) {
  SwungJacobian point;
  for (int i = 0; i < quadrature.profile_point_count(); ++i) {
    for (int j = 0; j < quadrature.trajectory_point_count(); ++j) {
      const PlanarCurveSample& p = profile[static_cast<size_t>(i)];
      const PlanarCurveSample& t = trajectory[static_cast<size_t>(j)];
      swung_jacobian(p, t, surface.alpha(), layout, 2, point);
      const double w = quadrature.weight(i, j);
      const double* m = quadrature.material(i, j);
      Eigen::MatrixXd local_mass = point.columns[0].transpose() * point.columns[0];
      Eigen::MatrixXd local_stiffness =
          Eigen::MatrixXd::Zero(point.column_count, point.column_count);
      for (int q = 1; q < 6; ++q) {
        const auto& quantity_jacobian = point.columns[static_cast<size_t>(q)];
        local_stiffness += w * m[1 + q] * quantity_jacobian.transpose() * quantity_jacobian;
        add_swung_hessian(p, t, surface.alpha(), layout, static_cast<SurfaceQuantity>(q),
                          w * m[1 + q] * point.point_derivatives[static_cast<size_t>(q)],
                          local_stiffness);
      }
      for (int a = 0; a < point.column_count; ++a) {
        for (int b = 0; b < point.column_count; ++b) {
          const int r = point.coordinate[static_cast<size_t>(a)];
          const int c = point.coordinate[static_cast<size_t>(b)];
          mass(r, c) += w * m[0] * local_mass(a, b);
          damping(r, c) += w * m[1] * local_mass(a, b);
          stiffness(r, c) += local_stiffness(a, b);
        }
      }
    }
  }
}

TEST(SwungElementAssembly, EqualsThePointByPointSumOfTheDefinitions) {
  for (const WeightMode mode : {WeightMode::kFixed, WeightMode::kFree}) {
    for (const SwungSurface& surface :
         {testing::random_swung_surface(3, 2, 93, true), swung_torus(2.0, 0.5)}) {
      const SwungQuadrature quadrature(surface, surface.profile().degree() + 2,
                                       surface.trajectory().degree() + 1, material());
      const SwungLayout layout = swung_layout(surface, mode);
      Eigen::VectorXd q = swung_coordinates(surface, mode);
      q += 0.05 * Eigen::VectorXd::Random(q.size());  // a generic state
      std::vector<PlanarCurveSample> profile;
      std::vector<PlanarCurveSample> trajectory;
      quadrature.sample(layout, q.data(), surface.profile().weights().data(),
                        surface.trajectory().weights().data(), profile, trajectory);
      const int n = layout.coordinate_count();
      Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(n, n);
      Eigen::MatrixXd damping = Eigen::MatrixXd::Zero(n, n);
      Eigen::MatrixXd stiffness = Eigen::MatrixXd::Zero(n, n);
      const SwungRestPoints no_rest;
      SwungElementAssembly assembly(quadrature, no_rest, layout, surface.alpha(),
                                    surface.profile().degree(), surface.trajectory().degree(),
                                    true);
      assembly.assemble(profile, trajectory, mass, damping, stiffness);
      Eigen::MatrixXd expected_mass = Eigen::MatrixXd::Zero(n, n);
      Eigen::MatrixXd expected_damping = Eigen::MatrixXd::Zero(n, n);
      Eigen::MatrixXd expected_stiffness = Eigen::MatrixXd::Zero(n, n);
      reference(surface, quadrature, layout, profile, trajectory, expected_mass, expected_damping,
                expected_stiffness);
      // The same terms summed in another order (and scaled by square roots): round-off.
      EXPECT_LT((mass - expected_mass).norm(), 1e-13 * expected_mass.norm());
      EXPECT_LT((damping - expected_damping).norm(), 1e-13 * expected_damping.norm());
      EXPECT_LT((stiffness - expected_stiffness).norm(), 1e-13 * expected_stiffness.norm());
      // Exactly symmetric by construction.
      EXPECT_EQ(mass, mass.transpose());
      EXPECT_EQ(stiffness, stiffness.transpose());
    }
  }
}

}  // namespace
}  // namespace dnurbs
