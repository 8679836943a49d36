// `dnurbs export` of triangular_nurbs shape files: the uniform mesh of N x N triangles per
// domain triangle, the adaptive mesh within a chord error, and the options that do not apply.

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/io/mesh_import.h"
#include "dnurbs/io/models/triangular_dnurbs_surface_scene.h"
#include "dnurbs/io/triangular_shape_file.h"
#include "tests/tools/run_dnurbs.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;
using Result = testing::CommandResult;

TEST(ExportCommand, TriangularShapeFileGivesUniformAndAdaptiveMeshes) {
  const auto directory = testing::fresh_directory("export_triangular");
  SceneTriangularDomain domain;
  domain.shape = "l_shape";
  domain.cells = Eigen::Vector2i(1, 1);  // 3 cells, 6 triangles
  const TriangularNurbsSurface flat = triangular_domain_surface(domain);
  Eigen::MatrixX3d points = flat.control_points();
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    points(i, 2) = 0.2 * std::sin(3.0 * points(i, 0)) * std::cos(2.0 * points(i, 1));
  }
  const TriangularNurbsSurface surface(flat.shared_basis(), points);
  const auto shape = directory / "l.json";
  write_triangular_shape_file(shape, surface);
  // Uniform: 6 domain triangles, 5 x 5 each
  const Result uniform = testing::run_dnurbs("export " + shape.string() + " " +
                                             (directory / "l.obj").string() + " --resolution 5");
  ASSERT_EQ(uniform.exit_code, 0) << uniform.err;
  EXPECT_THAT(uniform.out, HasSubstr("150 triangles"));
  const std::vector<TriangleMesh> meshes = import_meshes(directory / "l.obj");
  ASSERT_EQ(meshes.size(), 1u);
  EXPECT_EQ(meshes[0].triangle_count(), 6 * 25);
  // Default: 4 x 4 per domain triangle
  const Result standard =
      testing::run_dnurbs("export " + shape.string() + " " + (directory / "l.stl").string());
  ASSERT_EQ(standard.exit_code, 0) << standard.err;
  EXPECT_THAT(standard.out, HasSubstr("96 triangles"));
  // Adaptive: a PLY refined below the 6 domain triangles, with more triangles where the
  // surface bends (the bound itself is tested with the library, test_triangular_tessellation)
  const Result adaptive = testing::run_dnurbs(
      "export " + shape.string() + " " + (directory / "a.ply").string() + " --max-error 0.002");
  ASSERT_EQ(adaptive.exit_code, 0) << adaptive.err;
  const std::vector<TriangleMesh> refined = import_meshes(directory / "a.ply");
  ASSERT_EQ(refined.size(), 1u);
  EXPECT_GT(refined[0].triangle_count(), 6);
  // Options of tensor-product surfaces do not apply
  const Result angle = testing::run_dnurbs("export " + shape.string() + " " +
                                           (directory / "b.obj").string() + " --max-angle 10");
  EXPECT_EQ(angle.exit_code, 2);
  EXPECT_THAT(angle.err, HasSubstr("do not apply to triangular_nurbs"));
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace dnurbs
