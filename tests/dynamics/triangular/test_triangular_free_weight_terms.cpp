// Tests of dynamics/triangular/triangular_free_weight_terms.h against the dense Jacobian of one
// point: the 4 x 4 blocks of sum_alpha c_alpha J_alpha^T J_alpha and J_alpha^T f.

#include "dnurbs/dynamics/triangular/triangular_free_weight_terms.h"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "triangular_model_helpers.h"

namespace dnurbs {
namespace {

TEST(TriangularFreeWeightTerms, BlocksAndTransposedProductsMatchTheDenseJacobian) {
  const auto basis = test::triangular_basis(test::unit_square(1), 2);
  const TriangularNurbsSurface surface = test::curved_triangular_surface(basis, true);
  TriangularBasisValues values;
  basis->evaluate(Eigen::Vector2d(0.35, 0.6), 2, values);
  TriangularRationalJacobian jacobian;
  triangular_rational_jacobian(values, 2, surface.control_net(), true, jacobian);
  const Eigen::Index count = values.count;
  // Dense J_alpha (3 by 4 count): [R_a I_3, E_a] per listed B-spline, in list order.
  std::array<Eigen::MatrixXd, 6> dense;
  for (int alpha = 0; alpha < 6; ++alpha) {
    dense[static_cast<size_t>(alpha)] = Eigen::MatrixXd::Zero(3, 4 * count);
    for (Eigen::Index a = 0; a < count; ++a) {
      dense[static_cast<size_t>(alpha)].block(0, 4 * a, 3, 3) =
          jacobian.rational(alpha, a) * Eigen::Matrix3d::Identity();
      dense[static_cast<size_t>(alpha)].col(4 * a + 3) =
          jacobian.weight_column[static_cast<size_t>(alpha)].col(a);
    }
  }
  const std::array<double, 6> c = {1.3, 0.2, 0.7, 0.05, 0.11, 0.3};
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(4 * count, 4 * count);
  for (int alpha = 0; alpha < 6; ++alpha) {
    expected += c[static_cast<size_t>(alpha)] * dense[static_cast<size_t>(alpha)].transpose() *
                dense[static_cast<size_t>(alpha)];
  }
  // Local indices reversed, into a block of local count + 2 (padding untouched).
  const Eigen::Index local_count = count + 2;
  std::vector<int> local(static_cast<size_t>(count));
  for (Eigen::Index a = 0; a < count; ++a) {
    local[static_cast<size_t>(a)] = static_cast<int>(count - 1 - a);
  }
  std::vector<double> block(static_cast<size_t>(16 * local_count * local_count), 0.0);
  add_free_weight_terms(jacobian, c, values.count, local, static_cast<int>(local_count), block);
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
      assembled(block.data(), 4 * local_count, 4 * local_count);
  double worst = 0.0;
  for (Eigen::Index a = 0; a < count; ++a) {
    for (Eigen::Index b = 0; b < count; ++b) {
      const Eigen::Index la = local[static_cast<size_t>(a)];
      const Eigen::Index lb = local[static_cast<size_t>(b)];
      worst = std::max(worst,
                       (assembled.block(4 * la, 4 * lb, 4, 4) - expected.block(4 * a, 4 * b, 4, 4))
                           .cwiseAbs()
                           .maxCoeff());
    }
  }
  EXPECT_LT(worst, 1e-12 * expected.cwiseAbs().maxCoeff());  // same products, round-off
  EXPECT_EQ(assembled.bottomRows(8).cwiseAbs().maxCoeff(), 0.0);
  // J_alpha^T f into a free-weight force vector (4 coordinates per control point).
  const Eigen::Vector3d f(0.3, -1.2, 0.8);
  Eigen::VectorXd force =
      Eigen::VectorXd::Zero(4 * static_cast<Eigen::Index>(basis->function_count()));
  add_transposed_jacobian_times(values, jacobian, 4, true, f, force);
  const Eigen::VectorXd product = dense[4].transpose() * f;
  for (Eigen::Index a = 0; a < count; ++a) {
    const Eigen::Index offset =
        4 * static_cast<Eigen::Index>(values.function[static_cast<size_t>(a)]);
    EXPECT_LT((force.segment<4>(offset) - product.segment<4>(4 * a)).norm(),
              1e-14 * (1.0 + product.norm()));
  }
}

}  // namespace
}  // namespace dnurbs
