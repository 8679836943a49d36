#include "dnurbs/dynamics/core/line_force.h"

#include <utility>

#include "dnurbs/core/error.h"

namespace dnurbs {

Force line_force(std::vector<Eigen::Vector2d> points, VectorOfTime force) {
  if (points.empty()) {
    throw make_error("line force has no points");
  }
  for (size_t k = 0; k < points.size(); ++k) {
    if (!points[k].allFinite()) {
      throw make_error("line force point ", k, " (", points[k].x(), ", ", points[k].y(),
                       ") is not finite");
    }
  }
  if (!force) {
    throw make_error("line force has no force function");
  }
  return [points = std::move(points), force = std::move(force)](
             const Model& model, double t, ConstVectorRef q, ConstVectorRef /*qd*/,
             VectorRef generalized) {
    const Eigen::Vector3d f = force(t);
    for (const Eigen::Vector2d& u : points) {
      model.add_point_force(q, u, f, generalized);
    }
  };
}

}  // namespace dnurbs
