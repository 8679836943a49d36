#include "dnurbs/surface/restricted_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/surface/adaptive_tessellation.h"
#include "dnurbs/surface/compliant_triangulation.h"
#include "dnurbs/surface/parametric_surface.h"
#include "tests/surface/random_triangulation.h"

namespace dnurbs {
namespace {

using Segment = std::pair<Eigen::Vector2d, Eigen::Vector2d>;

// A saddle over the unit square with a Gaussian ridge along the diagonal u = v (height 0.1,
// width ~0.1): curved everywhere, most along the ridge.
ParametricSurface ridged_saddle() {
  return ParametricSurface(ParameterDomain{}, [](double u, double v) {
    const double d = (u - v) / std::sqrt(2.0);
    return Eigen::Vector3d(u, v, 0.2 * (u - 0.5) * (v - 0.5) + 0.1 * std::exp(-d * d / 0.01));
  });
}

// The edges of a triangulation used by one triangle.
std::vector<Segment> boundary_segments(const BlockTriangulation& base) {
  std::map<std::pair<int, int>, int> count;
  for (int t = 0; t < base.triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = base.triangles(t, k);
      const int b = base.triangles(t, (k + 1) % 3);
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<Segment> segments;
  for (const auto& [edge, users] : count) {
    if (users == 1) {
      segments.emplace_back(base.uv.row(edge.first).transpose(),
                            base.uv.row(edge.second).transpose());
    }
  }
  return segments;
}

// Edges shared by more than two triangles, and edges used once that are not on the base's
// boundary (a T-junction leaves such an edge inside the region).
struct Conformity {
  int over_shared = 0;
  int inner_boundary = 0;
};

Conformity conformity(const RestrictedMesh& mesh, const std::vector<Segment>& base_boundary) {
  std::map<std::pair<int, int>, int> count;
  for (const int t : mesh.triangles()) {
    const std::array<int, 3>& v = mesh.triangle_vertices(t);
    for (int k = 0; k < 3; ++k) {
      const int a = v[static_cast<size_t>(k)];
      const int b = v[static_cast<size_t>((k + 1) % 3)];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  }
  Conformity result;
  for (const auto& [edge, users] : count) {
    result.over_shared += users > 2 ? 1 : 0;
    if (users == 1) {
      const Eigen::Vector2d midpoint =
          0.5 * (mesh.parameter(edge.first) + mesh.parameter(edge.second));
      const bool on_boundary =
          std::any_of(base_boundary.begin(), base_boundary.end(), [&](const Segment& s) {
            const Eigen::Vector2d along = s.second - s.first;
            const Eigen::Vector2d offset = midpoint - s.first;
            // Midpoints of midpoints of a base edge: on it to rounding of the (u, v) (1e-15)
            const double cross = along.x() * offset.y() - along.y() * offset.x();
            const double t = along.dot(offset) / along.squaredNorm();
            return std::abs(cross) < 1e-14 && t > 0.0 && t < 1.0;
          });
      result.inner_boundary += on_boundary ? 0 : 1;
    }
  }
  return result;
}

void expect_conforming(const RestrictedMesh& mesh, const std::vector<Segment>& base_boundary) {
  const Conformity report = conformity(mesh, base_boundary);
  EXPECT_EQ(report.over_shared, 0);
  EXPECT_EQ(report.inner_boundary, 0);
  EXPECT_LE(mesh.max_neighbor_level_difference(), 1);
}

BlockTriangulation random_compliant_base(int cells, std::uint32_t seed, int* added = nullptr) {
  const testing::Triangulation input =
      testing::random_triangulation(cells, 4 * cells * cells, cells, seed);
  const CompliantTriangulation compliant = make_compliant(input.uv, input.triangles);
  if (added != nullptr) {
    *added = compliant.added_vertices;
  }
  return compliant.mesh;
}

// The (u, v) area of the current triangles.
double parameter_area(const RestrictedMesh& mesh) {
  double area = 0.0;
  for (const int t : mesh.triangles()) {
    const RestrictedTriangleGeometry g = mesh.geometry(t);
    area += testing::signed_area(g.uv[0], g.uv[1], g.uv[2]);
  }
  return area;
}

bool never(const RestrictedTriangleGeometry& /*triangle*/) {
  return false;
}

TEST(RestrictedMesh, TriangulatedBaseStaysConformingThroughRandomSplitsAndWelds) {
  for (std::uint32_t seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE(seed);
    const BlockTriangulation base = random_compliant_base(5, seed);
    const std::vector<Segment> boundary = boundary_segments(base);
    RestrictedMesh mesh(ridged_saddle(), base);
    const auto base_keys = mesh.triangle_keys();
    const double base_area = parameter_area(mesh);
    std::mt19937 random(seed);
    int splits = 0;
    int welds = 0;
    for (int operation = 0; operation < 300; ++operation) {
      const std::vector<int> current = mesh.triangles();
      if (random() % 3 != 0) {
        const int t = current[random() % current.size()];
        if (mesh.level(t) < 12) {
          splits += mesh.split(t);
        }
      } else {
        std::vector<int> weldable;
        for (const int t : current) {
          for (const int v : mesh.triangle_vertices(t)) {
            if (mesh.can_weld(v)) {
              weldable.push_back(v);
            }
          }
        }
        if (!weldable.empty()) {
          welds += mesh.weld(weldable[random() % weldable.size()]) ? 1 : 0;
        }
      }
      expect_conforming(mesh, boundary);
      // No triangle inverted or lost: the (u, v) area is the base's (to rounding, 1e-15)
      EXPECT_NEAR(parameter_area(mesh), base_area, 1e-13);
    }
    EXPECT_GT(splits, 100);
    EXPECT_GT(welds, 10);
    // Simplification by a test that never asks for refinement returns the compliant base
    mesh.coarsen(never);
    EXPECT_EQ(mesh.triangle_keys(), base_keys);
    EXPECT_EQ(mesh.triangle_count(), base.triangles.rows());
    EXPECT_EQ(mesh.parameter_vertex_count(), base.uv.rows());
  }
}

TEST(RestrictedMesh, UniformDepthDoublesTheTrianglesPerLevel) {
  const BlockTriangulation base = random_compliant_base(4, 3);
  const std::vector<Segment> boundary = boundary_segments(base);
  for (int depth = 0; depth <= 6; ++depth) {
    RestrictedMesh mesh(ridged_saddle(), base);
    mesh.refine(depth_criterion(depth));
    expect_conforming(mesh, boundary);
    EXPECT_EQ(mesh.triangle_count(), base.triangles.rows() << depth);
    for (const int t : mesh.triangles()) {
      EXPECT_EQ(mesh.level(t), depth);
    }
  }
}

// Refine by `tight`, then simplify by `loose` (which asks for refinement only where `tight`
// does): the mesh refined by `loose` alone.
void expect_simplify_gives_the_looser_refinement(const RestrictedMesh& base,
                                                 const std::vector<Segment>& boundary,
                                                 const RefinementTest& tight,
                                                 const RefinementTest& loose) {
  RestrictedMesh refined = base;
  EXPECT_GT(refined.refine(tight), 0);
  expect_conforming(refined, boundary);
  const auto tight_keys = refined.triangle_keys();
  EXPECT_EQ(refined.coarsen(tight), 0);  // the refining test keeps every split
  EXPECT_EQ(refined.triangle_keys(), tight_keys);
  EXPECT_GT(refined.coarsen(loose), 0);
  expect_conforming(refined, boundary);
  RestrictedMesh reference = base;
  reference.refine(loose);
  EXPECT_EQ(refined.triangle_keys(), reference.triangle_keys());
  std::cout << "[ simplify ] " << tight_keys.size() << " triangles refined, "
            << refined.triangle_count() << " after simplification\n";
}

TEST(RestrictedMesh, RefineThenSimplifyByALooserTestIsTheLooserRefinement) {
  const ParametricSurface surface = ridged_saddle();
  const BlockTriangulation base = random_compliant_base(5, 11);
  const std::vector<Segment> triangulated_boundary = boundary_segments(base);
  const std::vector<Segment> square_boundary = {
      {{0, 0}, {1, 0}}, {{1, 0}, {1, 1}}, {{1, 1}, {0, 1}}, {{0, 1}, {0, 0}}};
  for (const bool triangulated : {true, false}) {
    SCOPED_TRACE(triangulated ? "triangulated base" : "grid base");
    const RestrictedMesh start =
        triangulated ? RestrictedMesh(surface, base) : RestrictedMesh(surface, 3, 3);
    const std::vector<Segment>& boundary = triangulated ? triangulated_boundary : square_boundary;
    expect_simplify_gives_the_looser_refinement(start, boundary,
                                                surface_error_criterion(surface, 2e-4),
                                                surface_error_criterion(surface, 1e-3));
    expect_simplify_gives_the_looser_refinement(start, boundary, depth_criterion(6),
                                                depth_criterion(3));
  }
}

TEST(RestrictedMesh, TriangulatedBaseRejectsBadBases) {
  const ParametricSurface surface = ridged_saddle();
  BlockTriangulation square;
  square.uv.resize(4, 2);
  square.uv << 0, 0, 1, 0, 1, 1, 0, 1;
  square.triangles.resize(2, 3);
  square.triangles << 0, 1, 2, 3, 0, 2;  // the first's refinement edge 1-2 is not the diagonal
  EXPECT_THROW(RestrictedMesh(surface, square), Error);
  square.triangles << 1, 2, 0, 3, 0, 2;
  EXPECT_EQ(RestrictedMesh(surface, square).triangle_count(), 2);
  square.uv(2, 0) = 1.5;  // outside [0, 1] x [0, 1]
  EXPECT_THROW(RestrictedMesh(surface, square), Error);
}

}  // namespace
}  // namespace dnurbs
