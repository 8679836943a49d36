#pragma once
// Point sets for fitting: validation, a plain-text reader and the vertices of imported meshes.

#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// Throws Error if `points` (count by 3) is empty or holds a non-finite coordinate (naming the
/// row and the value). `what` names the set in the message ("points to fit").
void check_points(const Eigen::MatrixX3d& points, const char* what);

/// Reads points from a text file: one point per line as three numbers separated by blanks or
/// commas; blank lines and lines starting with '#' are skipped. Throws Error naming the file
/// and line if the file cannot be opened, a line does not hold three numbers, a value is not
/// finite, or there is no point.
Eigen::MatrixX3d load_points(const std::filesystem::path& path);

/// The vertices of every mesh stacked (count by 3); throws Error if there are none or one is
/// not finite. With io/mesh_import.h: mesh_vertices(import_meshes(path)).
Eigen::MatrixX3d mesh_vertices(const std::vector<TriangleMesh>& meshes);

}  // namespace dnurbs
