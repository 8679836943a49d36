#pragma once
// The up axis of mesh files. dnurbs is Z-up: its scenes stand on the plane z = 0, gravity points
// along -z. glTF 2.0 is Y-up (Khronos, "glTF 2.0 Specification", section 3.4 "Coordinate System
// and Units": +Y up, +Z forward, lengths in metres). export_meshes writes a glTF file's vertices
// and normals turned by z_up_to_y_up, so that viewers and other tools show the scene upright,
// and import_meshes turns a glTF file's back, so that a round trip is the identity and a glTF
// made elsewhere comes in Z-up. OBJ, STL and PLY declare no axis and are written as the model
// is, or Y-up when asked (UpAxis::kY: output.up_axis, dnurbs export --up-axis). Lengths are written
// as they are: a scene unit is a glTF metre.

#include <filesystem>

#include <Eigen/Core>

#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// The up axis of a file that declares none (OBJ, STL, PLY): Z as dnurbs (the default), or Y
/// for tools that expect it (vertices and normals turned by z_up_to_y_up, as glTF's are).
enum class UpAxis { kZ, kY };

/// True for the Y-up mesh formats, by the path's extension (case-insensitive): .gltf and .glb.
bool is_y_up_mesh_file(const std::filesystem::path& path);

/// The rotation from dnurbs' Z-up frame to a Y-up file's frame, 3 x 3: (x, y, z) -> (x, z, -y),
/// a quarter turn about +x (right-handed; its inverse is its transpose). Its entries are 0 and
/// +-1, so turning and turning back is exact.
Eigen::Matrix3d z_up_to_y_up();

/// The mesh's vertices and normals turned by `rotation` (3 x 3; names, uv and triangles kept).
TriangleMesh rotated_mesh(TriangleMesh mesh, const Eigen::Matrix3d& rotation);

}  // namespace dnurbs
