// Tests of dynamics/swung/swung_separable_forms.h: the closed-form quadratic forms of a swung
// surface with fixed weights and constant material equal the general Gauss-point quadrature, for
// every matrix, the energy, the internal force and the inertial force, and the model chooses the
// fast path only where it applies.

#include "dnurbs/dynamics/swung/swung_separable_forms.h"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "dnurbs/dynamics/swung/dnurbs_swung_surface.h"
#include "dnurbs/nurbs/swung_shapes.h"
#include "tests/nurbs/swung_sample_shapes.h"

namespace dnurbs {
namespace {

DNurbsSurfaceMaterial constant_material() {
  DNurbsSurfaceMaterial material;
  material.mass_density = 1.3;
  material.damping_density = 0.4;
  material.a10 = 1.0;
  material.a01 = 0.5;
  material.b20 = 0.02;
  material.b11 = 0.01;
  material.b02 = 0.03;
  return material;
}

DNurbsSwungSettings path(bool separable, bool geometric) {
  DNurbsSwungSettings settings;
  settings.separable_assembly = separable;
  settings.geometric_stiffness = geometric;
  return settings;
}

// |a - b| relative to |b|, for dense matrices or vectors.
double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / b.norm();
}

TEST(SwungSeparableForms, EqualTheGeneralQuadratureForEveryTerm) {
  for (const SwungSurface& surface : {testing::random_swung_surface(3, 2, 94, true),
                                      testing::random_swung_surface(2, 3, 95, false),
                                      swung_torus(2.0, 0.7), swung_hat(2.0, 1.0, 1.2)}) {
    for (const bool geometric : {true, false}) {
      const DNurbsSwungSurface fast(surface, constant_material(), path(true, geometric));
      const DNurbsSwungSurface general(surface, constant_material(), path(false, geometric));
      ASSERT_TRUE(fast.uses_separable_assembly());
      ASSERT_FALSE(general.uses_separable_assembly());
      std::srand(17);
      const Eigen::VectorXd q =
          fast.initial_coordinates() + 0.1 * Eigen::VectorXd::Random(fast.coordinate_count());
      const Eigen::VectorXd qd = Eigen::VectorXd::Random(fast.coordinate_count());
      ModelMatrices a;
      ModelMatrices b;
      fast.assemble_matrices(q, a);
      general.assemble_matrices(q, b);
      // The same Gauss points regrouped into products of 1-D sums: round-off only.
      EXPECT_LT(relative(Eigen::MatrixXd(a.mass), Eigen::MatrixXd(b.mass)), 1e-13);
      EXPECT_LT(relative(Eigen::MatrixXd(a.damping), Eigen::MatrixXd(b.damping)), 1e-13);
      EXPECT_LT(relative(Eigen::MatrixXd(a.stiffness), Eigen::MatrixXd(b.stiffness)), 1e-13);
      EXPECT_EQ(Eigen::MatrixXd(a.mass), Eigen::MatrixXd(a.mass).transpose());  // exactly
      EXPECT_EQ(Eigen::MatrixXd(a.stiffness), Eigen::MatrixXd(a.stiffness).transpose());
      EXPECT_NEAR(fast.potential_energy(q), general.potential_energy(q),
                  1e-13 * general.potential_energy(q));
      Eigen::VectorXd f = Eigen::VectorXd::Zero(q.size());
      Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
      fast.add_internal_force(q, f);
      general.add_internal_force(q, g);
      EXPECT_LT(relative(f, g), 1e-13);
      f.setZero();
      g.setZero();
      fast.add_inertial_force(q, qd, f);
      general.add_inertial_force(q, qd, g);
      EXPECT_LT(relative(f, g), 1e-13);
    }
  }
}

TEST(SwungSeparableForms, ModelUsesThemOnlyForFixedWeightsAndConstantMaterial) {
  const SwungSurface sphere = swung_sphere(1.0);
  EXPECT_TRUE(DNurbsSwungSurface(sphere, constant_material()).uses_separable_assembly());
  DNurbsSwungSettings free;
  free.weight_mode = WeightMode::kFree;
  EXPECT_FALSE(DNurbsSwungSurface(sphere, constant_material(), free).uses_separable_assembly());
  DNurbsSurfaceMaterial varying = constant_material();
  varying.b02 = MaterialFunction([](const Eigen::Vector2d& u) { return 0.1 + u.y(); });
  EXPECT_FALSE(DNurbsSwungSurface(sphere, varying).uses_separable_assembly());
}

}  // namespace
}  // namespace dnurbs
