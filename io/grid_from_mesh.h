#pragma once
// Grid surfaces (Terzopoulos, PDE) from an imported mesh: a mesh whose texture coordinates put
// its vertices on a regular (u, v) lattice (a scan resampled on a grid, or a mesh written by
// grid_triangle_mesh) gives the grid and the node positions of a rest shape.

#include <filesystem>

#include "dnurbs/surface/grid.h"
#include "dnurbs/surface/triangle_mesh.h"

namespace dnurbs {

/// A grid and its node positions (row k = node k = i + nu j).
struct GridFromMesh {
  Grid grid;
  NodePositions positions;
};

/// Reads the lattice from the mesh's uv: the distinct u values (closer than `relative_tolerance`
/// times the smallest gap count as one) must be equally spaced with a spacing h, the v values
/// too with the same h, and every (u_i, v_j) must carry a vertex; vertices repeated at one
/// (u, v) (exporters split them along seams) must agree in position to relative_tolerance times
/// the mesh's size and are merged. Grid(nu, nv, h) with u = u_0 + i h. Throws Error naming the
/// problem (no texture coordinates, fewer than 2 values along a direction, unequal spacings, a
/// missing or contradictory lattice vertex, a non-finite coordinate).
GridFromMesh grid_from_mesh(const TriangleMesh& mesh, double relative_tolerance = 1e-4);

/// grid_from_mesh of the only mesh of a file read through assimp (import_meshes); throws Error
/// naming the file if it cannot be read or holds other than one mesh.
GridFromMesh read_grid_from_mesh_file(const std::filesystem::path& path,
                                      double relative_tolerance = 1e-4);

}  // namespace dnurbs
