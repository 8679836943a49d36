#pragma once
// Comparing fitted surfaces with their source, for the io and tools tests of the "fit" key.

#include <algorithm>
#include <limits>
#include <utility>

#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs::testing {

/// Largest distance between corresponding control points of a and b (same knots, square nets),
/// over the eight parametrizations of one surface (u and v reversed or swapped): a fit starts
/// over the principal axes of its points, whose signs are arbitrary.
inline double control_point_distance_up_to_symmetry(const NurbsSurface& a, const NurbsSurface& b) {
  const int n = a.control_point_count_u();
  double best = std::numeric_limits<double>::infinity();
  for (int symmetry = 0; symmetry < 8; ++symmetry) {
    double worst = 0.0;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        int bi = (symmetry & 1) != 0 ? n - 1 - i : i;
        int bj = (symmetry & 2) != 0 ? n - 1 - j : j;
        if ((symmetry & 4) != 0) {
          std::swap(bi, bj);
        }
        worst = std::max(worst, (a.control_points().row(a.control_point_index(i, j)) -
                                 b.control_points().row(b.control_point_index(bi, bj)))
                                    .norm());
      }
    }
    best = std::min(best, worst);
  }
  return best;
}

}  // namespace dnurbs::testing
