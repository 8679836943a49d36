// Edge forces of images and volumes (dynamics/core/image_force.h): -grad P in model space
// against finite differences of the potential through the frame, the node weights of grid
// surfaces, a snake settling on a disc's edge, and the errors.

#include "dnurbs/dynamics/core/image_force.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/grid/snake.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "tests/common/error_message.h"
#include "tests/vision/vision_test_images.h"

namespace dnurbs {
namespace {

using testing::coverage_image;
using testing::coverage_volume;
using testing::disc;
using testing::error_message;

// A ring of n nodes of radius r about c in the plane z = c.z().
NodePositions ring(int n, double r, const Eigen::Vector3d& c) {
  NodePositions positions(n, 3);
  for (int i = 0; i < n; ++i) {
    const double angle = 2.0 * M_PI * i / n;
    positions.row(i) = (c + r * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0)).transpose();
  }
  return positions;
}

Eigen::VectorXd force_of(const Force& force, const Model& model, const Eigen::VectorXd& q) {
  Eigen::VectorXd generalized = Eigen::VectorXd::Zero(model.velocity_count());
  force(model, 0.0, q, Eigen::VectorXd::Zero(model.velocity_count()), generalized);
  return generalized;
}

TEST(ImageEdgeForce, IsMinusTheGradientOfThePotentialInModelSpace) {
  // An off-centre disc, a frame with unequal pixel sizes and an origin off zero: the force at
  // every node equals -grad_x P(x) by central differences of P through x = origin + spacing .* p
  // (step 1e-5 model units; the interpolant is C1 and piecewise cubic, so the difference
  // quotient's error is O(step^2 |P'''| / spacing^3) ~ 1e-8 of the force).
  const auto potential = std::make_shared<const ImageEdgePotential>(
      coverage_image(48, 40, disc({21.3, 18.6}, 9.0)), 1.5, 2.0);
  const ImageFrame frame{Eigen::Vector3d(-1.0, 2.0, 0.5), Eigen::Vector3d(0.1, 0.2, 1.0)};
  const Eigen::Vector3d centre =
      frame.origin + frame.spacing.cwiseProduct(Eigen::Vector3d(21.3, 18.6, 0));
  SnakeMaterial material;
  const Snake snake(NodeChain(12, true), ring(12, 1.0, centre), material);
  const Eigen::VectorXd q = snake.initial_coordinates();
  const Eigen::VectorXd force = force_of(image_edge_force(potential, frame), snake, q);
  const auto world_potential = [&](const Eigen::Vector2d& x) {
    return potential->value((x - frame.origin.head<2>()).cwiseQuotient(frame.spacing.head<2>()));
  };
  double largest = 0.0;
  for (int i = 0; i < 12; ++i) {
    const int offset = snake.control_point_offset(i);
    const Eigen::Vector2d x = q.segment<2>(offset);
    const double step = 1e-5;
    Eigen::Vector2d expected;
    for (int axis = 0; axis < 2; ++axis) {
      const Eigen::Vector2d e = step * Eigen::Vector2d::Unit(axis);
      expected[axis] = -(world_potential(x + e) - world_potential(x - e)) / (2.0 * step);
    }
    EXPECT_LT((force.segment<2>(offset) - expected).norm(), 1e-6 * expected.norm()) << i;
    EXPECT_EQ(force[offset + 2], 0.0);  // a 2-D image pulls in its plane only
    largest = std::max(largest, expected.norm());
  }
  EXPECT_GT(largest, 1.0);  // the ring crosses the edge band: the forces are not all zero
}

TEST(VolumeEdgeForce, IsMinusTheGradientOfThePotentialInThreeDimensions) {
  const auto potential = std::make_shared<const VolumeEdgePotential>(
      coverage_volume(24, 22, 20,
                      [](const Eigen::Vector3d& p) {
                        return (p - Eigen::Vector3d(11.2, 10.7, 9.6)).norm() <= 6.0;
                      }),
      1.0, 1.0);
  const ImageFrame frame{Eigen::Vector3d(0.5, -0.25, 1.0), Eigen::Vector3d(0.05, 0.05, 0.1)};
  const auto voxel = [&](const Eigen::Vector3d& x) {
    return Eigen::Vector3d((x - frame.origin).cwiseQuotient(frame.spacing));
  };
  // A ring 2.5 voxels above the ball's centre, of radius near the ball's section there.
  const Eigen::Vector3d centre =
      frame.origin + frame.spacing.cwiseProduct(Eigen::Vector3d(11.2, 10.7, 12.1));
  const Snake snake(NodeChain(10, true), ring(10, 0.27, centre), SnakeMaterial{});
  const Eigen::VectorXd q = snake.initial_coordinates();
  const Eigen::VectorXd force = force_of(volume_edge_force(potential, frame), snake, q);
  double largest_z = 0.0;
  for (int i = 0; i < 10; ++i) {
    const int offset = snake.control_point_offset(i);
    const Eigen::Vector3d x = q.segment<3>(offset);
    const double step = 1e-5;
    Eigen::Vector3d expected;
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Vector3d e = step * Eigen::Vector3d::Unit(axis);
      expected[axis] =
          -(potential->value(voxel(x + e)) - potential->value(voxel(x - e))) / (2.0 * step);
    }
    EXPECT_LT((force.segment<3>(offset) - expected).norm(), 1e-6 * expected.norm()) << i;
    largest_z = std::max(largest_z, std::abs(expected.z()));
  }
  EXPECT_GT(largest_z, 0.1);  // above the equator the edge pulls along z as well
}

TEST(ImageEdgeForce, GridSurfacesTakeItWithTheirNodeWeights) {
  // A node-sampled surface receives w_i f(x_i) at node i, with the same node weights w_i as
  // gravity's density mu g: image force_i = (gravity_i / (mu g)) (-grad P(x_i)).
  const auto potential = std::make_shared<const ImageEdgePotential>(
      coverage_image(40, 40, disc({19.5, 20.5}, 10.0)), 2.0, 1.0);
  const ImageFrame frame{Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.1)};
  const Grid grid(7, 7, 0.35);
  const TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d(0.9, 0.9, 0)));
  const Eigen::VectorXd q = sheet.initial_coordinates();
  const Eigen::VectorXd image = force_of(image_edge_force(potential, frame), sheet, q);
  const Eigen::VectorXd weight = force_of(gravity(Eigen::Vector3d(0, 0, 1)), sheet, q);
  for (int i = 0; i < grid.node_count(); ++i) {
    const int offset = sheet.control_point_offset(i);
    const Eigen::Vector2d pixel = q.segment<2>(offset) / 0.1;
    const Eigen::Vector2d expected = -weight[offset + 2] * potential->gradient(pixel) / 0.1;
    EXPECT_LT((image.segment<2>(offset) - expected).norm(), 1e-12 * (1.0 + expected.norm())) << i;
  }
}

TEST(ImageEdgeForce, SnakeSettlesOnTheEdgeOfADisc) {
  // A disc of radius R = 15 px, blurred by sigma = 1.5 px: the edge strength |grad(G * I)| peaks
  // sigma^2 / (2R) = 0.075 px inside the circle. A closed snake started 1.5 px outside, in model
  // units of 0.05 per pixel, settles there. The peak's position varies with the angle by up to
  // 0.1 px (the coverage rendering on the pixel grid and the cubic interpolation, bounded by
  // ImageEdgePotential.DiscEdgeIsTheMinimumOfThePotential), which bounds the spread of the radii
  // and, averaged, the mean (measured: mean 14.917 px against 14.925, spread 0.081 px); the
  // tension's inward pull, its force over P'', is ~1e-4 px.
  const double radius = 15.0;
  const double sigma = 1.5;
  const Eigen::Vector2d centre(32.4, 31.8);
  const auto potential = std::make_shared<const ImageEdgePotential>(
      coverage_image(64, 64, disc(centre, radius)), sigma, 1.0);
  const double pixel = 0.05;
  const ImageFrame frame{Eigen::Vector3d(-1.0, -1.0, 0.0), Eigen::Vector3d::Constant(pixel)};
  const Eigen::Vector3d world_centre =
      frame.origin + pixel * Eigen::Vector3d(centre.x(), centre.y(), 0.0);
  const int n = 48;
  SnakeMaterial material;
  material.mass_density = 1e-3;
  material.damping_density = 1.0;
  material.constant_tension = 1e-7;
  material.constant_rigidity = 1e-11;
  const Snake snake(NodeChain(n, true), ring(n, (radius + 1.5) * pixel, world_centre), material);
  System system(snake);
  system.add_force(0, image_edge_force(potential, frame));
  Integrator integrator(IntegratorSettings{IntegratorScheme::kImplicitEuler});
  for (int s = 0; s < 2000; ++s) {
    integrator.step(system, 0.01);
  }
  const NodePositions r = snake.positions(system.coordinates(0));
  const Eigen::ArrayXd radii =
      (r.leftCols<2>().rowwise() - world_centre.head<2>().transpose()).rowwise().norm().array() /
      pixel;
  std::printf("snake on a disc: mean radius %.4f px, spread %.2e px\n", radii.mean(),
              radii.maxCoeff() - radii.minCoeff());
  EXPECT_NEAR(radii.mean(), radius - sigma * sigma / (2.0 * radius), 0.03);
  EXPECT_LT(radii.maxCoeff() - radii.minCoeff(), 0.12);
}

TEST(ImageEdgeForce, BadInputIsNamed) {
  const auto potential =
      std::make_shared<const ImageEdgePotential>(coverage_image(8, 8, disc({4, 4}, 2.0)), 1.0, 1.0);
  EXPECT_THAT(error_message([&] { image_edge_force(nullptr); }),
              ::testing::HasSubstr("no potential"));
  EXPECT_THAT(error_message([&] {
                image_edge_force(potential, {Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 1)});
              }),
              ::testing::HasSubstr("spacing y = 0"));
  EXPECT_THAT(error_message([&] { volume_edge_force(nullptr, {}); }),
              ::testing::HasSubstr("no potential"));
  EXPECT_THAT(error_message([&] {
                image_edge_force(potential, {Eigen::Vector3d(NAN, 0, 0), Eigen::Vector3d::Ones()});
              }),
              ::testing::HasSubstr("origin (nan"));
}

}  // namespace
}  // namespace dnurbs
