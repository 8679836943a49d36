#include "io/mesh_import.h"

#include <system_error>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "core/error.h"
#include "core/input_file.h"

namespace dnurbs {
namespace {

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

}  // namespace

std::vector<TriangleMesh> import_meshes(const std::filesystem::path& path) {
  check_input_file(path, "mesh file");
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
  if (scene == nullptr || scene->mRootNode == nullptr ||
      (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
    throw make_error(path.string(),
                     ": assimp cannot read the mesh file: ", importer.GetErrorString());
  }
  std::vector<TriangleMesh> meshes;
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), meshes);
  return meshes;
}

}  // namespace dnurbs
