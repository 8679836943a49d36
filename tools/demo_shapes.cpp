#include "tools/demo_shapes.h"

#include <array>
#include <cmath>
#include <vector>

namespace dnurbs::tools {

NurbsSurface hat_surface() {
  constexpr int kCount = 7;
  const KnotVector knots = KnotVector::clamped_uniform(3, kCount);
  Eigen::MatrixX3d control_points(kCount * kCount, 3);
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(kCount * kCount);
  for (int i = 0; i < kCount; ++i) {
    for (int j = 0; j < kCount; ++j) {
      const double x = -1.2 + 0.4 * i;
      const double y = -1.2 + 0.4 * j;
      const double r = std::hypot(x, y);
      // Crown near the centre, brim curling up towards the rim
      const double crown = 1.4 * std::exp(-(r / 0.55) * (r / 0.55));
      const double brim = 0.12 * r * r * r / 1.7;
      const int row = i * kCount + j;
      control_points.row(row) << x, y, crown + brim;
      if (std::abs(i - 3) <= 1 && std::abs(j - 3) <= 1) {
        weights(row) = 2.5;
      }
    }
  }
  return NurbsSurface(knots, knots, control_points, weights);
}

NurbsSurface periodic_torus(double major_radius, double minor_radius,
                            const Eigen::Vector3d& centre) {
  // The 8 distinct control points of the unit rational quadratic circle, starting at angle 0
  const double s = std::sqrt(0.5);
  const std::array<std::array<double, 3>, 8> circle = {{{1, 0, 1},
                                                        {1, 1, s},
                                                        {0, 1, 1},
                                                        {-1, 1, s},
                                                        {-1, 0, 1},
                                                        {-1, -1, s},
                                                        {0, -1, 1},
                                                        {1, -1, s}}};
  const std::vector<double> period = {0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0};
  const KnotVector knots = KnotVector::periodic(2, period);
  Eigen::MatrixX3d control_points(64, 3);
  Eigen::VectorXd weights(64);
  for (int i = 0; i < 8; ++i) {    // u: around the z axis
    for (int j = 0; j < 8; ++j) {  // v: around the tube, from the outer equator upwards
      const auto& a = circle[static_cast<size_t>(i)];
      const auto& b = circle[static_cast<size_t>(j)];
      const double distance = major_radius + minor_radius * b[0];
      control_points.row(i * 8 + j) =
          centre.transpose() +
          Eigen::RowVector3d(distance * a[0], distance * a[1], minor_radius * b[1]);
      weights(i * 8 + j) = a[2] * b[2];
    }
  }
  return NurbsSurface(knots, knots, control_points, weights);
}

}  // namespace dnurbs::tools
