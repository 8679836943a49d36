#include "dnurbs/io/mesh_up_axis.h"

#include <string>

#include "dnurbs/core/input_file.h"

namespace dnurbs {

bool is_y_up_mesh_file(const std::filesystem::path& path) {
  const std::string extension = lowercase_extension(path);
  return extension == ".gltf" || extension == ".glb";
}

Eigen::Matrix3d z_up_to_y_up() {
  Eigen::Matrix3d rotation;
  rotation << 1, 0, 0,  //
      0, 0, 1,          //
      0, -1, 0;
  return rotation;
}

TriangleMesh rotated_mesh(TriangleMesh mesh, const Eigen::Matrix3d& rotation) {
  // Rows are points: (R p)^T = p^T R^T
  mesh.vertices = mesh.vertices * rotation.transpose();
  if (mesh.normals.rows() > 0) {
    mesh.normals = mesh.normals * rotation.transpose();
  }
  return mesh;
}

}  // namespace dnurbs
