#include "dnurbs/vision/freudenthal_grid.h"

#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

FreudenthalGrid::FreudenthalGrid(const Eigen::Vector2d& origin, double cell_size, int cells_x,
                                 int cells_y)
    : origin_(origin), cell_size_(cell_size), cells_x_(cells_x), cells_y_(cells_y) {
  if (!(std::isfinite(cell_size) && cell_size > 0.0)) {
    throw make_error("Freudenthal grid cell size ", cell_size, " is not positive and finite");
  }
  if (!origin.allFinite()) {
    throw make_error("Freudenthal grid origin (", origin.x(), ", ", origin.y(), ") is not finite");
  }
  if (cells_x < 2 || cells_y < 2) {
    throw make_error("Freudenthal grid of ", cells_x, " by ", cells_y,
                     " cells has fewer than 2 per side");
  }
  if (static_cast<long long>(cells_x + 1) * (cells_y + 1) > (1LL << 24)) {
    throw make_error("Freudenthal grid of ", cells_x, " by ", cells_y,
                     " cells exceeds 2^24 vertices");
  }
}

int FreudenthalGrid::edge_between(const Eigen::Vector2i& a, const Eigen::Vector2i& b) const {
  const Eigen::Vector2i first = (a.x() + a.y() <= b.x() + b.y()) ? a : b;
  const Eigen::Vector2i step =
      (a.x() + a.y() <= b.x() + b.y()) ? Eigen::Vector2i(b - a) : Eigen::Vector2i(a - b);
  const int family = step.x() == 1 ? (step.y() == 1 ? kDiagonal : kHorizontal) : kVertical;
  return edge_id(family, first.x(), first.y());
}

std::array<std::array<Eigen::Vector2i, 3>, 2> FreudenthalGrid::cell_triangles(int i, int j) const {
  const Eigen::Vector2i v00(i, j);
  const Eigen::Vector2i v10(i + 1, j);
  const Eigen::Vector2i v11(i + 1, j + 1);
  const Eigen::Vector2i v01(i, j + 1);
  return {{{v00, v10, v11}, {v00, v11, v01}}};
}

}  // namespace dnurbs
