#include "dnurbs/vision/tetrahedral_grid.h"

#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {
constexpr std::array<std::array<int, 3>, TetrahedralGrid::kFamilies> kDirections = {
    {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}}};
}  // namespace

TetrahedralGrid::TetrahedralGrid(const Eigen::Vector3d& origin, double cell_size,
                                 const Eigen::Vector3i& cells)
    : origin_(origin), cell_size_(cell_size), cells_(cells) {
  if (!(std::isfinite(cell_size) && cell_size > 0.0)) {
    throw make_error("tetrahedral grid cell size ", cell_size, " is not positive and finite");
  }
  if (!origin.allFinite()) {
    throw make_error("tetrahedral grid origin (", origin.x(), ", ", origin.y(), ", ", origin.z(),
                     ") is not finite");
  }
  if (cells.minCoeff() < 2) {
    throw make_error("tetrahedral grid of ", cells.x(), " by ", cells.y(), " by ", cells.z(),
                     " cells has fewer than 2 per side");
  }
  if (static_cast<long long>(cells.x() + 1) * (cells.y() + 1) * (cells.z() + 1) > (1LL << 24)) {
    throw make_error("tetrahedral grid of ", cells.x(), " by ", cells.y(), " by ", cells.z(),
                     " cells exceeds 2^24 vertices");
  }
}

bool TetrahedralGrid::on_border(const Eigen::Vector3i& g) const {
  return g.minCoeff() == 0 || g.x() == cells_.x() || g.y() == cells_.y() || g.z() == cells_.z();
}

Eigen::Vector3i TetrahedralGrid::direction(int family) {
  const auto& d = kDirections[static_cast<std::size_t>(family)];
  return {d[0], d[1], d[2]};
}

int TetrahedralGrid::family_of(const Eigen::Vector3i& step) {
  for (int family = 0; family < kFamilies; ++family) {
    if (step == direction(family) || step == -direction(family)) {
      return family;
    }
  }
  return -1;
}

std::array<std::array<Eigen::Vector3i, 4>, 6> TetrahedralGrid::cube_tetrahedra(
    const Eigen::Vector3i& g) {
  static constexpr std::array<std::array<int, 3>, 6> kOrders = {
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  std::array<std::array<Eigen::Vector3i, 4>, 6> tetrahedra;
  for (std::size_t t = 0; t < 6; ++t) {
    Eigen::Vector3i vertex = g;
    tetrahedra[t][0] = vertex;
    for (std::size_t k = 0; k < 3; ++k) {
      vertex[kOrders[t][k]] += 1;
      tetrahedra[t][k + 1] = vertex;
    }
  }
  return tetrahedra;
}

}  // namespace dnurbs
