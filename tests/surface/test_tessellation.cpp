#include "dnurbs/surface/tessellation.h"

#include <cmath>
#include <map>
#include <utility>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/primitive_shapes.h"

namespace dnurbs {
namespace {

// A non-rational bicubic patch over [0, 2] x [1, 3] with 5 x 4 control points (clamped).
NurbsSurface bicubic_patch() {
  const KnotVector knots_u = KnotVector::clamped_uniform(3, 5, 0.0, 2.0);
  const KnotVector knots_v = KnotVector::clamped_uniform(2, 4, 1.0, 3.0);
  Eigen::MatrixX3d points(20, 3);
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 4; ++j) {
      points.row(i * 4 + j) << i, j, 0.3 * std::sin(i + 2.0 * j);
    }
  }
  return NurbsSurface(knots_u, knots_v, points);
}

// Counts of each undirected edge, and of each directed edge
struct EdgeCounts {
  std::map<std::pair<int, int>, int> undirected;
  std::map<std::pair<int, int>, int> directed;
};

EdgeCounts count_edges(const TriangleMesh& mesh) {
  EdgeCounts counts;
  for (int f = 0; f < mesh.triangle_count(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles(f, k);
      const int b = mesh.triangles(f, (k + 1) % 3);
      ++counts.directed[{a, b}];
      ++counts.undirected[{std::min(a, b), std::max(a, b)}];
    }
  }
  return counts;
}

TEST(SurfaceTessellation, OpenSurfaceHasGridCountsAndSpansTheDomain) {
  const NurbsSurface patch = bicubic_patch();
  const TriangleMesh mesh = tessellate_surface(patch, 7, 5, "patch");
  EXPECT_EQ(mesh.name, "patch");
  EXPECT_EQ(mesh.vertex_count(), 8 * 6);
  EXPECT_EQ(mesh.triangle_count(), 2 * 7 * 5);
  EXPECT_EQ(mesh.normals.rows(), 48);
  EXPECT_EQ(mesh.uv.rows(), 48);
  // uv: vertex (i, j) is row i * 6 + j on the uniform grid of [0, 2] x [1, 3]
  for (int i = 0; i <= 7; ++i) {
    for (int j = 0; j <= 5; ++j) {
      EXPECT_NEAR(mesh.uv(i * 6 + j, 0), 2.0 * i / 7, 1e-15);
      EXPECT_NEAR(mesh.uv(i * 6 + j, 1), 1.0 + 2.0 * j / 5, 1e-15);
    }
  }
  // A clamped surface interpolates its corner control points (error: rounding of the basis)
  EXPECT_LT((mesh.vertices.row(0) - patch.control_points().row(0)).norm(), 1e-14);
  EXPECT_LT((mesh.vertices.row(47) - patch.control_points().row(19)).norm(), 1e-14);
  EXPECT_LT((mesh.vertices.row(5) - patch.control_points().row(3)).norm(), 1e-14);
  // Every vertex is the surface point of its uv, every normal is unit_normal there
  for (int r = 0; r < mesh.vertex_count(); ++r) {
    const double u = mesh.uv(r, 0);
    const double v = mesh.uv(r, 1);
    EXPECT_LT((mesh.vertices.row(r).transpose() - patch.point(u, v)).norm(), 1e-14);
    EXPECT_NEAR(mesh.normals.row(r).norm(), 1.0, 1e-14);
    EXPECT_LT((mesh.normals.row(r).transpose() - patch.unit_normal(u, v)).norm(), 1e-14);
  }
  // Open grid: 2 (7 + 5) boundary edges used once, every other edge twice
  const EdgeCounts edges = count_edges(mesh);
  int boundary = 0;
  for (const auto& [edge, count] : edges.undirected) {
    EXPECT_LE(count, 2);
    boundary += count == 1 ? 1 : 0;
  }
  EXPECT_EQ(boundary, 2 * (7 + 5));
}

TEST(SurfaceTessellation, TrianglesFaceAlongTheSurfaceNormal) {
  const NurbsSurface patch = bicubic_patch();
  const TriangleMesh mesh = tessellate_surface(patch, 9, 9);
  for (int f = 0; f < mesh.triangle_count(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0));
    const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(f, 2));
    const Eigen::Vector3d face = (b - a).cross(c - a);
    EXPECT_GT(face.dot(mesh.normals.row(mesh.triangles(f, 0))), 0.0) << "triangle " << f;
  }
}

TEST(PeriodicTorusTessellation, IsWatertightWithoutSeamDuplicates) {
  const TriangleMesh mesh = tessellate_surface(periodic_torus(2.0, 0.5), 12, 8);
  EXPECT_EQ(mesh.vertex_count(), 12 * 8);
  EXPECT_EQ(mesh.triangle_count(), 2 * 12 * 8);
  const EdgeCounts edges = count_edges(mesh);
  for (const auto& [edge, count] : edges.undirected) {
    EXPECT_EQ(count, 2) << "edge " << edge.first << "-" << edge.second;
  }
  for (const auto& [edge, count] : edges.directed) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << "->" << edge.second << " (orientation)";
  }
  // Euler characteristic of a torus: V - E + F = 0
  EXPECT_EQ(mesh.vertex_count() - static_cast<int>(edges.undirected.size()) + mesh.triangle_count(),
            0);
}

TEST(PeriodicTorusTessellation, VerticesLieOnTheExactTorusWithOutwardNormals) {
  constexpr double kMajor = 2.0;
  constexpr double kMinor = 0.5;
  const NurbsSurface torus = periodic_torus(kMajor, kMinor);
  const TriangleMesh mesh = tessellate_surface(torus, 24, 16);
  double worst_distance = 0.0;
  double worst_normal = 0.0;
  for (int r = 0; r < mesh.vertex_count(); ++r) {
    const Eigen::Vector3d p = mesh.vertices.row(r);
    // Nearest point of the tube's centre circle, and the exact outward normal
    const Eigen::Vector3d centre = kMajor * Eigen::Vector3d(p.x(), p.y(), 0.0).normalized();
    const Eigen::Vector3d exact_normal = (p - centre).normalized();
    worst_distance = std::max(worst_distance, std::abs((p - centre).norm() - kMinor));
    worst_normal = std::max(worst_normal, (mesh.normals.row(r).transpose() - exact_normal).norm());
    EXPECT_NEAR(mesh.normals.row(r).norm(), 1.0, 1e-14);
  }
  // The rational torus is exact; what remains is rounding in evaluation (a few ulps of 2.5)
  EXPECT_LT(worst_distance, 1e-14);
  EXPECT_LT(worst_normal, 1e-13);
}

TEST(SurfaceTessellation, RejectsTooLowResolutions) {
  EXPECT_THROW(tessellate_surface(bicubic_patch(), 0, 4), Error);
  EXPECT_THROW(tessellate_surface(bicubic_patch(), 4, -1), Error);
  EXPECT_THROW(tessellate_surface(periodic_torus(2.0, 0.5), 2, 8), Error);
  EXPECT_NO_THROW(tessellate_surface(bicubic_patch(), 1, 1));
}

TEST(CurveSampling, ClampedCircleSamplesCloseAndHaveRadiusOne) {
  const Eigen::MatrixX3d points = sample_curve(full_circle(1.0), 16);
  ASSERT_EQ(points.rows(), 17);
  for (int k = 0; k < points.rows(); ++k) {
    EXPECT_NEAR(points.row(k).norm(), 1.0, 1e-15);  // exact rational circle, rounding only
  }
  EXPECT_LT((points.row(0) - points.row(16)).norm(), 1e-15);
  // The periodic circle's samples do not repeat the first point
  EXPECT_EQ(sample_curve(periodic_circle(1.0), 16).rows(), 16);
}

TEST(CurveTube, PeriodicCircleGivesAClosedTubeAtTheRadius) {
  constexpr double kRadius = 0.1;
  const TriangleMesh tube = tessellate_curve_tube(periodic_circle(2.0), 32, kRadius, 10);
  EXPECT_EQ(tube.vertex_count(), 32 * 10);
  EXPECT_EQ(tube.triangle_count(), 2 * 32 * 10);
  for (int r = 0; r < tube.vertex_count(); ++r) {
    const Eigen::Vector3d p = tube.vertices.row(r);
    const Eigen::Vector3d centre = 2.0 * Eigen::Vector3d(p.x(), p.y(), 0.0).normalized();
    // Each ring lies in the normal plane at the sample, so its distance to the circle is exact
    EXPECT_NEAR((p - centre).norm(), kRadius, 1e-14);
    EXPECT_GT(tube.normals.row(r).dot((p - centre).normalized()), 1.0 - 1e-12);
  }
  const EdgeCounts edges = count_edges(tube);
  for (const auto& [edge, count] : edges.directed) {
    EXPECT_EQ(count, 1);
  }
  for (const auto& [edge, count] : edges.undirected) {
    EXPECT_EQ(count, 2);
  }
  // Triangles face outwards
  for (int f = 0; f < tube.triangle_count(); ++f) {
    const Eigen::Vector3d a = tube.vertices.row(tube.triangles(f, 0));
    const Eigen::Vector3d b = tube.vertices.row(tube.triangles(f, 1));
    const Eigen::Vector3d c = tube.vertices.row(tube.triangles(f, 2));
    EXPECT_GT((b - a).cross(c - a).dot(tube.normals.row(tube.triangles(f, 0))), 0.0);
  }
}

TEST(CurveTube, OpenCurveTubeHasNoClosingBandAndRejectsBadRadius) {
  const TriangleMesh tube = tessellate_curve_tube(full_circle(1.0), 8, 0.05, 6);
  EXPECT_EQ(tube.vertex_count(), 9 * 6);
  EXPECT_EQ(tube.triangle_count(), 2 * 8 * 6);
  EXPECT_THROW(tessellate_curve_tube(full_circle(1.0), 8, 0.0), Error);
  EXPECT_THROW(tessellate_curve_tube(full_circle(1.0), 8, 0.1, 2), Error);
}

}  // namespace
}  // namespace dnurbs
