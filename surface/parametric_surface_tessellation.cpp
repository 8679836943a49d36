#include "dnurbs/surface/parametric_surface_tessellation.h"

#include <utility>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/surface/parametric_surface_mesh_builder.h"

namespace dnurbs {

TriangleMesh tessellate_surface(const ParametricSurface& surface, int segments_u, int segments_v,
                                std::string name) {
  const ParameterDomain& domain = surface.domain();
  if (segments_u < (domain.periodic_u ? 3 : 1) || segments_v < (domain.periodic_v ? 3 : 1)) {
    throw make_error("tessellation: resolution ", segments_u, " by ", segments_v,
                     " is below 1 (3 along a periodic direction)");
  }
  const int count_u = domain.periodic_u ? segments_u : segments_u + 1;
  const int count_v = domain.periodic_v ? segments_v : segments_v + 1;
  ParametricSurfaceMeshBuilder builder(surface);
  // Sample the grid, u outer; pole rows collapse into one vertex each
  std::vector<int> index(static_cast<size_t>(count_u) * static_cast<size_t>(count_v));
  for (int i = 0; i < count_u; ++i) {
    const double u = domain.u_at(static_cast<double>(i) / segments_u);
    for (int j = 0; j < count_v; ++j) {
      const double v = domain.v_at(static_cast<double>(j) / segments_v);
      index[static_cast<size_t>(i) * static_cast<size_t>(count_v) + static_cast<size_t>(j)] =
          builder.add_vertex(u, v);
    }
  }
  // Two triangles per cell, periodic directions wrapping to the first sample
  auto at = [&](int i, int j) {
    return index[static_cast<size_t>(i % count_u) * static_cast<size_t>(count_v) +
                 static_cast<size_t>(j % count_v)];
  };
  for (int i = 0; i < segments_u; ++i) {
    for (int j = 0; j < segments_v; ++j) {
      const int a = at(i, j);
      const int b = at(i + 1, j);
      const int c = at(i + 1, j + 1);
      const int d = at(i, j + 1);
      builder.add_triangle(a, b, c);
      builder.add_triangle(a, c, d);
    }
  }
  return builder.build(std::move(name));
}

}  // namespace dnurbs
