#include "dnurbs/surface/parametric_fe_mesh.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/SparseCholesky>

#include "dnurbs/core/error.h"
#include "dnurbs/surface/deformable_superquadric_shape.h"
#include "tests/common/superquadric_test_support.h"

namespace dnurbs {
namespace {

using testing::central_difference;

constexpr double kPi = std::numbers::pi;

/// Random (u, v) over the whole domain, plus the seams and the poles.
std::vector<Eigen::Vector2d> sample_parameters() {
  std::mt19937 generator(7);
  std::uniform_real_distribution<double> u(-kPi / 2, kPi / 2);
  std::uniform_real_distribution<double> v(-kPi, kPi);
  std::vector<Eigen::Vector2d> samples;
  samples.reserve(216);
  for (int k = 0; k < 200; ++k) {
    samples.emplace_back(u(generator), v(generator));
  }
  for (const double seam_v : {-kPi, 0.0, kPi, 3.0 * kPi}) {
    for (const double seam_u : {-kPi / 2, -0.3, 0.0, kPi / 2}) {
      samples.emplace_back(seam_u, seam_v);
    }
  }
  return samples;
}

Eigen::VectorXd random_displacements(const ParametricFeMesh& mesh, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::VectorXd q_d(mesh.coordinate_count());
  for (int k = 0; k < q_d.size(); ++k) {
    q_d[k] = value(generator);
  }
  return q_d;
}

TEST(ParametricFeMesh, CountsNodesWithCollapsedPoles) {
  const ParametricFeMesh mesh(6, 8);
  EXPECT_EQ(mesh.node_count(), 2 + 5 * 8);
  EXPECT_EQ(mesh.coordinate_count(), 3 * 42);
  EXPECT_EQ(mesh.node_index(0, 5), mesh.south_pole_node());
  EXPECT_EQ(mesh.node_index(6, 3), mesh.north_pole_node());
  EXPECT_EQ(mesh.node_index(2, 8), mesh.node_index(2, 0));   // v = pi is v = -pi
  EXPECT_EQ(mesh.node_index(2, -1), mesh.node_index(2, 7));  // and wraps backwards
}

TEST(ParametricFeMesh, ShapeFunctionsArePartitionOfUnity) {
  const ParametricFeMesh mesh(5, 7);
  for (const Eigen::Vector2d& uv : sample_parameters()) {
    const FeShapeValues shape = mesh.shape_values(uv[0], uv[1]);
    ASSERT_GE(shape.active_count, 1);
    ASSERT_LE(shape.active_count, FeShapeValues::kMaxActive);
    const auto active = Eigen::seqN(0, shape.active_count);
    // Sums of four products of numbers in [0, 1]: rounding.
    EXPECT_NEAR(shape.value(active).sum(), 1.0, 1e-15) << uv.transpose();
    EXPECT_NEAR(shape.d_u(active).sum(), 0.0, 1e-14) << uv.transpose();
    EXPECT_NEAR(shape.d_v(active).sum(), 0.0, 1e-14) << uv.transpose();
    EXPECT_GE(shape.value(active).minCoeff(), 0.0);
  }
}

TEST(ParametricFeMesh, ShapeFunctionsInterpolateNodalValues) {
  const ParametricFeMesh mesh(5, 7);
  for (int node = 0; node < mesh.node_count(); ++node) {
    const Eigen::Vector2d uv = mesh.node_parameter(node);
    const FeShapeValues shape = mesh.shape_values(uv[0], uv[1]);
    for (int a = 0; a < shape.active_count; ++a) {
      // The node's local coordinate is 0 or 1 up to the rounding of (u + pi/2)/step.
      EXPECT_NEAR(shape.value[a], shape.node[a] == node ? 1.0 : 0.0, 1e-14) << node;
    }
  }
  // So a displacement field takes its nodal values at the nodes.
  const Eigen::VectorXd q_d = random_displacements(mesh, 3);
  for (int node = 0; node < mesh.node_count(); ++node) {
    const Eigen::Vector2d uv = mesh.node_parameter(node);
    const FeDisplacement d = mesh.displacement(q_d, mesh.shape_values(uv[0], uv[1]));
    EXPECT_LT((d.value - q_d.segment<3>(3 * static_cast<Eigen::Index>(node))).norm(), 1e-14)
        << node;
  }
}

TEST(ParametricFeMesh, WrapsInV) {
  const ParametricFeMesh mesh(4, 6);
  const Eigen::VectorXd q_d = random_displacements(mesh, 5);
  for (const double u : {-1.2, -0.2, 0.0, 0.9, 1.5}) {
    for (const double v : {-kPi, -2.0, 0.3, 2.9}) {
      const FeDisplacement d = mesh.displacement(q_d, mesh.shape_values(u, v));
      for (const double shifted : {v + 2.0 * kPi, v - 2.0 * kPi, v + 6.0 * kPi}) {
        const FeDisplacement e = mesh.displacement(q_d, mesh.shape_values(u, shifted));
        // v + 2 pi k loses the low bits of v: 1e-15 relative in v times |dN/dv| (1/step).
        EXPECT_LT((d.value - e.value).norm(), 1e-13) << u << " " << v << " " << shifted;
        EXPECT_LT((d.d_v - e.d_v).norm(), 1e-12) << u << " " << v << " " << shifted;
      }
    }
    // Continuity across the seam: v = pi (reached from below) equals v = -pi.
    const FeDisplacement below = mesh.displacement(q_d, mesh.shape_values(u, kPi - 1e-13));
    const FeDisplacement seam = mesh.displacement(q_d, mesh.shape_values(u, -kPi));
    // The field moves by |dN/dv| 1e-13 over the gap.
    EXPECT_LT((below.value - seam.value).norm(), 1e-11) << u;
  }
}

TEST(ParametricFeMesh, DisplacementIsSingleValuedAtThePoles) {
  const ParametricFeMesh mesh(4, 6);
  const Eigen::VectorXd q_d = random_displacements(mesh, 9);
  for (const double v : {-kPi, -1.0, 0.5, 3.0}) {
    EXPECT_EQ(mesh.displacement(q_d, mesh.shape_values(-kPi / 2, v)).value,
              q_d.segment<3>(3 * static_cast<Eigen::Index>(mesh.south_pole_node())).eval());
    EXPECT_EQ(mesh.displacement(q_d, mesh.shape_values(kPi / 2, v)).value,
              q_d.segment<3>(3 * static_cast<Eigen::Index>(mesh.north_pole_node())).eval());
    // Near the pole the field tends to the pole value (C0): within |dN/du| 1e-9.
    const FeDisplacement near = mesh.displacement(q_d, mesh.shape_values(kPi / 2 - 1e-9, v));
    EXPECT_LT(
        (near.value - q_d.segment<3>(3 * static_cast<Eigen::Index>(mesh.north_pole_node()))).norm(),
        1e-8);
  }
}

TEST(ParametricFeMesh, ShapeFunctionDerivativesMatchCentralDifferences) {
  const ParametricFeMesh mesh(5, 7);
  const Eigen::VectorXd q_d = random_displacements(mesh, 11);
  std::mt19937 generator(13);
  std::uniform_real_distribution<double> local(0.1, 0.9);  // stay inside a cell: C0 across edges
  const double step = 1e-6;
  for (int i = 0; i < mesh.cells_u(); ++i) {
    for (int j = 0; j < mesh.cells_v(); ++j) {
      const Eigen::Vector4d box = mesh.cell_bounds(i, j);
      const double u = box[0] + local(generator) * (box[1] - box[0]);
      const double v = box[2] + local(generator) * (box[3] - box[2]);
      const FeDisplacement d = mesh.displacement(q_d, mesh.shape_values(u, v));
      const auto at = [&](double x, double y) {
        return mesh.displacement(q_d, mesh.shape_values(x, y)).value;
      };
      const Eigen::Vector3d fd_u = central_difference([&](double x) { return at(x, v); }, u, step);
      const Eigen::Vector3d fd_v = central_difference([&](double y) { return at(u, y); }, v, step);
      // Bilinear: central differences are exact up to rounding 1e-16 / h = 1e-10.
      EXPECT_LT((d.d_u - fd_u).norm(), 1e-9) << i << " " << j;
      EXPECT_LT((d.d_v - fd_v).norm(), 1e-9) << i << " " << j;
    }
  }
}

TEST(ParametricFeMesh, ShapeMatrixTimesCoordinatesIsTheDisplacement) {
  const ParametricFeMesh mesh(3, 5);
  const Eigen::VectorXd q_d = random_displacements(mesh, 17);
  for (const Eigen::Vector2d& uv : sample_parameters()) {
    const Eigen::Vector3d via_matrix = mesh.shape_matrix(uv[0], uv[1]) * q_d;
    const Eigen::Vector3d direct = mesh.displacement(q_d, mesh.shape_values(uv[0], uv[1])).value;
    // Same sums in another order.
    EXPECT_LT((via_matrix - direct).norm(), 1e-15);
  }
}

TEST(ParametricFeMesh, MembraneStiffnessAnnihilatesConstantDisplacements) {
  const ParametricFeMesh mesh(6, 9);
  const Eigen::SparseMatrix<double> k =
      mesh.stiffness_matrix({.membrane_u = 2.0, .membrane_v = 0.5, .spring = 0.0});
  Eigen::VectorXd constant(mesh.coordinate_count());
  for (int node = 0; node < mesh.node_count(); ++node) {
    constant.segment<3>(3 * static_cast<Eigen::Index>(node)) << 0.3, -1.2, 2.0;
  }
  // Row sums of terms of size |K| cancel: rounding of a few ulps of the largest entry.
  const double scale = Eigen::MatrixXd(k).cwiseAbs().maxCoeff();
  EXPECT_LT((k * constant).lpNorm<Eigen::Infinity>(), 1e-13 * scale);
}

TEST(ParametricFeMesh, StiffnessIsSymmetricAndPositiveDefiniteWithASpring) {
  const ParametricFeMesh mesh(5, 6);
  const Eigen::SparseMatrix<double> k =
      mesh.stiffness_matrix({.membrane_u = 1.0, .membrane_v = 1.0, .spring = 0.1});
  ASSERT_EQ(k.rows(), mesh.coordinate_count());
  // Entries are assembled symmetrically from symmetric element matrices: exactly.
  EXPECT_EQ((Eigen::SparseMatrix<double>(k.transpose()) - k).norm(), 0.0);
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> cholesky(k);
  EXPECT_EQ(cholesky.info(), Eigen::Success);
}

TEST(ParametricFeMesh, StiffnessIntegratesExactlyRepresentedFields) {
  const ParametricFeMesh mesh(6, 8);
  // The scalar field f(u, v) = u is bilinear, so the mesh represents it exactly (the poles
  // take -pi/2 and pi/2 for every v); integral |f_u|^2 du dv = area = 2 pi^2, |f_v|^2 = 0,
  // integral f^2 = 2 pi * (pi^3 / 12).
  Eigen::VectorXd f(mesh.node_count());
  for (int node = 0; node < mesh.node_count(); ++node) {
    f[node] = mesh.node_parameter(node)[0];
  }
  const double area = 2.0 * kPi * kPi;
  const Eigen::SparseMatrix<double> k_u = mesh.scalar_stiffness_matrix({1.0, 0.0, 0.0});
  const Eigen::SparseMatrix<double> k_v = mesh.scalar_stiffness_matrix({0.0, 1.0, 0.0});
  const Eigen::SparseMatrix<double> m = mesh.scalar_mass_matrix();
  // 2 x 2 Gauss points integrate bilinear products exactly: rounding only.
  EXPECT_NEAR(f.dot(k_u * f), area, 1e-12);
  EXPECT_NEAR(f.dot(k_v * f), 0.0, 1e-12);
  // f^2 is quadratic in u within a cell but the bilinear interpolant of u is u itself: exact.
  EXPECT_NEAR(f.dot(m * f), 2.0 * kPi * std::pow(kPi, 3) / 12.0, 1e-12);
  // The spring term of the whole: 1^T M 1 = area.
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(mesh.node_count());
  EXPECT_NEAR(ones.dot(m * ones), area, 1e-12);
  // A longitude field f = cos v (through the nodes) has membrane_v energy near
  // integral sin^2 v du dv = pi * pi, with O(h^2) interpolation error on 8 cells.
  Eigen::VectorXd g(mesh.node_count());
  for (int node = 0; node < mesh.node_count(); ++node) {
    const Eigen::Vector2d uv = mesh.node_parameter(node);
    g[node] = std::cos(uv[1]) * std::cos(uv[0]);  // vanishes at the poles: single-valued
  }
  // integral (cos u sin v)^2 = (pi/2)(pi) = pi^2 / 2; the piecewise-linear interpolant on
  // cells of 45 degrees underestimates it by a few per cent.
  EXPECT_NEAR(g.dot(k_v * g) / (kPi * kPi / 2.0), 1.0, 0.1);
}

TEST(ParametricFeMesh, QuadraturePointsCoverTheDomainInsideTheirCells) {
  const ParametricFeMesh mesh(5, 7);
  const std::vector<ParameterQuadraturePoint> points = mesh.quadrature_points(3);
  ASSERT_EQ(points.size(), 5u * 7u * 9u);
  double total = 0.0;
  for (const ParameterQuadraturePoint& point : points) {
    total += point.weight;
    const Eigen::Vector4d box = mesh.cell_bounds(point.cell_u, point.cell_v);
    EXPECT_GT(point.u, box[0]);
    EXPECT_LT(point.u, box[1]);
    EXPECT_GT(point.v, box[2]);
    EXPECT_LT(point.v, box[3]);
  }
  // Positive weights summing to the area 2 pi^2: rounding over 315 terms.
  EXPECT_NEAR(total, 2.0 * kPi * kPi, 1e-12);
}

TEST(ParametricFeMesh, SphereAreaFromShapeTangentsIsFourPiRSquared) {
  // What the dynamic model does for M: integrate with the area element |s_u x s_v| at the
  // mesh's quadrature points. The integrand r^2 cos u is smooth on each cell.
  const double radius = 1.7;
  const DeformableSuperquadricShape sphere = DeformableSuperquadricShape::sphere(radius);
  const ParametricFeMesh mesh(8, 12);
  double area = 0.0;
  for (const ParameterQuadraturePoint& point : mesh.quadrature_points(4)) {
    const SuperquadricShapeEvaluation s = sphere.evaluate(point.u, point.v);
    area += point.weight * s.d_u.cross(s.d_v).norm();
  }
  // 4-point Gauss on cells of pi/8 integrates cos u to (pi/8)^8 / 8! relative: below 1e-11.
  EXPECT_NEAR(area / (4.0 * kPi * radius * radius), 1.0, 1e-11);
}

TEST(ParametricFeMesh, RejectsBadResolutionsAndParameters) {
  EXPECT_THROW(ParametricFeMesh(1, 8), Error);
  EXPECT_THROW(ParametricFeMesh(4, 2), Error);
  const ParametricFeMesh mesh(4, 6);
  EXPECT_THROW(mesh.shape_values(2.0, 0.0), Error);
  EXPECT_THROW(mesh.shape_values(std::nan(""), 0.0), Error);
  EXPECT_THROW(mesh.shape_values(0.0, std::numeric_limits<double>::infinity()), Error);
  EXPECT_THROW(mesh.scalar_stiffness_matrix({-1.0, 1.0, 0.0}), Error);
  EXPECT_THROW(mesh.node_parameter(mesh.node_count()), Error);
}

}  // namespace
}  // namespace dnurbs
