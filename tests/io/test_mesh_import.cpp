// import_meshes: a file's geometry comes in as written, and what a consumer cannot use (a
// non-finite vertex, a face that indexes past the vertices) is refused naming the file.
#include "dnurbs/io/mesh_import.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

std::filesystem::path write_obj(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path;
}

std::string import_error(const std::filesystem::path& path) {
  return testing::error_message([&] { import_meshes(path); });
}

TEST(MeshImport, ObjTriangleComesBackWithItsVerticesAndFace) {
  const auto path =
      write_obj("dnurbs_import_triangle.obj", "o tri\nv 0 0 0\nv 1 0 0\nv 0 2 0.5\nf 1 2 3\n");
  const std::vector<TriangleMesh> meshes = import_meshes(path);
  ASSERT_EQ(meshes.size(), 1U);
  ASSERT_EQ(meshes[0].vertex_count(), 3);
  ASSERT_EQ(meshes[0].triangle_count(), 1);
  EXPECT_EQ(meshes[0].vertices(meshes[0].triangles(0, 2), 1), 2.0);
  EXPECT_EQ(meshes[0].vertices(meshes[0].triangles(0, 2), 2), 0.5);
  std::filesystem::remove(path);
}

TEST(MeshImport, NonFiniteVertexIsRefusedNamingTheFileAndVertex) {
  const auto path =
      write_obj("dnurbs_import_nan.obj", "o tri\nv 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string message = import_error(path);
  EXPECT_THAT(message, ::testing::HasSubstr(path.string()));
  EXPECT_THAT(message, ::testing::HasSubstr("vertex 1 has a non-finite position"));
  std::filesystem::remove(path);
}

TEST(MeshImport, FaceIndexPastTheVerticesIsRefused) {
  const auto path =
      write_obj("dnurbs_import_index.obj", "o tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999\n");
  const std::string message = import_error(path);
  EXPECT_THAT(message, ::testing::HasSubstr(path.string()));
  EXPECT_THAT(message, ::testing::HasSubstr("assimp cannot read the mesh file"));
  std::filesystem::remove(path);
}

// Files found by fuzz/fuzz_mesh_import.cpp (tests/data/malformed_meshes/README.md): assimp
// crashes on the first, loops forever on the second and leaks on the third; both end as an Error
// naming the file.
TEST(MeshImport, AFileThatCrashesAssimpIsAnErrorNamingTheFileAndSignal) {
  const auto path =
      std::filesystem::path(DNURBS_TEST_DATA_DIR) / "malformed_meshes/assimp_crash_header.ply";
  const std::string message = import_error(path);
  EXPECT_THAT(message, ::testing::HasSubstr(path.string()));
  EXPECT_THAT(message, ::testing::HasSubstr("crashed (signal 11, Segmentation fault)"));
}

TEST(MeshImport, AFileOnWhichAssimpLoopsForeverEndsAtTheCpuTimeLimit) {
  const auto path =
      std::filesystem::path(DNURBS_TEST_DATA_DIR) / "malformed_meshes/assimp_endless_header.ply";
  EXPECT_EQ(import_error(path),
            path.string() +
                ": assimp, reading the mesh file, did not finish within its 10 s of CPU time");
}

TEST(MeshImport, AMalformedStlIsAnErrorNamingTheFile) {
  const auto path =
      std::filesystem::path(DNURBS_TEST_DATA_DIR) / "malformed_meshes/assimp_leak_vertex.stl";
  const std::string message = import_error(path);
  EXPECT_THAT(message, ::testing::StartsWith(path.string() + ": assimp cannot read the mesh file"));
}

}  // namespace
}  // namespace dnurbs
