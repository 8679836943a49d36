#include "dnurbs/dynamics/swung/swung_gauge.h"

#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

Eigen::VectorXd swung_scaling_gauge_direction(const SwungLayout& layout, const Eigen::VectorXd& q) {
  if (q.size() != layout.coordinate_count()) {
    throw make_error("swung gauge: coordinate vector has ", q.size(), " entries, the layout has ",
                     layout.coordinate_count());
  }
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  for (int i = 0; i < layout.profile_count; ++i) {
    const int x = layout.profile_offset(i);
    g[x] = q[x];
  }
  for (int j = 0; j < layout.trajectory_count; ++j) {
    const int x = layout.trajectory_offset(j);
    g[x] = -q[x];
    g[x + 1] = -q[x + 1];
  }
  return g;
}

int swung_scaling_gauge_coordinate(const SwungLayout& layout, const Eigen::VectorXd& q) {
  double largest = 0.0;
  const int middle = layout.profile_count - 1;  // twice the middle index
  int best_distance = 0;
  int gauge = -1;
  for (int i = 0; i < layout.profile_count; ++i) {
    const int index = layout.profile_offset(i);
    const double x = std::abs(q[index]);
    const int distance = std::abs(2 * i - middle);
    if (x > largest || (x == largest && x > 0.0 && distance < best_distance)) {
      largest = x;
      best_distance = distance;
      gauge = index;
    }
  }
  if (gauge < 0) {
    throw make_error(
        "every profile control point is on the z axis (x = 0): the swung surface is degenerate "
        "and its scaling gauge cannot be fixed");
  }
  return gauge;
}

bool fixes_swung_scaling_gauge(const SwungLayout& layout, const Eigen::VectorXd& q, int gauge,
                               const std::vector<int>& coordinates) {
  const Eigen::VectorXd g = swung_scaling_gauge_direction(layout, q);
  for (const int k : coordinates) {
    if (k != gauge && k >= 0 && k < g.size() && g[k] != 0.0) {
      return true;
    }
  }
  return false;
}

}  // namespace dnurbs
