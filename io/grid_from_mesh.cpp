#include "dnurbs/io/grid_from_mesh.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/io/mesh_import.h"

namespace dnurbs {
namespace {

// The distinct values of `values` (sorted, merged within `merge`), checked to be equally spaced;
// returns them and sets `spacing`.
std::vector<double> lattice_values(std::vector<double> values, double tolerance, const char* axis,
                                   double& spacing) {
  std::sort(values.begin(), values.end());
  const double extent = values.back() - values.front();
  if (!(extent > 0.0)) {
    throw make_error("grid from mesh: every vertex has the same ", axis, " = ", values.front(),
                     "; a grid needs at least 2 values along ", axis);
  }
  const double merge = tolerance * extent;
  std::vector<double> distinct{values.front()};
  for (const double x : values) {
    if (x - distinct.back() > merge) {
      distinct.push_back(x);
    }
  }
  spacing = extent / static_cast<double>(distinct.size() - 1);
  for (size_t i = 0; i < distinct.size(); ++i) {
    const double expected = values.front() + static_cast<double>(i) * spacing;
    if (std::abs(distinct[i] - expected) > merge + tolerance * spacing) {
      throw make_error("grid from mesh: ", axis, " values are not equally spaced: value ", i,
                       " is ", distinct[i], ", expected ", expected, " (spacing ", spacing, ")");
    }
  }
  return distinct;
}

}  // namespace

GridFromMesh grid_from_mesh(const TriangleMesh& mesh, double relative_tolerance) {
  if (!(relative_tolerance > 0.0) || !(relative_tolerance < 0.5)) {
    throw make_error("grid from mesh: relative tolerance ", relative_tolerance,
                     " is outside (0, 0.5)");
  }
  if (mesh.vertex_count() == 0) {
    throw make_error("grid from mesh: the mesh has no vertices");
  }
  if (mesh.uv.rows() != mesh.vertex_count()) {
    throw make_error("grid from mesh: the mesh has no texture coordinates (u, v)");
  }
  if (!mesh.uv.allFinite() || !mesh.vertices.allFinite()) {
    throw make_error("grid from mesh: a vertex or texture coordinate is not finite");
  }
  double spacing_u = 0.0;
  double spacing_v = 0.0;
  const Eigen::VectorXd u = mesh.uv.col(0);
  const Eigen::VectorXd v = mesh.uv.col(1);
  const std::vector<double> us =
      lattice_values({u.begin(), u.end()}, relative_tolerance, "u", spacing_u);
  const std::vector<double> vs =
      lattice_values({v.begin(), v.end()}, relative_tolerance, "v", spacing_v);
  if (std::abs(spacing_u - spacing_v) > relative_tolerance * std::max(spacing_u, spacing_v)) {
    throw make_error("grid from mesh: the u spacing ", spacing_u, " and the v spacing ", spacing_v,
                     " differ; a grid has one spacing h");
  }
  const int nu = static_cast<int>(us.size());
  const int nv = static_cast<int>(vs.size());
  GridFromMesh result{Grid(nu, nv, spacing_u), NodePositions(nu * nv, 3)};
  const double size =
      (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).norm();
  std::vector<char> seen(static_cast<size_t>(nu * nv), 0);
  for (int k = 0; k < mesh.vertex_count(); ++k) {
    const int i = static_cast<int>(std::lround((u[k] - us.front()) / spacing_u));
    const int j = static_cast<int>(std::lround((v[k] - vs.front()) / spacing_v));
    const int node = result.grid.index(i, j);
    const Eigen::RowVector3d x = mesh.vertices.row(k);
    if (seen[static_cast<size_t>(node)] &&
        (result.positions.row(node) - x).norm() > relative_tolerance * size) {
      throw make_error("grid from mesh: two vertices at (u, v) = (", u[k], ", ", v[k],
                       ") have different positions");
    }
    seen[static_cast<size_t>(node)] = 1;
    result.positions.row(node) = x;
  }
  for (int node = 0; node < nu * nv; ++node) {
    if (!seen[static_cast<size_t>(node)]) {
      const auto [i, j] = result.grid.node(node);
      throw make_error("grid from mesh: no vertex at lattice point (", i, ", ", j, ") of ", nu,
                       " x ", nv, ", (u, v) = (", us.front() + i * spacing_u, ", ",
                       vs.front() + j * spacing_v, ")");
    }
  }
  return result;
}

GridFromMesh read_grid_from_mesh_file(const std::filesystem::path& path,
                                      double relative_tolerance) {
  const std::vector<TriangleMesh> meshes = import_meshes(path);
  if (meshes.size() != 1) {
    throw make_error(path.string(), ": expected one mesh for a grid, found ", meshes.size());
  }
  try {
    return grid_from_mesh(meshes.front(), relative_tolerance);
  } catch (const Error& error) {
    throw make_error(path.string(), ": ", error.what());
  }
}

}  // namespace dnurbs
