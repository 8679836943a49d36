#include "dnurbs/dynamics/core/model_tessellation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "dnurbs/surface/parametric_surface_tessellation.h"

namespace dnurbs {
namespace {

// Every undirected edge in two triangles, every directed edge in one
bool is_closed(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> undirected;
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < mesh.triangle_count(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles(f, k);
      const int b = mesh.triangles(f, (k + 1) % 3);
      ++directed[{a, b}];
      ++undirected[{std::min(a, b), std::max(a, b)}];
    }
  }
  return std::all_of(undirected.begin(), undirected.end(),
                     [](const auto& edge) { return edge.second == 2; }) &&
         std::all_of(directed.begin(), directed.end(),
                     [](const auto& edge) { return edge.second == 1; });
}

TEST(ModelTessellation, DNurbsSphereMeshesLikeItsNurbsSurface) {
  const DNurbsSurface model(sphere(1.5));
  const Eigen::VectorXd q = model.initial_coordinates();
  ModelTessellationSettings settings;
  settings.segments_u = 6;
  settings.segments_v = 12;
  const TriangleMesh mesh = tessellate_model(model, q, settings, "ball");
  const TriangleMesh expected = tessellate_surface(parametric_surface(sphere(1.5)), 6, 12);
  EXPECT_EQ(mesh.name, "ball");
  ASSERT_EQ(mesh.vertex_count(), expected.vertex_count());
  EXPECT_EQ(mesh.vertex_count(), 5 * 12 + 2);  // one vertex per pole, no seam duplicates
  // x(u) from the control points in q equals the NURBS evaluation up to rounding
  EXPECT_LT((mesh.vertices - expected.vertices).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_EQ(mesh.triangles, expected.triangles);
  EXPECT_TRUE(is_closed(mesh));
}

TEST(ModelTessellation, MovedSuperquadricIsClosedWithNormalsOfTheRotatedShape) {
  SuperquadricShapeParameters shape;
  shape << 1.0, 1.0, 0.8, 1.2, 0.6, 0.7, 0.2, 0.1, 0.0, 0.0, 0.0, 0.3, 0.0, 0.0;
  const Eigen::Vector3d centre(1.0, -2.0, 0.5);
  const Eigen::Quaterniond orientation(
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  const DeformableSuperquadricModel model(shape, centre, orientation);
  const Eigen::VectorXd q = model.initial_coordinates();
  ModelTessellationSettings settings;
  settings.segments_u = 10;
  settings.segments_v = 16;
  const TriangleMesh mesh = tessellate_model(model, q, settings);
  EXPECT_EQ(mesh.vertex_count(), 9 * 16 + 2);
  EXPECT_TRUE(is_closed(mesh));
  const DeformableSuperquadricShape reference(shape);
  const Eigen::Matrix3d rotation = orientation.toRotationMatrix();
  for (int k = 0; k < mesh.vertex_count(); ++k) {
    const double u = mesh.uv(k, 0);
    const double v = mesh.uv(k, 1);
    const Eigen::Vector3d x = centre + rotation * reference.point(u, v);
    EXPECT_LT((mesh.vertices.row(k).transpose() - x).norm(), 1e-14) << "vertex " << k;
    // Central differences of x with step 1e-5 of the extent: truncation ~ h^2 |x'''| / 6 over
    // |x_u x x_v|; the superquadric's exponents below 1 make x''' large near cos = 0 or
    // sin = 0 (observed 3e-8 at v = -pi), hence 1e-6 instead of 1e-9; the poles use the ring
    // mean of ParametricSurface
    const Eigen::Vector3d n = rotation * reference.unit_normal(u, v);
    EXPECT_LT((mesh.normals.row(k).transpose() - n).norm(), 1e-6) << "vertex " << k;
  }
}

TEST(ModelTessellation, DNurbsCurveGivesATube) {
  const DNurbsCurve model(full_circle(2.0));
  ModelTessellationSettings settings;
  settings.segments_u = 20;
  settings.tube_radius = 0.1;
  settings.tube_sides = 6;
  const TriangleMesh mesh = tessellate_model(model, model.initial_coordinates(), settings);
  EXPECT_EQ(mesh.vertex_count(), 21 * 6);
  for (int k = 0; k < mesh.vertex_count(); ++k) {
    const Eigen::Vector3d x = mesh.vertices.row(k).transpose();
    // the tube ring sits at distance 0.1 from the circle of radius 2 in the xy plane
    const double ring = std::hypot(std::hypot(x.x(), x.y()) - 2.0, x.z());
    EXPECT_NEAR(ring, 0.1, 1e-12);
  }
}

TEST(ModelTessellation, AdaptiveMeshOfADNurbsSphereIsClosedAndFiner) {
  const DNurbsSurface model(sphere(1.0));
  ModelTessellationSettings settings;
  settings.segments_u = 2;
  settings.segments_v = 4;
  settings.max_error = 5e-3;
  const TriangleMesh mesh = tessellate_model(model, model.initial_coordinates(), settings);
  EXPECT_TRUE(is_closed(mesh));
  EXPECT_GT(mesh.vertex_count(), 1 * 4 + 2);  // more than the base mesh
  for (int k = 0; k < mesh.vertex_count(); ++k) {
    EXPECT_NEAR(mesh.vertices.row(k).norm(), 1.0, 1e-14);  // rational evaluation rounding
  }
}

TEST(ModelTessellation, WrongCoordinatesNameTheSizes) {
  const DNurbsSurface model(sphere(1.0));
  try {
    tessellate_model(model, Eigen::VectorXd::Zero(5));
    FAIL() << "expected Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("5 entries"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace dnurbs
