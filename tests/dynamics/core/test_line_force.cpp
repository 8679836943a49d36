#include "dnurbs/dynamics/core/line_force.h"

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/surface/grid.h"

namespace dnurbs {
namespace {

TEST(LineForce, IsTheSameForceAtEveryPointOfTheLine) {
  // On a grid surface a point force at a node acts on that node only: the upper row's nodes
  // each receive f exactly, every other node nothing.
  const Grid grid(5, 4, 0.5);
  const TerzopoulosSurface curtain(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()));
  const Eigen::Vector3d f(-1.0, 0.5, 2.0);
  const Force force = line_force(grid.row_parameters(0), [f](double) { return f; });
  const Eigen::VectorXd q = curtain.initial_coordinates();
  Eigen::VectorXd generalized = Eigen::VectorXd::Zero(q.size());
  force(curtain, 0.0, q, Eigen::VectorXd::Zero(q.size()), generalized);
  for (int k = 0; k < grid.node_count(); ++k) {
    const Eigen::Vector3d expected = grid.node(k).second == 0 ? f : Eigen::Vector3d::Zero();
    EXPECT_EQ(Eigen::Vector3d(generalized.segment<3>(3 * k)), expected) << "node " << k;
  }
  EXPECT_THROW(line_force({}, [f](double) { return f; }), Error);
  EXPECT_THROW(grid.row_parameters(4), Error);
}

}  // namespace
}  // namespace dnurbs
