#include "dnurbs/io/mesh_import.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <utility>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "dnurbs/core/child_process_call.h"
#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"
#include "dnurbs/io/mesh_up_axis.h"

namespace dnurbs {
namespace {

// A mesh that reaches grid_from_mesh or a fit must be finite: a file's "v nan 0 0" or 1e999
// (read as inf) is refused here, naming the file, the mesh and the vertex.
void check_finite(const TriangleMesh& mesh, const std::filesystem::path& path) {
  for (int i = 0; i < mesh.vertex_count(); ++i) {
    const bool finite = mesh.vertices.row(i).allFinite() &&
                        (mesh.normals.rows() == 0 || mesh.normals.row(i).allFinite()) &&
                        (mesh.uv.rows() == 0 || mesh.uv.row(i).allFinite());
    if (!finite) {
      throw make_error(path.string(), ": mesh \"", printable_excerpt(mesh.name), "\": vertex ", i,
                       " has a non-finite position, normal or texture coordinate");
    }
  }
}

TriangleMesh to_triangle_mesh(const aiMesh& mesh, const aiMatrix4x4& transform, std::string name) {
  const aiMatrix3x3 normal_transform = aiMatrix3x3(transform).Inverse().Transpose();
  TriangleMesh result;
  result.name = std::move(name);
  const int vertex_count = static_cast<int>(mesh.mNumVertices);
  result.vertices.resize(vertex_count, 3);
  for (int i = 0; i < vertex_count; ++i) {
    const aiVector3D p = transform * mesh.mVertices[i];
    result.vertices.row(i) << p.x, p.y, p.z;
  }
  if (mesh.HasNormals()) {
    result.normals.resize(vertex_count, 3);
    for (int i = 0; i < vertex_count; ++i) {
      aiVector3D n = normal_transform * mesh.mNormals[i];
      n.NormalizeSafe();
      result.normals.row(i) << n.x, n.y, n.z;
    }
  }
  if (mesh.HasTextureCoords(0)) {
    result.uv.resize(vertex_count, 2);
    for (int i = 0; i < vertex_count; ++i) {
      result.uv.row(i) << mesh.mTextureCoords[0][i].x, mesh.mTextureCoords[0][i].y;
    }
  }
  int triangle_count = 0;
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    triangle_count += mesh.mFaces[f].mNumIndices == 3 ? 1 : 0;
  }
  result.triangles.resize(triangle_count, 3);
  int row = 0;
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices == 3) {  // points and lines are dropped
      result.triangles.row(row++) << static_cast<int>(face.mIndices[0]),
          static_cast<int>(face.mIndices[1]), static_cast<int>(face.mIndices[2]);
    }
  }
  return result;
}

void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent,
             std::vector<TriangleMesh>& meshes) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned k = 0; k < node.mNumMeshes; ++k) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[k]];
    if ((mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) {
      continue;
    }
    const std::string name =
        node.mName.length > 0 ? node.mName.C_Str() : std::string(mesh.mName.C_Str());
    meshes.push_back(to_triangle_mesh(mesh, transform, name));
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    collect(scene, *node.mChildren[c], transform, meshes);
  }
}

// The meshes as bytes, from the importing child process to the caller (same machine, same
// layout): per mesh the name's size and bytes, the row counts of vertices, normals, uv and
// triangles, then each matrix's coefficients.
template <typename Value>
void append_raw(std::string& bytes, const Value* values, std::size_t count) {
  bytes.append(reinterpret_cast<const char*>(values), count * sizeof(Value));
}

std::string to_bytes(const std::vector<TriangleMesh>& meshes) {
  std::string bytes;
  for (const TriangleMesh& mesh : meshes) {
    const std::array<std::int64_t, 5> sizes = {static_cast<std::int64_t>(mesh.name.size()),
                                               mesh.vertices.rows(), mesh.normals.rows(),
                                               mesh.uv.rows(), mesh.triangles.rows()};
    append_raw(bytes, sizes.data(), sizes.size());
    bytes += mesh.name;
    append_raw(bytes, mesh.vertices.data(), mesh.vertices.size());
    append_raw(bytes, mesh.normals.data(), mesh.normals.size());
    append_raw(bytes, mesh.uv.data(), mesh.uv.size());
    append_raw(bytes, mesh.triangles.data(), mesh.triangles.size());
  }
  return bytes;
}

class ByteReader {
 public:
  ByteReader(std::string_view bytes, const std::filesystem::path& path)
      : bytes_(bytes), path_(path) {}
  bool done() const { return offset_ == bytes_.size(); }
  template <typename Value>
  void read(Value* values, std::int64_t count) {
    const std::size_t size = static_cast<std::size_t>(count) * sizeof(Value);
    if (count < 0 || size > bytes_.size() - offset_) {
      throw make_error(path_.string(), ": the mesh reader's reply is cut short");
    }
    if (size > 0) {  // an empty matrix's data() may be null
      std::memcpy(values, bytes_.data() + offset_, size);
    }
    offset_ += size;
  }

 private:
  std::string_view bytes_;
  const std::filesystem::path& path_;
  std::size_t offset_ = 0;
};

std::vector<TriangleMesh> from_bytes(std::string_view bytes, const std::filesystem::path& path) {
  std::vector<TriangleMesh> meshes;
  ByteReader reader(bytes, path);
  while (!reader.done()) {
    std::array<std::int64_t, 5> sizes{};
    reader.read(sizes.data(), sizes.size());
    const std::int64_t rows_limit = static_cast<std::int64_t>(bytes.size() / sizeof(int));
    for (const std::int64_t size : sizes) {
      if (size < 0 || size > rows_limit) {
        throw make_error(path.string(), ": the mesh reader's reply is malformed");
      }
    }
    TriangleMesh& mesh = meshes.emplace_back();
    mesh.name.resize(static_cast<std::size_t>(sizes[0]));
    reader.read(mesh.name.data(), sizes[0]);
    mesh.vertices.resize(sizes[1], 3);
    reader.read(mesh.vertices.data(), mesh.vertices.size());
    mesh.normals.resize(sizes[2], 3);
    reader.read(mesh.normals.data(), mesh.normals.size());
    mesh.uv.resize(sizes[3], 2);
    reader.read(mesh.uv.data(), mesh.uv.size());
    mesh.triangles.resize(sizes[4], 3);
    reader.read(mesh.triangles.data(), mesh.triangles.size());
  }
  return meshes;
}

std::vector<TriangleMesh> read_with_assimp(const std::filesystem::path& path) {
  Assimp::Importer importer;
  // aiProcess_ValidateDataStructure: assimp checks mesh and face indices against their arrays
  // (a file's face "f 1 2 99999" is refused instead of indexing past the vertices)
  const aiScene* scene =
      importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                           aiProcess_ValidateDataStructure);
  if (scene == nullptr || scene->mRootNode == nullptr ||
      (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
    throw make_error(path.string(),
                     ": assimp cannot read the mesh file: ", importer.GetErrorString());
  }
  std::vector<TriangleMesh> meshes;
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), meshes);
  if (is_y_up_mesh_file(path)) {  // glTF is Y-up: back to dnurbs' Z-up (io/mesh_up_axis.h)
    for (TriangleMesh& mesh : meshes) {
      mesh = rotated_mesh(std::move(mesh), z_up_to_y_up().transpose());
    }
  }
  return meshes;
}

}  // namespace

std::vector<TriangleMesh> import_meshes(const std::filesystem::path& path, int cpu_seconds) {
  check_input_file(path, "mesh file");
  // assimp runs in a child process: on some malformed files (a PLY header found by
  // fuzz/fuzz_mesh_import.cpp) assimp 5.2.5 reads outside its buffers and crashes, and a crash
  // there must end as an Error here, not as the end of a run or of a sculpting session.
  // On others it loops forever (a PLY header, found the same way): by default the child gets
  // 10 s of CPU time plus 1 s per MB of file, several times what assimp needs for that size.
  if (cpu_seconds < 0) {
    throw make_error(path.string(), ": the CPU time limit of the mesh reader is ", cpu_seconds,
                     " s, expected > 0 (or 0 for the default)");
  }
  if (cpu_seconds == 0) {
    cpu_seconds = 10 + static_cast<int>(std::min<std::uintmax_t>(
                           std::filesystem::file_size(path) >> 20, kInputFileLimit >> 20));
  }
  const std::string bytes =
      call_in_child_process([&path] { return to_bytes(read_with_assimp(path)); },
                            path.string() + ": assimp, reading the mesh file,", cpu_seconds);
  std::vector<TriangleMesh> meshes = from_bytes(bytes, path);
  for (const TriangleMesh& mesh : meshes) {
    check_finite(mesh, path);
  }
  return meshes;
}

}  // namespace dnurbs
