#pragma once
// The Coxeter-Freudenthal triangulation of a square grid: the affine cell image decomposition
// (ACID) on which T-snakes are reparameterized (McInerney & Terzopoulos, T-snakes: Topology
// adaptive snakes, Medical Image Analysis 4(2) 2000; Terzopoulos, Deformable Models:
// Classic, Topology-Adaptive and Generalized Formulations, section 3.1, Fig. 4(a)).

#include <array>

#include <Eigen/Core>

namespace dnurbs {

/// A grid of cells_x by cells_y square cells of side cell_size, from `origin`; every cell is split
/// by its diagonal from (i, j) to (i + 1, j + 1) into two triangles, the same in every cell.
///
/// Vertices (i, j), 0 <= i <= cells_x, 0 <= j <= cells_y, at origin + cell_size (i, j), indexed
/// i + (cells_x + 1) j. Edges come in three families, each named by its first vertex (i, j):
/// kHorizontal to (i + 1, j), kVertical to (i, j + 1), kDiagonal to (i + 1, j + 1); the edge id is
/// family * vertex_count + vertex index. Triangles of cell (i, j), counter-clockwise in (x, y):
/// {(i, j), (i + 1, j), (i + 1, j + 1)} and {(i, j), (i + 1, j + 1), (i, j + 1)}.
class FreudenthalGrid {
 public:
  enum Family { kHorizontal = 0, kVertical = 1, kDiagonal = 2 };

  /// Throws Error naming the value for a cell size that is not positive and finite, an origin
  /// that is not finite, fewer than 2 cells per side, or over 2^24 vertices.
  FreudenthalGrid(const Eigen::Vector2d& origin, double cell_size, int cells_x, int cells_y);

  const Eigen::Vector2d& origin() const { return origin_; }
  double cell_size() const { return cell_size_; }
  int cells_x() const { return cells_x_; }
  int cells_y() const { return cells_y_; }
  int vertex_count() const { return (cells_x_ + 1) * (cells_y_ + 1); }
  int vertex_index(int i, int j) const { return i + (cells_x_ + 1) * j; }
  bool on_border(int i, int j) const { return i == 0 || j == 0 || i == cells_x_ || j == cells_y_; }
  Eigen::Vector2d vertex_position(int i, int j) const {
    return origin_ + cell_size_ * Eigen::Vector2d(i, j);
  }
  /// (p - origin) / cell_size: the point in grid units, vertex (i, j) at (i, j).
  Eigen::Vector2d to_grid(const Eigen::Vector2d& point) const {
    return (point - origin_) / cell_size_;
  }
  /// The unit step of an edge family in grid units: (1, 0), (0, 1) or (1, 1).
  static Eigen::Vector2i direction(int family) {
    return family == kHorizontal
               ? Eigen::Vector2i(1, 0)
               : (family == kVertical ? Eigen::Vector2i(0, 1) : Eigen::Vector2i(1, 1));
  }
  int edge_id(int family, int i, int j) const {
    return family * vertex_count() + vertex_index(i, j);
  }
  /// The id of the grid edge joining two vertices that differ by a step of one family (in either
  /// order); the caller guarantees they are neighbors.
  int edge_between(const Eigen::Vector2i& a, const Eigen::Vector2i& b) const;
  /// The two counter-clockwise triangles of cell (i, j), as grid vertex coordinates.
  std::array<std::array<Eigen::Vector2i, 3>, 2> cell_triangles(int i, int j) const;

 private:
  Eigen::Vector2d origin_;
  double cell_size_;
  int cells_x_;
  int cells_y_;
};

}  // namespace dnurbs
