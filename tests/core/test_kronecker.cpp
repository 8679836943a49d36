// The Kronecker layout: S (x) I_b entry by entry against the dense product, and the fixed nodes
// of a list of fixed coordinates, and the quadratic form x^T (S (x) I_b) x against the expanded
// matrix's.

#include "dnurbs/core/kronecker.h"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

TEST(KroneckerIdentity, EqualsTheDenseKroneckerProduct) {
  SparseMatrix scalar(4, 4);
  scalar.insert(0, 0) = 2.0;
  scalar.insert(1, 0) = -1.5;
  scalar.insert(0, 1) = -1.5;
  scalar.insert(3, 2) = 0.25;
  scalar.insert(2, 3) = 0.25;
  scalar.makeCompressed();
  for (const int b : {1, 3, 4}) {
    const SparseMatrix expanded = kronecker_identity(scalar, b);
    const Eigen::MatrixXd dense = Eigen::MatrixXd(scalar);
    Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(4 * b, 4 * b);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        expected.block(i * b, j * b, b, b) = dense(i, j) * Eigen::MatrixXd::Identity(b, b);
      }
    }
    // Entries are copied, so the product is exact
    EXPECT_EQ((Eigen::MatrixXd(expanded) - expected).cwiseAbs().maxCoeff(), 0.0) << b;
    EXPECT_EQ(expanded.nonZeros(), b * scalar.nonZeros()) << b;
    EXPECT_TRUE(expanded.isCompressed());
  }
  EXPECT_THROW(kronecker_identity(scalar, 0), Error);
}

TEST(KroneckerQuadraticForm, EqualsTheExpandedQuadraticForm) {
  SparseMatrix scalar(4, 4);
  scalar.insert(0, 0) = 2.0;
  scalar.insert(1, 0) = -1.5;
  scalar.insert(0, 1) = -1.5;
  scalar.insert(1, 1) = 3.0;
  scalar.insert(3, 2) = 0.25;
  scalar.insert(2, 3) = 0.25;
  scalar.insert(2, 2) = 1.0;
  scalar.insert(3, 3) = 0.5;
  scalar.makeCompressed();
  for (const int b : {1, 3}) {
    const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(4 * b, -1.0, 2.0);
    const double expected = x.dot(kronecker_identity(scalar, b) * x);
    // The same products summed in another order: rounding only, |terms| <= 12
    EXPECT_NEAR(kronecker_quadratic_form(scalar, x, b), expected, 1e-14) << "b = " << b;
  }
  // By hand for b = 1 and x = (1, 1, 0, 0): 2 - 1.5 - 1.5 + 3 = 2
  EXPECT_DOUBLE_EQ(kronecker_quadratic_form(scalar, Eigen::Vector4d(1, 1, 0, 0), 1), 2.0);
  EXPECT_THROW(kronecker_quadratic_form(scalar, Eigen::VectorXd::Zero(11), 3), Error);
  EXPECT_THROW(kronecker_quadratic_form(scalar, Eigen::VectorXd::Zero(4), 0), Error);
}

TEST(KroneckerQuadraticForm, OfADifferenceEqualsTheFormOfTheSubtractedVector) {
  SparseMatrix scalar(3, 3);
  scalar.insert(0, 0) = 4.0;
  scalar.insert(1, 0) = -2.0;
  scalar.insert(0, 1) = -2.0;
  scalar.insert(1, 1) = 5.0;
  scalar.insert(2, 2) = 0.5;
  scalar.makeCompressed();
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(6, -1.0, 1.5);
  const Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(6, 0.25, -0.5);
  // The same products of the same differences, summed in the same order: equal to the last bit
  EXPECT_EQ(kronecker_quadratic_form_of_difference(scalar, x, y, 2),
            kronecker_quadratic_form(scalar, x - y, 2));
  // By hand for b = 1, x - y = (1, 1, 2): 4 - 2 - 2 + 5 + 0.5 * 4 = 7
  EXPECT_DOUBLE_EQ(kronecker_quadratic_form_of_difference(scalar, Eigen::Vector3d(3, 2, 2),
                                                          Eigen::Vector3d(2, 1, 0), 1),
                   7.0);
  EXPECT_THROW(kronecker_quadratic_form_of_difference(scalar, x, Eigen::VectorXd::Zero(5), 2),
               Error);
  EXPECT_THROW(kronecker_quadratic_form_of_difference(scalar, x, y, 3), Error);
}

TEST(FixedNodes, WholeNodesAreFoundAndPartialOnesRefused) {
  EXPECT_EQ(fixed_nodes({}, 3), std::vector<int>());
  EXPECT_EQ(fixed_nodes({3, 4, 5, 9, 10, 11}, 3), (std::vector<int>{1, 3}));
  EXPECT_FALSE(fixed_nodes({3, 4}, 3).has_value());        // node 1 partly fixed
  EXPECT_FALSE(fixed_nodes({4, 5, 6}, 3).has_value());     // straddles nodes 1 and 2
  EXPECT_FALSE(fixed_nodes({0, 1, 2, 4}, 3).has_value());  // a stray coordinate
  EXPECT_EQ(fixed_nodes({0, 1, 2, 3}, 4), std::vector<int>{0});
  EXPECT_THROW(fixed_nodes({0}, 0), Error);
}

}  // namespace
}  // namespace dnurbs
