#include "dnurbs/surface/adaptive_tessellation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// True if the angle between unit vectors a and b is above the angle of cosine `cosine_limit`;
// false if either is zero.
bool angle_exceeds(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double cosine_limit) {
  return !a.isZero() && !b.isZero() && a.dot(b) < cosine_limit;
}

void check_sample_order(int sample_order) {
  if (sample_order < 1) {
    throw make_error("surface error: sample order ", sample_order, " is below 1");
  }
}

}  // namespace

RefinementTest depth_criterion(int depth) {
  if (depth < 0) {
    throw make_error("depth criterion: depth ", depth, " is negative");
  }
  return [depth](const RestrictedTriangleGeometry& triangle) { return triangle.level < depth; };
}

RefinementTest normal_angle_criterion(double max_angle) {
  if (!(max_angle > 0.0) || !(max_angle <= std::numbers::pi)) {
    throw make_error("normal angle criterion: max_angle ", max_angle, " is outside (0, pi]");
  }
  // Compare cosines: the angle exceeds max_angle where n_a . n_b < cos(max_angle)
  const double limit = std::cos(max_angle);
  return [limit](const RestrictedTriangleGeometry& triangle) {
    const auto& n = triangle.normals;
    return std::min({n[0].dot(n[1]), n[1].dot(n[2]), n[2].dot(n[0])}) < limit;
  };
}

RefinementTest normals_criterion(double ridge_angle, double endpoint_angle) {
  if (!(ridge_angle > 0.0) || !(ridge_angle <= std::numbers::pi)) {
    throw make_error("normals criterion: ridge_angle ", ridge_angle, " is outside (0, pi]");
  }
  if (!(endpoint_angle > 0.0) || !(endpoint_angle <= std::numbers::pi)) {
    throw make_error("normals criterion: endpoint_angle ", endpoint_angle, " is outside (0, pi]");
  }
  const double ridge_limit = std::cos(ridge_angle);
  const double endpoint_limit = std::cos(endpoint_angle);
  return [ridge_limit, endpoint_limit](const RestrictedTriangleGeometry& triangle) {
    if (triangle.mesh == nullptr) {
      throw make_error("normals criterion: triangle geometry without its mesh (level ",
                       triangle.level, ")");
    }
    const RestrictedMesh& mesh = *triangle.mesh;
    const Eigen::Vector3d facet = mesh.facet_normal(triangle.triangle);
    const std::array<int, 3>& vertex = mesh.triangle_vertices(triangle.triangle);
    for (int k = 0; k < 3; ++k) {
      // Goldenstein et al. 2005, section 5.2.2: the edge opposite corner k is a ridge or valley
      // when the facets on its two sides turn by more than the threshold, and jagged when the
      // facet normals averaged around its end points do
      const int across = mesh.neighbor(triangle.triangle, k);
      if (across >= 0 && angle_exceeds(facet, mesh.facet_normal(across), ridge_limit)) {
        return true;
      }
      if (angle_exceeds(mesh.averaged_facet_normal(vertex[static_cast<size_t>((k + 1) % 3)]),
                        mesh.averaged_facet_normal(vertex[static_cast<size_t>((k + 2) % 3)]),
                        endpoint_limit)) {
        return true;
      }
    }
    return false;
  };
}

SurfaceError triangle_surface_error(const ParametricSurface& surface,
                                    const RestrictedTriangleGeometry& triangle, int sample_order) {
  check_sample_order(sample_order);
  const int n = sample_order;
  SurfaceError error;
  double weighted = 0.0;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) {
      const int k = n - i - j;
      // Composite vertex rule: a point is in 1 (corner), 3 (edge) or 6 (interior) sub-triangles
      const int zeros = (i == 0) + (j == 0) + (k == 0);
      if (zeros == 2) {
        continue;  // a corner: eps = 0 there (the vertices lie on the surface)
      }
      const double weight = zeros == 1 ? 3.0 : 6.0;
      const double a = static_cast<double>(i) / n;
      const double b = static_cast<double>(j) / n;
      const double c = static_cast<double>(k) / n;
      const Eigen::Vector2d uv = a * triangle.uv[0] + b * triangle.uv[1] + c * triangle.uv[2];
      const Eigen::Vector3d linear =
          a * triangle.points[0] + b * triangle.points[1] + c * triangle.points[2];
      // Goldenstein et al. 2005, eq. 5: eps(u, v) = |p(u, v) - P_Poly(u, v)|
      const double eps = (surface.point(uv.x(), uv.y()) - linear).norm();
      error.max = std::max(error.max, eps);
      weighted += weight * eps;
    }
  }
  error.mean = weighted / (3.0 * n * n);  // Goldenstein et al. 2005, eq. 6 divided by the area
  return error;
}

RefinementTest surface_error_criterion(const ParametricSurface& surface, double max_error,
                                       double mean_error, int sample_order) {
  if (!(max_error > 0.0)) {
    throw make_error("surface error criterion: max_error ", max_error, " is not positive");
  }
  if (!(mean_error > 0.0)) {
    throw make_error("surface error criterion: mean_error ", mean_error, " is not positive");
  }
  check_sample_order(sample_order);
  return
      [surface, max_error, mean_error, sample_order](const RestrictedTriangleGeometry& triangle) {
        const SurfaceError error = triangle_surface_error(surface, triangle, sample_order);
        return error.max > max_error || error.mean > mean_error;
      };
}

SurfaceError mesh_surface_error(const RestrictedMesh& mesh, int sample_order) {
  check_sample_order(sample_order);
  SurfaceError total;
  double area = 0.0;
  double integral = 0.0;
  for (const int t : mesh.triangles()) {
    const RestrictedTriangleGeometry g = mesh.geometry(t);
    const SurfaceError error = triangle_surface_error(mesh.surface(), g, sample_order);
    const Eigen::Vector2d e1 = g.uv[1] - g.uv[0];
    const Eigen::Vector2d e2 = g.uv[2] - g.uv[0];
    const double a = 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
    total.max = std::max(total.max, error.max);
    integral += a * error.mean;
    area += a;
  }
  total.mean = area > 0.0 ? integral / area : 0.0;
  return total;
}

UniformTessellationChoice coarsest_uniform_tessellation(const ParametricSurface& surface,
                                                        int base_cells_u, int base_cells_v,
                                                        double max_error, int sample_order) {
  if (!(max_error > 0.0)) {
    throw make_error("uniform tessellation: max_error ", max_error, " is not positive");
  }
  check_sample_order(sample_order);
  const int largest_scale =
      RestrictedMesh::kMaxBaseCells / std::max({base_cells_u, base_cells_v, 1});
  auto evaluate = [&](int scale) {
    const RestrictedMesh mesh(surface, scale * base_cells_u, scale * base_cells_v);
    UniformTessellationChoice choice;
    choice.cells_u = scale * base_cells_u;
    choice.cells_v = scale * base_cells_v;
    choice.vertices = mesh.to_triangle_mesh().vertex_count();
    choice.error = mesh_surface_error(mesh, sample_order);
    return choice;
  };
  int high = 1;
  UniformTessellationChoice best = evaluate(high);
  while (best.error.max > max_error) {
    if (high == largest_scale) {
      throw make_error("uniform tessellation: error ", best.error.max, " above max_error ",
                       max_error, " at ", best.cells_u, " x ", best.cells_v, " cells");
    }
    high = std::min(2 * high, largest_scale);
    best = evaluate(high);
  }
  int low = high / 2;  // fails the bound (or 0)
  while (high - low > 1) {
    const int middle = (low + high) / 2;
    const UniformTessellationChoice trial = evaluate(middle);
    if (trial.error.max <= max_error) {
      high = middle;
      best = trial;
    } else {
      low = middle;
    }
  }
  return best;
}

RestrictedMesh refine_to_surface_error_from_best_base(const ParametricSurface& surface,
                                                      double max_error, int base_cells_u,
                                                      int base_cells_v, int max_level,
                                                      int sample_order) {
  constexpr double kSelectionCoarsening = 16.0;  // four levels up (see the header)
  const RefinementTest final_test = surface_error_criterion(
      surface, max_error, std::numeric_limits<double>::infinity(), sample_order);
  const RefinementTest selection_test =
      surface_error_criterion(surface, kSelectionCoarsening * max_error,
                              std::numeric_limits<double>::infinity(), sample_order);
  const ParameterDomain& domain = surface.domain();
  auto cells = [](int base, double factor, bool periodic) {
    const int count = static_cast<int>(std::lround(base * factor));
    return std::clamp(count, periodic ? 3 : 1, RestrictedMesh::kMaxBaseCells);
  };
  // The given base first (validated by RestrictedMesh, with its messages)
  std::pair<int, int> best_base{base_cells_u, base_cells_v};
  int best_vertices = 0;
  std::vector<std::pair<int, int>> tried;
  for (int k = 0; k <= 3; ++k) {
    for (int l = -2; l <= 2; ++l) {
      const double scale = std::exp2(k / 4.0);
      const std::pair<int, int> base =
          tried.empty() ? best_base
                        : std::pair<int, int>{
                              cells(base_cells_u, scale, domain.periodic_u),
                              cells(base_cells_v, scale * std::exp2(l / 4.0), domain.periodic_v)};
      if (std::find(tried.begin(), tried.end(), base) != tried.end()) {
        continue;
      }
      tried.push_back(base);
      RestrictedMesh candidate(surface, base.first, base.second);
      candidate.refine(selection_test, max_level);
      const int vertices = candidate.to_triangle_mesh().vertex_count();
      if (tried.size() == 1 || vertices < best_vertices) {
        best_base = base;
        best_vertices = vertices;
      }
    }
  }
  RestrictedMesh best(surface, best_base.first, best_base.second);
  best.refine(final_test, max_level);
  return best;
}

TriangleMesh tessellate_adaptive(const ParametricSurface& surface,
                                 const RefinementTest& needs_refinement, int base_cells_u,
                                 int base_cells_v, int max_level, std::string name) {
  RestrictedMesh mesh(surface, base_cells_u, base_cells_v);
  mesh.refine(needs_refinement, max_level);
  return mesh.to_triangle_mesh(std::move(name));
}

}  // namespace dnurbs
