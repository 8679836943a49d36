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

}  // namespace dnurbs::tools
