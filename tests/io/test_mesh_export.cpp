#include "dnurbs/io/mesh_export.h"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "dnurbs/core/error.h"
#include "dnurbs/io/gltf_extensions.h"
#include "dnurbs/io/mesh_import.h"
#include "dnurbs/io/mesh_up_axis.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "dnurbs/surface/tessellation.h"
#include "tests/common/child_process.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;
using Json = nlohmann::json;

std::filesystem::path fresh_directory(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("dnurbs_test_mesh_export_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory;
}

std::vector<std::string> file_names(const std::filesystem::path& directory) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<TriangleMesh> sample_meshes() {
  return {tessellate_surface(periodic_torus(2.0, 0.5), 10, 6, "torus"),
          tessellate_surface(sphere(0.75), 5, 8, "sphere")};
}

// Largest distance from a vertex of `from` to the nearest vertex of `to`
double one_sided_distance(const Eigen::MatrixX3d& from, const Eigen::MatrixX3d& to) {
  double worst = 0.0;
  for (int i = 0; i < from.rows(); ++i) {
    worst = std::max(worst, (to.rowwise() - from.row(i)).rowwise().norm().minCoeff());
  }
  return worst;
}

Eigen::MatrixX3d all_vertices(const std::vector<TriangleMesh>& meshes) {
  Eigen::Index rows = 0;
  for (const auto& mesh : meshes) {
    rows += mesh.vertices.rows();
  }
  Eigen::MatrixX3d stacked(rows, 3);
  Eigen::Index row = 0;
  for (const auto& mesh : meshes) {
    stacked.middleRows(row, mesh.vertices.rows()) = mesh.vertices;
    row += mesh.vertices.rows();
  }
  return stacked;
}

int all_triangles(const std::vector<TriangleMesh>& meshes) {
  int count = 0;
  for (const auto& mesh : meshes) {
    count += mesh.triangle_count();
  }
  return count;
}

class MeshExportRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(MeshExportRoundTrip, ImportGivesTheSameVerticesAndTriangles) {
  const auto directory = fresh_directory("round_trip_" + GetParam());
  const std::filesystem::path path = directory / ("meshes." + GetParam());
  const std::vector<TriangleMesh> meshes = sample_meshes();
  export_meshes(meshes, path);
  const std::vector<TriangleMesh> imported = import_meshes(path);
  ASSERT_FALSE(imported.empty());
  EXPECT_EQ(all_triangles(imported), all_triangles(meshes));
  // Files store single precision: |x| <= 2.5 rounds by at most 2.5 * 2^-24 ~ 1.5e-7
  const Eigen::MatrixX3d original = all_vertices(meshes);
  const Eigen::MatrixX3d read = all_vertices(imported);
  EXPECT_LT(one_sided_distance(original, read), 1e-6);
  EXPECT_LT(one_sided_distance(read, original), 1e-6);
  // Every imported triangle is one of the original triangles (by its corner positions)
  for (const auto& mesh : imported) {
    for (int f = 0; f < mesh.triangle_count(); f += 7) {
      const Eigen::Vector3d centroid =
          (mesh.vertices.row(mesh.triangles(f, 0)) + mesh.vertices.row(mesh.triangles(f, 1)) +
           mesh.vertices.row(mesh.triangles(f, 2))) /
          3.0;
      double nearest = 1e300;
      for (const auto& source : meshes) {
        for (int g = 0; g < source.triangle_count(); ++g) {
          const Eigen::Vector3d c = (source.vertices.row(source.triangles(g, 0)) +
                                     source.vertices.row(source.triangles(g, 1)) +
                                     source.vertices.row(source.triangles(g, 2))) /
                                    3.0;
          nearest = std::min(nearest, (c - centroid).norm());
        }
      }
      EXPECT_LT(nearest, 1e-6);
    }
  }
  // No temporary file is left: only the exported file (and its .mtl or .bin)
  for (const auto& name : file_names(directory)) {
    EXPECT_THAT(name, ::testing::Not(HasSubstr(".tmp")));
    EXPECT_THAT(name, ::testing::StartsWith("meshes."));
  }
  std::filesystem::remove_all(directory);
}

INSTANTIATE_TEST_SUITE_P(Formats, MeshExportRoundTrip,
                         ::testing::Values("obj", "stl", "ply", "gltf", "glb"));

// glTF is Y-up (io/mesh_up_axis.h): the file holds (x, z, -y), which its POSITION accessor's
// bounds show, and the import turns it back exactly; OBJ keeps the model's axes
// One triangle "tri" with corners (0, 0, 0), (1, 0, 0), (0, 2, 1).
TriangleMesh one_triangle() {
  TriangleMesh triangle;
  triangle.name = "tri";
  triangle.vertices.resize(3, 3);
  triangle.vertices << 0, 0, 0,  //
      1, 0, 0,                   //
      0, 2, 1;
  triangle.triangles.resize(1, 3);
  triangle.triangles << 0, 1, 2;
  return triangle;
}

TEST(MeshExport, GltfIsWrittenYUpAndReadBackZUp) {
  const TriangleMesh triangle = one_triangle();
  const auto directory = fresh_directory("y_up");
  export_mesh(triangle, directory / "tri.gltf");
  const Json gltf = Json::parse(std::ifstream(directory / "tri.gltf"));
  const int position =
      gltf.at("meshes").at(0).at("primitives").at(0).at("attributes").at("POSITION");
  const Json& accessor = gltf.at("accessors").at(static_cast<size_t>(position));
  EXPECT_EQ(accessor.at("min"), Json::parse("[0, 0, -2]"));
  EXPECT_EQ(accessor.at("max"), Json::parse("[1, 1, 0]"));
  for (const char* name : {"tri.gltf", "tri.glb", "tri.obj"}) {
    if (std::string(name) != "tri.gltf") {
      export_mesh(triangle, directory / name);
    }
    const std::vector<TriangleMesh> meshes = import_meshes(directory / name);
    ASSERT_EQ(meshes.size(), 1U) << name;
    EXPECT_EQ(meshes[0].vertices, triangle.vertices) << name;
  }
  std::filesystem::remove_all(directory);
}

// UpAxis::kY turns OBJ, STL and PLY Y-up like glTF; glTF is Y-up whatever the setting
TEST(MeshExport, UpAxisYTurnsTheFormatsThatDeclareNoAxis) {
  const TriangleMesh triangle = one_triangle();
  const Eigen::MatrixX3d turned = triangle.vertices * z_up_to_y_up().transpose();
  const auto directory = fresh_directory("up_axis");
  for (const char* name : {"tri.obj", "tri.stl", "tri.ply"}) {
    export_meshes({triangle}, directory / name, UpAxis::kY);
    EXPECT_EQ(import_meshes(directory / name).at(0).vertices, turned) << name;
    export_meshes({triangle}, directory / name, UpAxis::kZ);
    EXPECT_EQ(import_meshes(directory / name).at(0).vertices, triangle.vertices) << name;
  }
  export_meshes({triangle}, directory / "y.gltf", UpAxis::kY);
  export_meshes({triangle}, directory / "z.gltf", UpAxis::kZ);
  std::ifstream y(directory / "y.gltf");
  std::ifstream z(directory / "z.gltf");
  EXPECT_EQ(Json::parse(y).at("accessors"), Json::parse(z).at("accessors"));  // the same bounds
  EXPECT_EQ(import_meshes(directory / "y.gltf").at(0).vertices, triangle.vertices);
  std::filesystem::remove_all(directory);
}

// The glTF documents list no extension they do not use (assimp lists KHR_materials_volume and
// FB_ngon_encoding whatever the scene); the binary file's header and chunk lengths stay valid
TEST(MeshExport, GltfListsOnlyTheExtensionsItUses) {
  const TriangleMesh triangle = one_triangle();
  const auto directory = fresh_directory("extensions");
  export_mesh(triangle, directory / "tri.gltf");
  export_mesh(triangle, directory / "tri.glb");
  const Json gltf = Json::parse(std::ifstream(directory / "tri.gltf"));
  std::ifstream in(directory / "tri.glb", std::ios::binary);
  const std::string glb{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  ASSERT_GT(glb.size(), 20U);
  const auto u32 = [&](size_t at) {
    std::uint32_t value = 0;
    std::memcpy(&value, glb.data() + at, 4);
    return static_cast<size_t>(value);
  };
  EXPECT_EQ(u32(8), glb.size());  // the header's total length
  EXPECT_EQ(u32(12) % 4, 0U);     // the JSON chunk is padded to 4 bytes
  const Json binary = Json::parse(glb.substr(20, u32(12)));
  for (const Json* document : {&gltf, &binary}) {
    EXPECT_FALSE(document->contains("extensionsUsed")) << document->dump().substr(0, 200);
    EXPECT_FALSE(document->contains("extensionsRequired"));
    EXPECT_EQ(document->at("asset").at("version"), "2.0");
  }
  for (const char* name : {"tri.gltf", "tri.glb"}) {
    EXPECT_EQ(import_meshes(directory / name).at(0).vertices, triangle.vertices) << name;
  }
  // Used extensions stay: the rule on a document that uses one of the two it lists
  Json document = Json::parse(R"({"extensionsUsed": ["KHR_a", "KHR_b"],
                                  "extensionsRequired": ["KHR_b"],
                                  "materials": [{"extensions": {"KHR_a": {}}}]})");
  drop_unused_gltf_extensions(document);
  EXPECT_EQ(document.at("extensionsUsed"), Json::parse(R"(["KHR_a"])"));
  EXPECT_FALSE(document.contains("extensionsRequired"));
  std::filesystem::remove_all(directory);
}

TEST(MeshExport, ObjKeepsOneObjectPerMeshWithNormalsAndUv) {
  const auto directory = fresh_directory("obj_objects");
  const std::vector<TriangleMesh> meshes = sample_meshes();
  export_meshes(meshes, directory / "two.obj");
  EXPECT_EQ(file_names(directory), (std::vector<std::string>{"two.mtl", "two.obj"}));
  const std::vector<TriangleMesh> imported = import_meshes(directory / "two.obj");
  ASSERT_EQ(imported.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(imported[k].name, meshes[k].name);
    EXPECT_EQ(imported[k].triangle_count(), meshes[k].triangle_count());
    ASSERT_EQ(imported[k].normals.rows(), imported[k].vertices.rows());
    ASSERT_EQ(imported[k].uv.rows(), imported[k].vertices.rows());
    // Each imported vertex carries the normal and uv of the original vertex at its position
    // (the torus has no repeated positions; single precision in the file)
    if (meshes[k].name == "torus") {
      for (int r = 0; r < imported[k].vertex_count(); ++r) {
        Eigen::Index nearest = 0;
        (meshes[k].vertices.rowwise() - imported[k].vertices.row(r))
            .rowwise()
            .norm()
            .minCoeff(&nearest);
        EXPECT_LT((imported[k].normals.row(r) - meshes[k].normals.row(nearest)).norm(), 1e-6);
        EXPECT_LT((imported[k].uv.row(r) - meshes[k].uv.row(nearest)).norm(), 1e-6);
      }
    }
  }
  std::filesystem::remove_all(directory);
}

// A mesh name goes into the files as text: one that is not a plain name (io/output_path.h) is
// replaced by mesh_<i>, so that a name with line breaks cannot inject OBJ or MTL records
TEST(MeshExport, NamesThatAreNotPlainCannotInjectRecords) {
  const auto directory = fresh_directory("hostile_names");
  std::vector<TriangleMesh> meshes = sample_meshes();
  meshes[0].name = "rod\nv nan nan nan\nf 1 2 99999";
  meshes[1].name = std::string("sphere\0tail", 11);
  export_meshes(meshes, directory / "two.obj");
  for (const char* file : {"two.obj", "two.mtl"}) {
    std::ifstream in(directory / file);
    std::string line;
    int lines = 0;
    while (std::getline(in, line)) {
      ++lines;
      EXPECT_THAT(line, ::testing::Not(HasSubstr("nan"))) << file;
      EXPECT_NE(line, "f 1 2 99999") << file;
      EXPECT_EQ(line.find('\0'), std::string::npos) << file;
    }
    EXPECT_GT(lines, 3) << file;
  }
  const std::vector<TriangleMesh> imported = import_meshes(directory / "two.obj");
  ASSERT_EQ(imported.size(), 2u);
  EXPECT_EQ(imported[0].name, "mesh_0");
  EXPECT_EQ(imported[1].name, "mesh_1");
  EXPECT_EQ(imported[0].triangle_count(), meshes[0].triangle_count());
  EXPECT_EQ(imported[1].triangle_count(), meshes[1].triangle_count());
  std::filesystem::remove_all(directory);
}

// Mesh files hold single precision: a finite double beyond it is an error, not "v inf"
TEST(MeshExport, VertexBeyondSinglePrecisionIsAnErrorAndWritesNothing) {
  const auto directory = fresh_directory("float_range");
  std::vector<TriangleMesh> meshes = sample_meshes();
  meshes[1].vertices(3, 1) = 1e50;
  for (const char* file : {"big.obj", "big.stl", "big.ply", "big.gltf"}) {
    try {
      export_meshes(meshes, directory / file);
      ADD_FAILURE() << file << " was written";
    } catch (const Error& error) {
      EXPECT_THAT(error.what(), HasSubstr("mesh 1 (\"sphere\") has vertex 3 = (")) << file;
      EXPECT_THAT(error.what(), HasSubstr("beyond the single precision of mesh files")) << file;
    }
  }
  EXPECT_TRUE(file_names(directory).empty());
  std::filesystem::remove_all(directory);
}

// A full disk, injected as a file size limit (RLIMIT_FSIZE: a write past it fails with EFBIG,
// SIGXFSZ ignored) in a child process: every format's export fails with an Error naming the
// file, the previous file stays as it was and no temporary is left.
TEST(MeshExport, AWriteThatFailsKeepsTheOldFileAndExitsWithAnError) {
  const auto directory = fresh_directory("write_fails");
  for (const char* file : {"m.obj", "m.stl", "m.ply", "m.gltf", "m.glb"}) {
    SCOPED_TRACE(file);
    const std::filesystem::path target = directory / file;
    { std::ofstream(target) << "the previous file\n"; }
    const int code = testing::exit_code_with_file_size_limit(4096, [&] {
      try {
        export_meshes(sample_meshes(), target);
      } catch (const Error& error) {
        const std::string message = error.what();
        const bool named = message.find(target.string() + ": the export failed (") == 0 &&
                           message.find("no file was changed") != std::string::npos;
        return named ? 0 : 2;
      }
      return 1;  // the export claimed success
    });
    EXPECT_EQ(code, 0) << "1: no error, 2: a message without the file";
    std::ifstream in(target);
    std::string contents((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(contents, "the previous file\n");
  }
  const std::vector<std::string> left = file_names(directory);
  EXPECT_EQ(left, (std::vector<std::string>{"m.glb", "m.gltf", "m.obj", "m.ply", "m.stl"}));
  std::filesystem::remove_all(directory);
}

TEST(MeshExport, UnknownExtensionIsAnErrorAndWritesNothing) {
  const auto directory = fresh_directory("bad_extension");
  try {
    export_meshes(sample_meshes(), directory / "mesh.xyz");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("unknown mesh file extension \".xyz\""));
    EXPECT_THAT(error.what(), HasSubstr(".obj, .stl, .ply, .gltf or .glb"));
  }
  EXPECT_THROW(export_meshes(sample_meshes(), directory / "mesh"), Error);
  EXPECT_TRUE(file_names(directory).empty());
  EXPECT_EQ(mesh_format_from_path("A.OBJ"), MeshFormat::kObj);
  EXPECT_EQ(mesh_format_from_path("a.glb"), MeshFormat::kGlb);
  std::filesystem::remove_all(directory);
}

TEST(MeshExport, FailedExportKeepsTheOldFileAndLeavesNoTemporary) {
  const auto directory = fresh_directory("failed");
  const std::filesystem::path path = directory / "keep.stl";
  { std::ofstream(path) << "old contents"; }
  TriangleMesh broken = sample_meshes()[0];
  broken.triangles(3, 1) = broken.vertex_count();  // index out of range
  EXPECT_THROW(export_mesh(broken, path), Error);
  EXPECT_THROW(export_meshes({}, path), Error);
  EXPECT_EQ(file_names(directory), std::vector<std::string>{"keep.stl"});
  std::ifstream in(path);
  std::string contents;
  std::getline(in, contents);
  EXPECT_EQ(contents, "old contents");
  // A directory that does not exist: assimp cannot open the temporary file
  EXPECT_THROW(export_meshes(sample_meshes(), directory / "missing" / "mesh.obj"), Error);
  std::filesystem::remove_all(directory);
}

TEST(MeshImport, MissingOrUnreadableFileIsAnError) {
  const auto directory = fresh_directory("import");
  try {
    import_meshes(directory / "none.obj");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("none.obj: the mesh file does not exist"));
  }
  { std::ofstream(directory / "garbage.ply") << "this is not a ply file\n"; }
  try {
    import_meshes(directory / "garbage.ply");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("garbage.ply: assimp cannot read the mesh file"));
  }
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace dnurbs
