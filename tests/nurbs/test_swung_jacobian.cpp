// Tests of nurbs/swung_jacobian.h: the Jacobians dense_jacobian, J_u, J_v, J_uu, J_uv, J_vv, Jdot
// qd and the second derivatives of the swung surface with respect to its coordinates, all against
// finite differences of the surface, for fixed and free weights; the scaling gauge; the layout.

#include "dnurbs/nurbs/swung_jacobian.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/swung_shapes.h"
#include "swung_sample_shapes.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

struct JacobianCase {
  const char* name;
  SwungSurface surface;
  WeightMode mode;
};

std::vector<JacobianCase> jacobian_cases() {
  return {{"fixed weights, open trajectory", testing::random_swung_surface(3, 2, 61, false),
           WeightMode::kFixed},
          {"free weights, open trajectory", testing::random_swung_surface(3, 2, 61, false),
           WeightMode::kFree},
          {"fixed weights, periodic trajectory", testing::random_swung_surface(2, 3, 71, true),
           WeightMode::kFixed},
          {"free weights, periodic trajectory", testing::random_swung_surface(2, 3, 71, true),
           WeightMode::kFree},
          {"free weights, torus", swung_torus(2.0, 0.7), WeightMode::kFree}};
}

const std::array<Eigen::Vector2d, 3> sample_parameters = {
    Eigen::Vector2d(0.12, 0.67), Eigen::Vector2d(0.5, 0.05), Eigen::Vector2d(0.91, 0.38)};

// S^Q, Q = S, S_u, S_v, S_uu, S_uv, S_vv, of the surface at coordinates q.
std::array<Eigen::Vector3d, 6> quantities_at(const JacobianCase& c, const Eigen::VectorXd& q,
                                             const Eigen::Vector2d& uv) {
  const SurfaceDerivatives d =
      swung_surface_at(c.surface, c.mode, q).derivatives(uv.x(), uv.y(), 2);
  return {d(0, 0), d(1, 0), d(0, 1), d(2, 0), d(1, 1), d(0, 2)};
}

SwungJacobian jacobian_at(const JacobianCase& c, const Eigen::VectorXd& q,
                          const Eigen::Vector2d& uv) {
  SwungJacobian jacobian;
  swung_jacobian(swung_surface_at(c.surface, c.mode, q), uv.x(), uv.y(), 2, c.mode, jacobian);
  return jacobian;
}

Eigen::MatrixXd dense(const SwungJacobian& jacobian, int quantity, int count) {
  return Eigen::MatrixXd(to_sparse_matrix(jacobian, static_cast<SurfaceQuantity>(quantity), count));
}

TEST(SwungJacobian, EveryQuantityMatchesFiniteDifferencesOfTheSurface) {
  for (const JacobianCase& c : jacobian_cases()) {
    const Eigen::VectorXd q = swung_coordinates(c.surface, c.mode);
    const int n = static_cast<int>(q.size());
    EXPECT_EQ(
        n, (c.mode == WeightMode::kFree ? 3 : 2) * (c.surface.profile().control_point_count() +
                                                    c.surface.trajectory().control_point_count()));
    const double h = 1e-6;
    for (const Eigen::Vector2d& uv : sample_parameters) {
      const SwungJacobian jacobian = jacobian_at(c, q, uv);
      const std::array<Eigen::Vector3d, 6> values = quantities_at(c, q, uv);
      for (int quantity = 0; quantity < 6; ++quantity) {
        EXPECT_LT((jacobian.point_derivatives[static_cast<size_t>(quantity)] -
                   values[static_cast<size_t>(quantity)])
                      .norm(),
                  1e-13 * (1.0 + values[static_cast<size_t>(quantity)].norm()));
        const Eigen::MatrixXd dense_jacobian = dense(jacobian, quantity, n);
        double scale = 1.0;
        for (int k = 0; k < n; ++k) {
          scale = std::max(scale, dense_jacobian.col(k).norm());
        }
        for (int k = 0; k < n; ++k) {
          Eigen::VectorXd plus = q;
          Eigen::VectorXd minus = q;
          plus[k] += h;
          minus[k] -= h;
          const Eigen::Vector3d fd = (quantities_at(c, plus, uv)[static_cast<size_t>(quantity)] -
                                      quantities_at(c, minus, uv)[static_cast<size_t>(quantity)]) /
                                     (2 * h);
          // Central difference: O(h^2) truncation (~1e-12 |d^3 S|) + O(1e-16 |S^Q| / h)
          // round-off (~1e-10 |S^Q|), relative to the largest column.
          EXPECT_LT((dense_jacobian.col(k) - fd).norm(), 1e-8 * scale)
              << c.name << ", quantity " << quantity << ", coordinate " << k << " at "
              << uv.transpose();
        }
      }
    }
  }
}

TEST(SwungJacobian, JdotTimesVelocityMatchesFiniteDifferencesOfTheJacobian) {
  for (const JacobianCase& c : jacobian_cases()) {
    const Eigen::VectorXd q = swung_coordinates(c.surface, c.mode);
    const int n = static_cast<int>(q.size());
    std::srand(5);
    Eigen::VectorXd qd = Eigen::VectorXd::Random(n);
    const double h = 1e-5;
    for (const Eigen::Vector2d& uv : sample_parameters) {
      std::array<Eigen::Vector3d, 6> rate;
      swung_jacobian_rate(swung_surface_at(c.surface, c.mode, q), uv.x(), uv.y(), 2, c.mode, qd,
                          rate);
      const SwungJacobian plus = jacobian_at(c, q + h * qd, uv);
      const SwungJacobian minus = jacobian_at(c, q - h * qd, uv);
      for (int quantity = 0; quantity < 6; ++quantity) {
        // Jdot qd = d/ds [dense_jacobian(q + s qd)] qd at s = 0.
        const Eigen::Vector3d fd =
            (dense(plus, quantity, n) * qd - dense(minus, quantity, n) * qd) / (2 * h);
        // O(h^2) truncation with third derivatives of size ~1e2 (~1e-8) + round-off ~1e-11.
        EXPECT_LT((rate[static_cast<size_t>(quantity)] - fd).norm(), 1e-7 * (1.0 + fd.norm()))
            << c.name << ", quantity " << quantity << " at " << uv.transpose();
        if (c.mode == WeightMode::kFixed) {
          // Bilinear in the curves: Jdot qd = 2 alpha (f' g') in x, y and 0 in z, never zero.
          EXPECT_EQ(rate[static_cast<size_t>(quantity)].z(), 0.0);
          EXPECT_GT(rate[static_cast<size_t>(quantity)].norm(), 1e-3);
        }
      }
    }
  }
}

TEST(SwungJacobian, HessianContractionMatchesFiniteDifferencesOfTheJacobian) {
  for (const JacobianCase& c : jacobian_cases()) {
    const Eigen::VectorXd q = swung_coordinates(c.surface, c.mode);
    const SwungLayout layout = swung_layout(c.surface, c.mode);
    const int n = static_cast<int>(q.size());
    const Eigen::Vector3d lambda(0.7, -1.1, 0.4);
    const double h = 1e-6;
    for (const Eigen::Vector2d& uv : sample_parameters) {
      const SwungSurface surface = swung_surface_at(c.surface, c.mode, q);
      PlanarCurveSample profile;
      PlanarCurveSample trajectory;
      planar_curve_basis(surface.profile().knots(), uv.x(), profile);
      planar_curve_basis(surface.trajectory().knots(), uv.y(), trajectory);
      planar_curve_rational(swung_profile_net(layout, q.data(), surface.profile().weights().data()),
                            profile);
      planar_curve_rational(
          swung_trajectory_net(layout, q.data(), surface.trajectory().weights().data()),
          trajectory);
      const SwungJacobian jacobian = jacobian_at(c, q, uv);
      for (int quantity = 0; quantity < 6; ++quantity) {
        Eigen::MatrixXd local = Eigen::MatrixXd::Zero(jacobian.column_count, jacobian.column_count);
        add_swung_hessian(profile, trajectory, surface.alpha(), layout,
                          static_cast<SurfaceQuantity>(quantity), lambda, local);
        EXPECT_EQ(local, local.transpose());  // exactly symmetric by construction
        Eigen::MatrixXd global = Eigen::MatrixXd::Zero(n, n);
        for (int i = 0; i < jacobian.column_count; ++i) {
          for (int j = 0; j < jacobian.column_count; ++j) {
            global(jacobian.coordinate[static_cast<size_t>(i)],
                   jacobian.coordinate[static_cast<size_t>(j)]) += local(i, j);
          }
        }
        // Column k of sum_c lambda_c d^2 S_c / dq dq = d/dq_k (dense_jacobian^T lambda).
        for (int k = 0; k < n; ++k) {
          Eigen::VectorXd plus = q;
          Eigen::VectorXd minus = q;
          plus[k] += h;
          minus[k] -= h;
          const Eigen::VectorXd fd = (dense(jacobian_at(c, plus, uv), quantity, n).transpose() -
                                      dense(jacobian_at(c, minus, uv), quantity, n).transpose()) *
                                     lambda / (2 * h);
          // O(h^2) truncation + O(1e-16 |dense_jacobian| / h) round-off, |dense_jacobian| up to
          // ~1e2.
          EXPECT_LT((global.col(k) - fd).norm(), 1e-7 * (1.0 + fd.norm()))
              << c.name << ", quantity " << quantity << ", coordinate " << k;
        }
      }
    }
  }
}

TEST(SwungJacobian, ScalingGaugeDirectionDoesNotMoveTheSurface) {
  for (const JacobianCase& c : jacobian_cases()) {
    const SwungLayout layout = swung_layout(c.surface, c.mode);
    const Eigen::VectorXd q = swung_coordinates(c.surface, c.mode);
    // (p_x, t) -> (s p_x, t / s): d/ds at s = 1 is (x_i, -X_j, -Y_j), zero elsewhere.
    Eigen::VectorXd gauge = Eigen::VectorXd::Zero(q.size());
    for (int i = 0; i < layout.profile_count; ++i) {
      gauge[layout.profile_offset(i)] = q[layout.profile_offset(i)];
    }
    for (int j = 0; j < layout.trajectory_count; ++j) {
      gauge.segment<2>(layout.trajectory_offset(j)) = -q.segment<2>(layout.trajectory_offset(j));
    }
    for (const Eigen::Vector2d& uv : sample_parameters) {
      const SwungJacobian jacobian = jacobian_at(c, q, uv);
      for (int quantity = 0; quantity < 6; ++quantity) {
        const Eigen::MatrixXd dense_jacobian =
            dense(jacobian, quantity, static_cast<int>(q.size()));
        // alpha (R_a x_a g - f R_b X_b) = alpha (f g - f g): cancels up to rounding.
        EXPECT_LT((dense_jacobian * gauge).norm(), 1e-13 * dense_jacobian.norm() * gauge.norm())
            << c.name;
      }
    }
  }
}

TEST(SwungCoordinates, RoundTripAndValidation) {
  const SwungSurface surface = testing::random_swung_surface(3, 2, 81, true);
  for (const WeightMode mode : {WeightMode::kFixed, WeightMode::kFree}) {
    const Eigen::VectorXd q = swung_coordinates(surface, mode);
    const SwungSurface back = swung_surface_at(surface, mode, q);
    EXPECT_EQ(back.profile().control_points(), surface.profile().control_points());
    EXPECT_EQ(back.trajectory().weights(), surface.trajectory().weights());
    EXPECT_EQ(swung_coordinates(back, mode), q);
  }
  const SwungLayout layout = swung_layout(surface, WeightMode::kFree);
  EXPECT_EQ(layout.trajectory_offset(0), 3 * surface.profile().control_point_count());
  Eigen::VectorXd q = swung_coordinates(surface, WeightMode::kFree);
  EXPECT_NE(testing::error_message(
                [&] { (void)swung_surface_at(surface, WeightMode::kFree, q.head(q.size() - 1)); })
                .find("has " + std::to_string(q.size() - 1) + " entries, expected " +
                      std::to_string(q.size())),
            std::string::npos);
  q[layout.trajectory_offset(2) + 2] = -0.5;
  EXPECT_NE(testing::error_message([&] {
              (void)swung_surface_at(surface, WeightMode::kFree, q);
            }).find("weight 2 is -0.5"),
            std::string::npos);
  q[layout.trajectory_offset(2) + 2] = 1.0;
  q[4] = std::nan("");
  EXPECT_NE(testing::error_message([&] {
              (void)swung_surface_at(surface, WeightMode::kFree, q);
            }).find("coordinate 4 is nan"),
            std::string::npos);
}

}  // namespace
}  // namespace dnurbs
