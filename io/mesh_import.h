#pragma once
// Importing triangle meshes through assimp (any format assimp reads).

#include <filesystem>
#include <vector>

#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// Reads every mesh of the file's scene as a TriangleMesh, with the node transforms applied
/// (aiProcess_Triangulate | aiProcess_JoinIdenticalVertices; polygons are triangulated, points
/// and lines dropped). A mesh's name is its node's name, or the mesh's own when the node has
/// none. normals and uv have 0 rows where the file has none.
/// assimp runs in a child process (core/child_process_call.h), so that a file that crashes it
/// (assimp 5.2.5 has such bugs) gives an Error instead of ending the program.
/// Throws Error if the file does not exist, assimp cannot read it (with assimp's message) or its
/// data structure is invalid (aiProcess_ValidateDataStructure), assimp crashes on it (naming the
/// signal), or a vertex, normal or texture coordinate is not finite (naming the mesh and the
/// vertex).
/// `cpu_seconds` bounds the CPU time assimp may take (0: 10 s plus 1 s per MB of file, several
/// times what assimp needs; assimp 5.2.5 loops forever on some malformed files).
std::vector<TriangleMesh> import_meshes(const std::filesystem::path& path, int cpu_seconds = 0);

}  // namespace dnurbs
