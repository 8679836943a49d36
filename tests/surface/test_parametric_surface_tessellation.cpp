#include "dnurbs/surface/parametric_surface_tessellation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "dnurbs/surface/parametric_surface.h"
#include "dnurbs/surface/tessellation.h"

namespace dnurbs {
namespace {

constexpr double kPi = std::numbers::pi;

// Every undirected edge in exactly two triangles and every directed edge in one: closed, no
// cracks, consistently wound.
void expect_closed(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> undirected;
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < mesh.triangle_count(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles(f, k);
      const int b = mesh.triangles(f, (k + 1) % 3);
      ASSERT_NE(a, b) << "degenerate triangle " << f;
      ++directed[{a, b}];
      ++undirected[{std::min(a, b), std::max(a, b)}];
    }
  }
  for (const auto& [edge, count] : undirected) {
    EXPECT_EQ(count, 2) << "edge " << edge.first << "-" << edge.second;
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "directed edge " << edge.first << "-" << edge.second;
  }
  // Euler characteristic V - E + F: 2 for a sphere, 0 for a torus (checked by the callers)
}

int euler_characteristic(const TriangleMesh& mesh) {
  // On a closed mesh E = 3 F / 2
  return mesh.vertex_count() - 3 * mesh.triangle_count() / 2 + mesh.triangle_count();
}

// Geometric normals point the same way as the vertex normals
void expect_outward_winding(const TriangleMesh& mesh) {
  for (int f = 0; f < mesh.triangle_count(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0)).transpose();
    const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, 1)).transpose();
    const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(f, 2)).transpose();
    const Eigen::Vector3d face = (b - a).cross(c - a);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      mean += mesh.normals.row(mesh.triangles(f, k)).transpose();
    }
    EXPECT_GT(face.dot(mean), 0.0) << "triangle " << f;
  }
}

SuperquadricShapeParameters squarish_superquadric() {
  SuperquadricShapeParameters q;
  // a, a1, a2, a3, e1, e2, t1, t2, b1, b2, b3, tau, sx, sy
  q << 1.0, 1.0, 0.8, 1.2, 0.6, 0.7, 0.2, 0.1, 0.0, 0.0, 0.0, 0.3, 0.0, 0.0;
  return q;
}

TEST(ParametricTessellation, SuperquadricHasOneVertexPerPoleAndIsClosed) {
  const DeformableSuperquadricShape shape(squarish_superquadric());
  const ParametricSurface surface = parametric_surface(shape);
  const int nu = 8;
  const int nv = 12;
  const TriangleMesh mesh = tessellate_surface(surface, nu, nv, "superquadric");
  // (nu - 1) latitude rings of nv vertices and one vertex per pole
  EXPECT_EQ(mesh.vertex_count(), (nu - 1) * nv + 2);
  EXPECT_EQ(mesh.triangle_count(), 2 * nu * nv - 2 * nv);
  for (const double pole : {-kPi / 2.0, kPi / 2.0}) {
    const Eigen::Vector3d x = shape.point(pole, 0.0);
    int at_pole = 0;
    for (int k = 0; k < mesh.vertex_count(); ++k) {
      // the pole's points for different v agree exactly (cos(+-pi/2) is below kSignedPowerZero)
      at_pole += (mesh.vertices.row(k).transpose() - x).norm() == 0.0;
    }
    EXPECT_EQ(at_pole, 1) << "pole u = " << pole;
  }
  expect_closed(mesh);
  EXPECT_EQ(euler_characteristic(mesh), 2);
  expect_outward_winding(mesh);
  // Normals are the shape's own outward unit normals, pole limits included
  for (int k = 0; k < mesh.vertex_count(); ++k) {
    const Eigen::Vector3d expected = shape.unit_normal(mesh.uv(k, 0), mesh.uv(k, 1));
    EXPECT_LT((mesh.normals.row(k).transpose() - expected).norm(), 1e-15) << "vertex " << k;
    EXPECT_LT((mesh.vertices.row(k).transpose() - shape.point(mesh.uv(k, 0), mesh.uv(k, 1))).norm(),
              1e-15);
  }
}

TEST(ParametricTessellation, NurbsSphereClosuresAreDetectedAndTheMeshIsClosed) {
  const NurbsSurface sphere_surface = sphere(2.0);
  const ParameterDomain domain = nurbs_parameter_domain(sphere_surface);
  EXPECT_FALSE(domain.periodic_u);
  EXPECT_TRUE(domain.periodic_v);  // the clamped circle's seam
  EXPECT_TRUE(domain.pole_u_min);
  EXPECT_TRUE(domain.pole_u_max);
  const TriangleMesh mesh = tessellate_surface(parametric_surface(sphere_surface), 6, 10);
  EXPECT_EQ(mesh.vertex_count(), 5 * 10 + 2);
  expect_closed(mesh);
  EXPECT_EQ(euler_characteristic(mesh), 2);
  expect_outward_winding(mesh);
  for (int k = 0; k < mesh.vertex_count(); ++k) {
    // rational evaluation rounds to a few ulps of the radius
    EXPECT_NEAR(mesh.vertices.row(k).norm(), 2.0, 1e-14);
    // NurbsSurface::unit_normal is S_u x S_v, which points inwards on this sphere
    EXPECT_NEAR(mesh.normals.row(k).dot(mesh.vertices.row(k)) / 2.0, -1.0, 1e-12);
  }
}

TEST(ParametricTessellation, PeriodicTorusIsClosedWithoutSeamVertices) {
  const TriangleMesh mesh = tessellate_surface(parametric_surface(periodic_torus(3.0, 1.0)), 16, 8);
  EXPECT_EQ(mesh.vertex_count(), 16 * 8);
  expect_closed(mesh);
  EXPECT_EQ(euler_characteristic(mesh), 0);
}

TEST(ParametricTessellation, OpenNurbsPatchMatchesTheNurbsTessellation) {
  const KnotVector knots_u = KnotVector::clamped_uniform(3, 5, 0.0, 2.0);
  const KnotVector knots_v = KnotVector::clamped_uniform(2, 4, 1.0, 3.0);
  Eigen::MatrixX3d points(20, 3);
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 4; ++j) {
      points.row(i * 4 + j) << i, j, 0.3 * std::sin(i + 2.0 * j);
    }
  }
  const NurbsSurface patch(knots_u, knots_v, points);
  const TriangleMesh expected = tessellate_surface(patch, 7, 5);
  const TriangleMesh mesh = tessellate_surface(parametric_surface(patch), 7, 5);
  ASSERT_EQ(mesh.vertex_count(), expected.vertex_count());
  ASSERT_EQ(mesh.triangle_count(), expected.triangle_count());
  // Parameters u_min + (u_max - u_min) i / n may differ from the NURBS tessellation's
  // (u_max - u_min) i / n by one rounding
  EXPECT_LT((mesh.uv - expected.uv).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((mesh.vertices - expected.vertices).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((mesh.normals - expected.normals).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_EQ(mesh.triangles, expected.triangles);
}

TEST(ParametricTessellation, DifferenceNormalsMatchTheSphereIncludingPoles) {
  // A sphere of radius 1.5 as a plain function, without a normal function
  ParameterDomain domain = superquadric_parameter_domain();
  const ParametricSurface surface(
      domain,
      [](double u, double v) {
        return Eigen::Vector3d(1.5 * std::cos(u) * std::cos(v), 1.5 * std::cos(u) * std::sin(v),
                               1.5 * std::sin(u));
      },
      {}, NormalOrientation::kSvCrossSu);
  const TriangleMesh mesh = tessellate_surface(surface, 9, 12);
  expect_closed(mesh);
  expect_outward_winding(mesh);
  for (int k = 0; k < mesh.vertex_count(); ++k) {
    const Eigen::Vector3d exact = mesh.vertices.row(k).normalized().transpose();
    // Central differences with step 1e-5 of the extent: truncation ~ h^2 / 6 ~ 1e-10; at the
    // poles the mean over a ring 1e-4 of the extent off the pole: exact by symmetry up to
    // rounding of the tilted normals (~1e-11)
    EXPECT_LT((mesh.normals.row(k).transpose() - exact).norm(), 1e-9) << "vertex " << k;
  }
}

// The unit sphere with u the longitude (periodic) and v the latitude (poles at v_min, v_max)
ParametricSurface sphere_with_poles_in_v() {
  ParameterDomain domain;
  domain.u_min = 0.0;
  domain.u_max = 2.0 * kPi;
  domain.v_min = -kPi / 2.0;
  domain.v_max = kPi / 2.0;
  domain.periodic_u = true;
  domain.pole_v_min = true;
  domain.pole_v_max = true;
  return ParametricSurface(domain, [](double u, double v) {
    return Eigen::Vector3d(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
  });
}

TEST(ParametricTessellation, PolesAlongVAreSingleVerticesToo) {
  const ParametricSurface surface = sphere_with_poles_in_v();
  const TriangleMesh mesh = tessellate_surface(surface, 12, 7);
  EXPECT_EQ(mesh.vertex_count(), 12 * 6 + 2);
  expect_closed(mesh);
  EXPECT_EQ(euler_characteristic(mesh), 2);
  expect_outward_winding(mesh);
  for (int k = 0; k < mesh.vertex_count(); ++k) {
    // Difference normals (and the ring mean at the poles): S_u x S_v is outward here; errors as
    // in DifferenceNormalsMatchTheSphereIncludingPoles
    EXPECT_LT((mesh.normals.row(k) - mesh.vertices.row(k)).norm(), 1e-9) << "vertex " << k;
  }
}

TEST(ParametricTessellation, InvalidInputNamesTheValue) {
  ParameterDomain domain;
  domain.u_max = -1.0;
  EXPECT_THROW(domain.validate(), Error);
  ParameterDomain both;
  both.periodic_u = true;
  both.pole_u_min = true;
  EXPECT_THROW(both.validate(), Error);
  EXPECT_THROW(ParametricSurface(ParameterDomain{}, SurfaceFunction{}), Error);
  const ParametricSurface surface = parametric_surface(periodic_torus(3.0, 1.0));
  try {
    tessellate_surface(surface, 2, 8);
    FAIL() << "expected Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("2 by 8"), std::string::npos) << error.what();
  }
  // A surface whose tangents vanish off its poles has no difference normal there
  const ParametricSurface flat(ParameterDomain{},
                               [](double, double) { return Eigen::Vector3d(1.0, 2.0, 3.0); });
  EXPECT_THROW(flat.unit_normal(0.5, 0.5), Error);
}

}  // namespace
}  // namespace dnurbs
