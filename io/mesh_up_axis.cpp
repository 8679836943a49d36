#include "io/mesh_up_axis.h"

#include <algorithm>
#include <cctype>
#include <string>

namespace dnurbs {

bool is_y_up_mesh_file(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
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
