// Tests of dynamics/triangular/triangular_quadrature.h: the rule on the polynomial cells is
// exact (the matrices do not change with the rule's degree), the cached B-splines are the
// basis's, and the composite rule's error against the exact matrices is measured.

#include "dnurbs/dynamics/triangular/triangular_quadrature.h"

#include <iostream>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/triangular/triangular_dnurbs_surface.h"
#include "triangular_model_helpers.h"

namespace dnurbs {
namespace {

DNurbsSurfaceMaterial plate_under_tension() {
  DNurbsSurfaceMaterial material;
  material.mass_density = 1.0;
  material.a10 = 0.3;
  material.b20 = 1.0;
  material.b11 = 1.0;
  material.b02 = 1.0;
  return material;
}

// Scalar mass and stiffness matrices of the degree-n model with the given rule.
std::pair<Eigen::MatrixXd, Eigen::MatrixXd> matrices(
    const std::shared_ptr<const TriangularBSplineBasis>& basis, int degree, int subdivisions) {
  TriangularDNurbsSettings settings;
  settings.quadrature_degree = degree;
  settings.quadrature_subdivisions = subdivisions;
  const TriangularDNurbsSurface model(test::curved_triangular_surface(basis, false),
                                      plate_under_tension(), settings);
  return {Eigen::MatrixXd(model.scalar_matrices()->mass),
          Eigen::MatrixXd(model.scalar_matrices()->stiffness)};
}

TEST(TriangularQuadrature, RuleOnThePolynomialCellsIsExact) {
  for (int n = 1; n <= 3; ++n) {
    const auto basis = test::triangular_basis(l_shape_triangulation(1), n);
    const auto [mass, stiffness] = matrices(basis, 2 * n, 0);
    const auto [mass_higher, stiffness_higher] = matrices(basis, 2 * n + 2, 0);
    // Exact integrals of polynomial pieces: a higher degree changes only round-off.
    EXPECT_LT((mass - mass_higher).norm(), 1e-14 * mass.norm()) << "degree " << n;
    EXPECT_LT((stiffness - stiffness_higher).norm(), 1e-14 * stiffness.norm()) << "degree " << n;
  }
}

TEST(TriangularQuadrature, WeightsTileEveryTriangleAndTheCacheIsTheBasis) {
  const auto basis = test::triangular_basis(square_with_hole_triangulation(1), 2);
  const TriangularQuadrature quadrature(basis, 4, 0, 2);
  TriangularBasisValues cached;
  TriangularBasisValues direct;
  std::vector<int> local;
  for (int e = 0; e < quadrature.element_count(); ++e) {
    double area = 0.0;
    for (int p = quadrature.element_begin(e); p < quadrature.element_begin(e + 1); ++p) {
      area += quadrature.weight(p);
      EXPECT_EQ(quadrature.element_of(p), e);
      if (p % 17 != 0) {
        continue;
      }
      quadrature.basis_at(p, cached, local);
      basis->evaluate_in_triangle(e, quadrature.parameter(p), 2, direct);
      // The cache is the cell's Taylor polynomial at its centroid: the same values up to the
      // round-off of a degree-2 polynomial with derivatives up to ~1 / (cloud radius)^2.
      const double scale = 1.0 + direct.value.cwiseAbs().maxCoeff();
      Eigen::Matrix<double, 6, Eigen::Dynamic> rebuilt =
          Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, direct.count);
      for (int k = 0; k < cached.count; ++k) {
        const int a = local[static_cast<size_t>(k)];
        EXPECT_EQ(cached.function[static_cast<size_t>(k)], direct.function[static_cast<size_t>(a)]);
        rebuilt.col(a) = cached.value.col(k);
      }
      // B-splines left out of the cache vanish at the point.
      EXPECT_LT((rebuilt - direct.value).cwiseAbs().maxCoeff(), 1e-13 * scale) << "point " << p;
    }
    EXPECT_NEAR(area, basis->triangulation().area(e), 1e-14);
    EXPECT_LE(static_cast<int>(quadrature.element_functions(e).size()),
              quadrature.max_local_count());
  }
  EXPECT_THROW(TriangularQuadrature(basis, 15, 0, 2), Error);
  EXPECT_THROW(TriangularQuadrature(basis, 4, 65, 2), Error);
  EXPECT_THROW(TriangularQuadrature(basis, 4, 0, 3), Error);
  EXPECT_THROW(TriangularQuadrature(nullptr, 4, 0, 2), Error);
}

TEST(TriangularQuadrature, CompositeRuleErrorAgainstTheExactCellsIsMeasured) {
  // The figures quoted in triangular_quadrature.h: degree 2, unit square of 4 x 4 cells, rule
  // of degree 4 on s^2 sub-triangles per domain triangle, relative Frobenius errors.
  const auto basis = test::triangular_basis(test::unit_square(4), 2);
  const auto [mass, stiffness] = matrices(basis, 4, 0);
  double previous_mass = 1.0;
  double previous_stiffness = 1.0;
  for (const int s : {1, 2, 4, 8}) {
    const auto [composite_mass, composite_stiffness] = matrices(basis, 4, s);
    const double mass_error = (composite_mass - mass).norm() / mass.norm();
    const double stiffness_error = (composite_stiffness - stiffness).norm() / stiffness.norm();
    std::cout << "composite rule, s = " << s << ": relative error of M " << mass_error << ", of K "
              << stiffness_error << "\n";
    EXPECT_LT(mass_error, previous_mass);
    EXPECT_LT(stiffness_error, previous_stiffness);
    previous_mass = mass_error;
    previous_stiffness = stiffness_error;
  }
  // Still far from exact at s = 8: K's integrand jumps across knot segments (first order).
  EXPECT_GT(previous_stiffness, 1e-2);
}

}  // namespace
}  // namespace dnurbs
