#pragma once
// Triangulations of common parametric domains for triangular B-splines and triangular D-NURBS:
// rectangles, rectangles with cells removed (an L-shape, a square with a hole), and uniform
// refinement (every triangle split into four at its edge midpoints).

#include <functional>

#include <Eigen/Core>

#include "dnurbs/nurbs/triangulation.h"

namespace dnurbs {

/// How the cells of a rectangular grid are split into two triangles.
enum class DiagonalPattern {
  kUniform,     ///< every cell along the diagonal from (u0, v0) to (u1, v1)
  kAlternating  ///< the diagonal direction alternates like a checkerboard
};

/// The rectangle [lo, hi] split into cells_u by cells_v cells, each into two triangles.
/// Vertex (i, j) (i along u, j along v) is vertex i (cells_v + 1) + j. Throws Error for counts
/// < 1 or a rectangle with hi <= lo.
Triangulation rectangle_triangulation(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                      int cells_u, int cells_v,
                                      DiagonalPattern pattern = DiagonalPattern::kAlternating);

/// The cells (i, j) of that grid for which keep(i, j) is true, with the unused vertices removed
/// (vertices keep their grid order). Throws Error if no cell is kept or the kept cells do not
/// form a valid domain (Triangulation's checks, e.g. two cells touching only at a corner).
Triangulation grid_cells_triangulation(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                       int cells_u, int cells_v,
                                       const std::function<bool(int, int)>& keep,
                                       DiagonalPattern pattern = DiagonalPattern::kAlternating);

/// The L-shaped domain [0, 2]^2 minus (1, 2] x (1, 2], `cells` cells per unit length.
Triangulation l_shape_triangulation(int cells);

/// The square [0, 3]^2 with the square hole (1, 2)^2, `cells` cells per unit length.
Triangulation square_with_hole_triangulation(int cells);

/// Every triangle split into four at its edge midpoints (shared midpoints shared): the mesh
/// size halves. New vertices follow the old ones.
Triangulation refine_triangulation(const Triangulation& triangulation);

}  // namespace dnurbs
