// Grid surfaces from imported meshes: a grid mesh written to a file comes back as the same grid
// and node positions; meshes that are not a regular (u, v) lattice are rejected by name.

#include "dnurbs/io/grid_from_mesh.h"

#include <cmath>
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/io/mesh_export.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

// A bumpy 9 x 7 grid of spacing 0.25
NodePositions bumpy_positions(const Grid& grid) {
  NodePositions positions(grid.node_count(), 3);
  for (int k = 0; k < grid.node_count(); ++k) {
    const auto [i, j] = grid.node(k);
    const double u = i * grid.spacing();
    const double v = j * grid.spacing();
    positions.row(k) << u, v, 0.3 * std::sin(2.0 * u) * std::cos(v);
  }
  return positions;
}

std::string message_of(const TriangleMesh& mesh) {
  try {
    grid_from_mesh(mesh);
  } catch (const Error& error) {
    return error.what();
  }
  return "accepted";
}

TEST(GridFromMesh, AGridMeshWrittenToObjComesBackAsTheSameGrid) {
  const Grid grid(9, 7, 0.25);
  const NodePositions positions = bumpy_positions(grid);
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "dnurbs_grid_from_mesh.obj";
  export_mesh(grid_triangle_mesh(grid, positions, "sheet"), file);
  const GridFromMesh read = read_grid_from_mesh_file(file);
  EXPECT_EQ(read.grid.nu(), 9);
  EXPECT_EQ(read.grid.nv(), 7);
  EXPECT_NEAR(read.grid.spacing(), 0.25, 1e-6);  // OBJ stores single precision
  EXPECT_LT((read.positions - positions).cwiseAbs().maxCoeff(), 1e-6);
  std::filesystem::remove(file);
  std::filesystem::remove(std::filesystem::path(file).replace_extension(".mtl"));
  // In memory, exactly; a vertex split along a seam (same (u, v), same position) merges
  TriangleMesh mesh = grid_triangle_mesh(grid, positions);
  mesh.vertices.conservativeResize(mesh.vertex_count() + 1, 3);
  mesh.uv.conservativeResize(mesh.uv.rows() + 1, 2);
  mesh.vertices.row(mesh.vertex_count() - 1) = positions.row(grid.index(4, 3));
  mesh.uv.row(mesh.uv.rows() - 1) << 1.0, 0.75;
  const GridFromMesh exact = grid_from_mesh(mesh);
  EXPECT_EQ(exact.grid.spacing(), 0.25);
  EXPECT_EQ(exact.positions, positions);
}

TEST(GridFromMesh, MeshesThatAreNotARegularLatticeAreRejectedByName) {
  const Grid grid(5, 4, 0.5);
  const NodePositions positions = bumpy_positions(grid);
  const TriangleMesh good = grid_triangle_mesh(grid, positions);
  TriangleMesh no_uv = good;
  no_uv.uv.resize(0, 2);
  EXPECT_THAT(message_of(no_uv), HasSubstr("no texture coordinates"));
  TriangleMesh stretched = good;
  stretched.uv.col(1) *= 2.0;
  EXPECT_THAT(message_of(stretched), HasSubstr("the u spacing 0.5 and the v spacing 1 differ"));
  TriangleMesh uneven = good;
  uneven.uv(grid.index(2, 0), 0) = 1.3;  // u values 0, 0.5, 1.3 (one vertex), 1, 1.5, 2
  EXPECT_THAT(message_of(uneven), HasSubstr("u values are not equally spaced"));
  TriangleMesh missing = good;  // drop the last vertex: lattice point (4, 3) has none
  missing.vertices.conservativeResize(missing.vertex_count() - 1, 3);
  missing.uv.conservativeResize(missing.uv.rows() - 1, 2);
  EXPECT_THAT(message_of(missing), HasSubstr("no vertex at lattice point (4, 3)"));
  TriangleMesh contradictory = good;
  contradictory.vertices.conservativeResize(good.vertex_count() + 1, 3);
  contradictory.uv.conservativeResize(good.vertex_count() + 1, 2);
  contradictory.vertices.row(good.vertex_count()) << 9.0, 9.0, 9.0;
  contradictory.uv.row(good.vertex_count()) << 0.5, 0.5;
  EXPECT_THAT(message_of(contradictory), HasSubstr("have different positions"));
  TriangleMesh flat_line = good;
  flat_line.uv.col(1).setZero();
  EXPECT_THAT(message_of(flat_line), HasSubstr("at least 2 values along v"));
  TriangleMesh not_finite = good;
  not_finite.vertices(0, 2) = std::nan("");
  EXPECT_THAT(message_of(not_finite), HasSubstr("not finite"));
  EXPECT_THAT(message_of(TriangleMesh{}), HasSubstr("no vertices"));
  try {
    read_grid_from_mesh_file("/nonexistent/sheet.obj");
    ADD_FAILURE() << "a missing file was accepted";
  } catch (const Error& error) {
    EXPECT_THAT(std::string(error.what()), HasSubstr("/nonexistent/sheet.obj"));
  }
}

}  // namespace
}  // namespace dnurbs
