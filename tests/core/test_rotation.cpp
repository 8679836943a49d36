// Rotations: the cross-product matrix, the exponential map and the Cayley map against Eigen's
// angle-axis rotations and their defining identities.

#include "dnurbs/core/rotation.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

TEST(CrossMatrix, TimesAVectorIsTheCrossProduct) {
  const Eigen::Vector3d p(0.3, -1.2, 2.5);
  const Eigen::Vector3d v(-0.7, 0.4, 1.1);
  // Each entry is one product or a difference of two: rounding of one operation
  EXPECT_LT((cross_matrix(p) * v - p.cross(v)).norm(), 1e-15);
  EXPECT_EQ(cross_matrix(p) + cross_matrix(p).transpose(), Eigen::Matrix3d::Zero());
}

TEST(QuaternionExp, EqualsTheAngleAxisRotationForLargeAndTinyAngles) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, -2).normalized();
  for (const double angle : {1e-9, 1e-5, 1e-4, 0.3, 2.0, std::numbers::pi}) {
    const Eigen::Quaterniond q = quaternion_exp(angle * axis);
    const Eigen::Matrix3d expected = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    // Rounding of the half-angle sine and cosine and of both rotation matrices: a few ulps in
    // each of the 9 entries (Frobenius norm 3 times an entry's error)
    EXPECT_LT((q.toRotationMatrix() - expected).norm(), 2e-15) << angle;
    EXPECT_NEAR(q.norm(), 1.0, 2e-16) << angle;
  }
}

TEST(Cayley, IsAUnitQuaternionOfSecondOrderAccuracy) {
  const Eigen::Vector3d w(0.2, -0.5, 0.4);
  // cay(h w) and exp(h w) differ by O(h^3): the error ratio is 8 when h halves
  double previous = 0.0;
  for (const double h : {0.1, 0.05, 0.025}) {
    const double error =
        (cayley(h * w).toRotationMatrix() - quaternion_exp(h * w).toRotationMatrix()).norm();
    EXPECT_NEAR(cayley(h * w).norm(), 1.0, 2e-16);
    if (previous > 0.0) {
      EXPECT_NEAR(previous / error, 8.0, 0.1) << h;
    }
    previous = error;
  }
}

TEST(UnitQuaternion, NormalizesAndNamesABadNorm) {
  const Eigen::Quaterniond q = unit_quaternion(Eigen::Vector4d(2, 0, 0, 0));
  EXPECT_EQ(q.w(), 1.0);
  EXPECT_THROW(unit_quaternion(Eigen::Vector4d::Zero()), Error);
  try {
    unit_quaternion(Eigen::Vector4d(std::nan(""), 0, 0, 0));
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("norm nan"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace dnurbs
