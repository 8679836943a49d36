// Tests of dynamics/triangular/triangular_tessellation.h: uniform meshes (counts, shared
// vertices, orientation, exactness on a flat surface, h^2 chord error) and adaptive meshes
// (conforming, within the error bound, fewer triangles than uniform at the same error).

#include "dnurbs/dynamics/triangular/triangular_tessellation.h"

#include <cmath>
#include <iostream>
#include <map>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "dnurbs/core/error.h"
#include "triangular_model_helpers.h"

namespace dnurbs {
namespace {

// Number of triangles on each undirected edge of the mesh: 1 on the boundary, 2 inside for a
// conforming mesh; also checks that no edge is used twice in one direction.
std::map<std::pair<int, int>, int> edge_uses(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> uses;
  std::map<std::pair<int, int>, int> directed;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.triangles(t, c);
      const int b = mesh.triangles(t, (c + 1) % 3);
      ++uses[{std::min(a, b), std::max(a, b)}];
      const int times = ++directed[std::make_pair(a, b)];
      EXPECT_EQ(times, 1) << "edge " << a << " " << b;
    }
  }
  return uses;
}

// A bump: the flat net lifted by a narrow Gaussian at (0.3, 0.35).
TriangularNurbsSurface bump_surface() {
  const auto basis = test::triangular_basis(test::unit_square(4), 3);
  const TriangularNurbsSurface flat = flat_triangular_surface(basis);
  Eigen::MatrixX3d points = flat.control_points();
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector2d p = points.row(i).head<2>().transpose();
    points(i, 2) = 0.3 * std::exp(-(p - Eigen::Vector2d(0.3, 0.35)).squaredNorm() / 0.01);
  }
  return {basis, points};
}

TEST(TriangularTessellation, UniformMeshSharesVerticesAndIsExactOnAFlatSurface) {
  const Triangulation domain = l_shape_triangulation(1);
  const auto basis = test::triangular_basis(domain, 2);
  const TriangularNurbsSurface flat = flat_triangular_surface(basis);
  for (const int s : {1, 3, 4}) {
    const TriangleMesh mesh = tessellate_triangular_surface(flat, s);
    const int edges =
        (3 * domain.triangle_count() + static_cast<int>(domain.boundary_edges().rows())) / 2;
    EXPECT_EQ(mesh.triangle_count(), domain.triangle_count() * s * s);
    // Vertices: domain vertices, s - 1 per domain edge, (s - 1)(s - 2)/2 inside each triangle.
    EXPECT_EQ(mesh.vertex_count(), domain.vertex_count() + edges * (s - 1) +
                                       domain.triangle_count() * (s - 1) * (s - 2) / 2);
    int boundary = 0;
    for (const auto& [edge, count] : edge_uses(mesh)) {
      EXPECT_LE(count, 2);
      boundary += count == 1 ? 1 : 0;
    }
    EXPECT_EQ(boundary, static_cast<int>(domain.boundary_edges().rows()) * s);
    // The flat surface x = (u, v, 0): vertices at their parameters, normals +z, triangles
    // counter-clockwise seen from +z, and no chord error.
    for (int v = 0; v < mesh.vertex_count(); ++v) {
      EXPECT_LT((mesh.vertices.row(v).head<2>() - mesh.uv.row(v)).norm(), 1e-14);
      EXPECT_LT((mesh.normals.row(v) - Eigen::RowVector3d::UnitZ()).norm(), 1e-12);
    }
    for (int t = 0; t < mesh.triangle_count(); ++t) {
      const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(t, 0));
      const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(t, 1));
      const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(t, 2));
      EXPECT_GT((b - a).cross(c - a).z(), 0.0);
    }
    EXPECT_LT(triangular_chord_error(flat, mesh), 1e-14);
  }
  EXPECT_THROW(tessellate_triangular_surface(flat, 0), Error);
}

TEST(TriangularTessellation, UniformChordErrorFallsLikeHSquaredOnASmoothSurface) {
  // A gentle surface (the curved test net on 2 x 2 cells, degree 2): the interpolation error of
  // flat triangles is O(h^2) once h is below the knot-cloud scale.
  const TriangularNurbsSurface surface =
      test::curved_triangular_surface(test::triangular_basis(test::unit_square(2), 2), false);
  const double coarse = triangular_chord_error(surface, tessellate_triangular_surface(surface, 8));
  const double fine = triangular_chord_error(surface, tessellate_triangular_surface(surface, 16));
  std::cout << "uniform chord error 8 -> 16 subdivisions: " << coarse << " -> " << fine << "\n";
  EXPECT_GT(coarse / fine, 3.0);  // 4 for h^2; the knot segments' curvature spikes cost some
}

TEST(TriangularTessellation, AdaptiveMeshIsConformingWithinTheErrorAndSmallerThanUniform) {
  const TriangularNurbsSurface surface = bump_surface();
  const double tolerance = 3e-3;
  const TriangleMesh adaptive = tessellate_triangular_surface_adaptive(surface, tolerance);
  for (const auto& [edge, count] : edge_uses(adaptive)) {
    EXPECT_LE(count, 2);  // no T-junctions: every edge has at most two triangles
  }
  // Boundary edges of the mesh lie on the domain boundary (the outer square).
  for (const auto& [edge, count] : edge_uses(adaptive)) {
    if (count == 1) {
      const Eigen::Vector2d a = adaptive.uv.row(edge.first);
      const Eigen::Vector2d b = adaptive.uv.row(edge.second);
      const Eigen::Vector2d mid = 0.5 * (a + b);
      EXPECT_TRUE(std::min({mid.x(), mid.y(), 1.0 - mid.x(), 1.0 - mid.y()}) < 1e-14);
    }
  }
  const double adaptive_error = triangular_chord_error(surface, adaptive, 4);
  // The criterion samples 4 points per triangle; the 4-interval lattice (15 points) finds a little
  // more.
  EXPECT_LT(adaptive_error, 1.5 * tolerance);
  int s = 1;
  double uniform_error = 1.0;
  while (uniform_error > adaptive_error && s < 64) {
    s *= 2;
    uniform_error = triangular_chord_error(surface, tessellate_triangular_surface(surface, s), 4);
  }
  const int uniform_triangles = surface.basis().triangulation().triangle_count() * s * s;
  std::cout << "adaptive: " << adaptive.triangle_count() << " triangles at chord error "
            << adaptive_error << "; uniform needs " << uniform_triangles << " (s = " << s
            << ", error " << uniform_error << ")\n";
  EXPECT_LT(3 * adaptive.triangle_count(), uniform_triangles);
  EXPECT_THROW(tessellate_triangular_surface_adaptive(surface, 0.0), Error);
  EXPECT_THROW(tessellate_triangular_surface_adaptive(surface, 1e-3, 0), Error);
}

TEST(TriangularTessellation, ModelTessellationFollowsTheCoordinates) {
  const auto basis = test::triangular_basis(test::unit_square(1), 2);
  const TriangularDNurbsSurface model(flat_triangular_surface(basis));
  Eigen::VectorXd q = model.initial_coordinates();
  for (int i = 0; i < model.control_point_count(); ++i) {
    q[3 * i + 2] += 0.25;  // lift the whole surface
  }
  const TriangleMesh mesh = tessellate_triangular_model(model, q, 2);
  EXPECT_EQ(mesh.triangle_count(), 8);
  EXPECT_LT((mesh.vertices.col(2).array() - 0.25).abs().maxCoeff(), 1e-14);
  const TriangleMesh adaptive = tessellate_triangular_model(model, q, 2, 1e-3);
  EXPECT_EQ(adaptive.triangle_count(), 2);  // flat: nothing to refine
}

}  // namespace
}  // namespace dnurbs
