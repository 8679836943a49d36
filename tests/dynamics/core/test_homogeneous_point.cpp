// Tests of dynamics/core/homogeneous_point.h: the rational point and its derivatives from the
// homogeneous sums equal those of the rational Jacobian (dynamics/core/quadrature_assembly.h) and
// finite differences; the force density applied through the basis equals J^T h formed from the
// Jacobian's columns; the rate equals J_0 xi. On a bicubic patch over non-uniform knots with
// random weights, and on a cubic curve (no v derivatives).

#include "dnurbs/dynamics/core/homogeneous_point.h"

#include <array>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "dnurbs/nurbs/knot_vector.h"

namespace dnurbs {
namespace {

// A control net of `count` nodes with free-weight layout (x, y, z, w per node), random.
std::vector<double> random_net(int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  std::uniform_real_distribution<double> weight(0.4, 2.5);
  std::vector<double> net(static_cast<size_t>(4 * count));
  for (int i = 0; i < count; ++i) {
    for (int r = 0; r < 3; ++r) {
      net[static_cast<size_t>(4 * i + r)] = coordinate(random);
    }
    net[static_cast<size_t>(4 * i + 3)] = weight(random);
  }
  return net;
}

ControlNet view(const std::vector<double>& net) {
  ControlNet result;
  result.positions = net.data();
  result.position_stride = 4;
  result.weights = net.data() + 3;
  result.weight_stride = 4;
  return result;
}

struct Patch {
  KnotVector knots_u;
  KnotVector knots_v;
  bool surface;
  int count_v;
};

Patch surface_patch() {
  return {KnotVector(3, {0, 0, 0, 0, 0.2, 0.5, 0.55, 1, 1, 1, 1}),
          KnotVector(3, {0, 0, 0, 0, 0.3, 0.4, 1, 1, 1, 1}), true, 6};
}

Patch curve_patch() {
  const KnotVector knots(3, {0, 0, 0, 0, 0.2, 0.5, 0.55, 1, 1, 1, 1});
  return {knots, knots, false, 1};
}

PointBasis basis_at(const Patch& patch, double u, double v) {
  DirectionBasis basis_u;
  DirectionBasis basis_v;
  direction_basis(patch.knots_u, u, basis_u);
  if (patch.surface) {
    direction_basis(patch.knots_v, v, basis_v);
  } else {
    trivial_direction_basis(basis_v);
  }
  PointBasis basis;
  tensor_product_basis(basis_u, basis_v, patch.count_v, basis);
  return basis;
}

HomogeneousSums sums_at(const PointBasis& basis, const ControlNet& net) {
  HomogeneousSums sums{};
  for (auto& sum : sums) {
    sum.setZero();
  }
  for (int a = 0; a < basis.active_count; ++a) {
    const int node = basis.node[static_cast<size_t>(a)];
    const double w = net.weights[node * net.weight_stride];
    Eigen::Vector4d homogeneous;
    homogeneous << w * Eigen::Map<const Eigen::Vector3d>(net.positions +
                                                         node * net.position_stride),
        w;
    for (int alpha = 0; alpha < kQuantityCount; ++alpha) {
      sums[static_cast<size_t>(alpha)] += basis.value(alpha, a) * homogeneous;
    }
  }
  return sums;
}

int node_count(const Patch& patch) {
  return patch.knots_u.control_point_count() * patch.count_v;
}

TEST(HomogeneousPoint, DerivativesEqualTheRationalJacobianAndFiniteDifferences) {
  for (const Patch& patch : {surface_patch(), curve_patch()}) {
    const std::vector<double> net = random_net(node_count(patch), 3);
    const int order_v = patch.surface ? 2 : 0;
    for (const auto& [u, v] : std::vector<std::pair<double, double>>{
             {0.1, 0.7}, {0.37, 0.35}, {0.52, 0.12}, {0.8, 0.9}}) {
      const PointBasis basis = basis_at(patch, u, v);
      RationalJacobian jacobian;
      rational_jacobian(basis, 2, view(net), true, jacobian);
      HomogeneousPoint point;
      homogeneous_point(sums_at(basis, view(net)), 2, order_v, point);
      EXPECT_NEAR(point.inverse_weight[0], 1.0 / jacobian.weight_sum, 1e-15);
      for (int alpha = 0; alpha < kQuantityCount; ++alpha) {
        // The same quotient rule summed in another order: rounding, 1e-13 relative
        const Eigen::Vector3d& expected = jacobian.point[static_cast<size_t>(alpha)];
        EXPECT_LT((point.point[static_cast<size_t>(alpha)] - expected).norm(),
                  1e-13 * (1.0 + expected.norm()))
            << "quantity " << alpha << " at (" << u << ", " << v << ")";
      }
      // x_u and x_uu by central differences of x and x_u (h = 1e-5: truncation h^2 x''' ~ 1e-8)
      const double h = 1e-5;
      HomogeneousPoint plus;
      HomogeneousPoint minus;
      homogeneous_point(sums_at(basis_at(patch, u + h, v), view(net)), 2, order_v, plus);
      homogeneous_point(sums_at(basis_at(patch, u - h, v), view(net)), 2, order_v, minus);
      EXPECT_LT(((plus.point[0] - minus.point[0]) / (2 * h) - point.point[1]).norm(), 1e-6);
      EXPECT_LT(((plus.point[1] - minus.point[1]) / (2 * h) - point.point[3]).norm(), 1e-5);
      if (patch.surface) {
        EXPECT_LT(((plus.point[2] - minus.point[2]) / (2 * h) - point.point[4]).norm(), 1e-5);
      } else {
        EXPECT_EQ(point.point[2].norm() + point.point[4].norm() + point.point[5].norm(), 0.0);
      }
    }
  }
}

TEST(HomogeneousPoint, ForceDensityThroughTheBasisEqualsJacobianTransposeTimesH) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (const Patch& patch : {surface_patch(), curve_patch()}) {
    const int nodes = node_count(patch);
    const std::vector<double> net = random_net(nodes, 5);
    const int order_v = patch.surface ? 2 : 0;
    for (const int order : {0, 1, 2}) {
      const PointBasis basis = basis_at(patch, 0.41, 0.63);
      RationalJacobian jacobian;
      rational_jacobian(basis, order, view(net), true, jacobian);
      HomogeneousPoint point;
      homogeneous_point(sums_at(basis, view(net)), order, order_v, point);
      std::array<Eigen::Vector3d, kQuantityCount> h{};
      for (auto& vector : h) {
        vector << value(random), value(random), value(random);
      }
      HomogeneousSums density{};
      homogeneous_force_density(point, h, density);
      // F from the density: F^h_a = sum_beta N_a^beta density_beta, then (P, w) by the chain rule
      Eigen::VectorXd force = Eigen::VectorXd::Zero(4 * nodes);
      Eigen::VectorXd expected = Eigen::VectorXd::Zero(4 * nodes);
      for (int a = 0; a < basis.active_count; ++a) {
        const int node = basis.node[static_cast<size_t>(a)];
        Eigen::Vector4d homogeneous = Eigen::Vector4d::Zero();
        for (int beta = 0; beta < point.quantities; ++beta) {
          homogeneous += basis.value(beta, a) * density[static_cast<size_t>(beta)];
        }
        const Eigen::Map<const Eigen::Vector3d> position(&net[static_cast<size_t>(4 * node)]);
        const double w = net[static_cast<size_t>(4 * node + 3)];
        force.segment<3>(4 * node) = w * homogeneous.head<3>();
        force[4 * node + 3] = position.dot(homogeneous.head<3>()) + homogeneous[3];
        // J^T h from the Jacobian's columns, over the quantities with a basis
        for (int alpha = 0; alpha < quantity_count(order); ++alpha) {
          if (!patch.surface && (alpha == 2 || alpha == 4 || alpha == 5)) {
            continue;
          }
          const Eigen::Vector3d& h_alpha = h[static_cast<size_t>(alpha)];
          expected.segment<3>(4 * node) += jacobian.rational(alpha, a) * h_alpha;
          expected[4 * node + 3] +=
              jacobian.weight_column[static_cast<size_t>(alpha)].col(a).dot(h_alpha);
        }
      }
      EXPECT_GT(expected.norm(), 0.1);
      EXPECT_LT((force - expected).norm(), 1e-13 * expected.norm())
          << (patch.surface ? "surface" : "curve") << ", order " << order;
      // The rate: J_0 xi for a random rate xi of (P, w)
      Eigen::VectorXd xi(4 * nodes);
      for (Eigen::Index k = 0; k < xi.size(); ++k) {
        xi[k] = value(random);
      }
      Eigen::Vector4d rate_sum = Eigen::Vector4d::Zero();
      Eigen::Vector3d rate = Eigen::Vector3d::Zero();
      for (int a = 0; a < basis.active_count; ++a) {
        const int node = basis.node[static_cast<size_t>(a)];
        const Eigen::Map<const Eigen::Vector3d> position(&net[static_cast<size_t>(4 * node)]);
        const double w = net[static_cast<size_t>(4 * node + 3)];
        Eigen::Vector4d homogeneous_rate;
        homogeneous_rate << w * xi.segment<3>(4 * node) + xi[4 * node + 3] * position,
            xi[4 * node + 3];
        rate_sum += basis.value(0, a) * homogeneous_rate;
        rate += jacobian.rational(0, a) * xi.segment<3>(4 * node) +
                jacobian.weight_column[0].col(a) * xi[4 * node + 3];
      }
      EXPECT_LT((rational_rate(point, rate_sum) - rate).norm(), 1e-14 * (1.0 + rate.norm()));
    }
  }
}

}  // namespace
}  // namespace dnurbs
