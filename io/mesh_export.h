#pragma once
// Exporting triangle meshes through assimp: OBJ, STL, PLY and glTF 2, chosen by file extension.

#include <filesystem>
#include <string>
#include <vector>

#include "dnurbs/io/mesh_up_axis.h"
#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// File formats export_meshes writes.
enum class MeshFormat {
  kObj,   ///< .obj (Wavefront, with a .mtl beside it): one object and one material per mesh
  kStl,   ///< .stl (binary STL: positions only, single precision)
  kPly,   ///< .ply (binary PLY)
  kGltf,  ///< .gltf (glTF 2 JSON with a .bin buffer beside it)
  kGlb,   ///< .glb (binary glTF 2)
};

/// The format of a path's extension (case-insensitive); throws Error naming the extension and
/// the supported ones otherwise.
MeshFormat mesh_format_from_path(const std::filesystem::path& path);

/// assimp's exporter id of a format ("obj", "stlb", "plyb", "gltf2", "glb2").
std::string assimp_format_id(MeshFormat format);

/// Writes the meshes into one file, the format chosen by the extension: one node and one
/// material (named after the mesh, with its own diffuse color) per mesh, normals and (u, v)
/// texture coordinates where the mesh has them (and the format stores them).
///
/// Every file the exporter writes (the .obj and its .mtl, the .gltf and its .bin) is first
/// written to a temporary file in the same directory and renamed to its name only when the whole
/// export has succeeded; on failure the temporary files are removed.
/// Throws Error for an unknown extension, an empty mesh list, a mesh with an index out of range
/// or mismatched normal/uv rows, and when assimp fails (with assimp's message).
/// `up`: the up axis of OBJ, STL and PLY files (io/mesh_up_axis.h); glTF is always Y-up.
void export_meshes(const std::vector<TriangleMesh>& meshes, const std::filesystem::path& path,
                   UpAxis up = UpAxis::kZ);

/// export_meshes of one mesh.
void export_mesh(const TriangleMesh& mesh, const std::filesystem::path& path);

}  // namespace dnurbs
