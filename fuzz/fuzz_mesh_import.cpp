// libFuzzer target: the mesh importer (import_meshes, through assimp). The first input byte
// picks the file extension, and with it assimp's reader (OBJ, STL, PLY, OFF, glTF: the byte
// modulo 5, so the seeds of fuzz/corpus/mesh start with A to E); the rest is the file. An
// imported mesh must be usable by every consumer (grid_from_mesh, fitting): finite vertices,
// normals and texture coordinates, triangle indices inside the vertex range.

#include <array>
#include <filesystem>
#include <fstream>
#include <string>

#include "dnurbs/core/error.h"
#include "dnurbs/io/mesh_import.h"
#include "fuzz/fuzz_support.h"

namespace {

// assimp's CPU time per input: a second is a hundred times what a 4 kB file needs, and an input
// on which assimp loops forever then costs the run one second, not the default ten.
constexpr int kCpuSeconds = 1;
constexpr std::array<const char*, 5> kExtensions = {".obj", ".stl", ".ply", ".off", ".gltf"};

void check_usable(const dnurbs::TriangleMesh& mesh) {
  if (!mesh.vertices.allFinite() || !mesh.normals.allFinite() || !mesh.uv.allFinite()) {
    dnurbs::fuzz::fail("mesh \"" + mesh.name + "\" has a non-finite vertex, normal or uv");
  }
  if (mesh.normals.rows() != 0 && mesh.normals.rows() != mesh.vertices.rows()) {
    dnurbs::fuzz::fail("mesh \"" + mesh.name + "\" has a normal count unequal to its vertices");
  }
  if (mesh.triangles.size() > 0 &&
      (mesh.triangles.minCoeff() < 0 || mesh.triangles.maxCoeff() >= mesh.vertex_count())) {
    dnurbs::fuzz::fail("mesh \"" + mesh.name + "\" has a triangle index outside its vertices");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) {
    return 0;
  }
  const std::filesystem::path path =
      dnurbs::fuzz::scratch_folder() /
      (std::string("mesh") + kExtensions[data[0] % kExtensions.size()]);
  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
    if (!file) {
      dnurbs::fuzz::fail("cannot write the input to " + path.string());
    }
  }
  try {
    for (const dnurbs::TriangleMesh& mesh : dnurbs::import_meshes(path, kCpuSeconds)) {
      check_usable(mesh);
    }
  } catch (const dnurbs::Error&) {
  }
  std::filesystem::remove(path);
  return 0;
}
