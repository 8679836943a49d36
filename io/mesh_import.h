#pragma once
// Importing triangle meshes through assimp (any format assimp reads).

#include <filesystem>
#include <vector>

#include "surface/triangle_mesh.h"

namespace dnurbs {

/// Reads every mesh of the file's scene as a TriangleMesh, with the node transforms applied
/// (aiProcess_Triangulate | aiProcess_JoinIdenticalVertices; polygons are triangulated, points
/// and lines dropped). A mesh's name is its node's name, or the mesh's own when the node has
/// none. normals and uv have 0 rows where the file has none.
/// Throws Error if the file does not exist or assimp cannot read it (with assimp's message).
std::vector<TriangleMesh> import_meshes(const std::filesystem::path& path);

}  // namespace dnurbs
