#pragma once
// The simplicial ACID of T-surfaces: a grid of cubes, each split into 6 tetrahedra around its main
// diagonal (the Freudenthal / Kuhn triangulation; Terzopoulos, Deformable Models: Classic,
// Topology-Adaptive and Generalized Formulations, section 3.2; McInerney & Terzopoulos,
// Topology adaptive deformable surfaces for medical image volume segmentation, IEEE TMI 18(10)
// 1999).

#include <array>

#include <Eigen/Core>

namespace dnurbs {

/// A grid of cells_x by cells_y by cells_z cubes of side cell_size from `origin`. Cube (i, j, k)
/// is split into the 6 tetrahedra {g, g + e_a, g + e_a + e_b, g + (1, 1, 1)} for the 6 orders
/// (a, b, c) of the axes (g = (i, j, k)); the split is the same in every cube, so the faces match.
///
/// Vertices (i, j, k), 0 <= i <= cells_x etc., at origin + cell_size (i, j, k), indexed
/// i + (cells_x + 1) (j + (cells_y + 1) k). Edges come in 7 families, the steps (1,0,0), (0,1,0),
/// (0,0,1), (1,1,0), (1,0,1), (0,1,1), (1,1,1); edge id = family * vertex_count + index of its
/// first vertex (the one with the smaller coordinates).
class TetrahedralGrid {
 public:
  static constexpr int kFamilies = 7;

  /// Throws Error naming the value for a cell size that is not positive and finite, an origin that
  /// is not finite, fewer than 2 cells per side, or over 2^24 vertices.
  TetrahedralGrid(const Eigen::Vector3d& origin, double cell_size, const Eigen::Vector3i& cells);

  const Eigen::Vector3d& origin() const { return origin_; }
  double cell_size() const { return cell_size_; }
  const Eigen::Vector3i& cells() const { return cells_; }
  int vertex_count() const { return (cells_.x() + 1) * (cells_.y() + 1) * (cells_.z() + 1); }
  int vertex_index(const Eigen::Vector3i& g) const {
    return g.x() + (cells_.x() + 1) * (g.y() + (cells_.y() + 1) * g.z());
  }
  bool on_border(const Eigen::Vector3i& g) const;
  Eigen::Vector3d vertex_position(const Eigen::Vector3i& g) const {
    return origin_ + cell_size_ * g.cast<double>();
  }
  /// (p - origin) / cell_size.
  Eigen::Vector3d to_grid(const Eigen::Vector3d& point) const {
    return (point - origin_) / cell_size_;
  }
  /// The step of an edge family (components 0 or 1).
  static Eigen::Vector3i direction(int family);
  /// The family of a step between neighboring vertices (either sign); -1 if it is none.
  static int family_of(const Eigen::Vector3i& step);
  int edge_id(int family, const Eigen::Vector3i& first) const {
    return family * vertex_count() + vertex_index(first);
  }
  /// The 6 tetrahedra of cube g, as grid vertex coordinates.
  static std::array<std::array<Eigen::Vector3i, 4>, 6> cube_tetrahedra(const Eigen::Vector3i& g);

 private:
  Eigen::Vector3d origin_;
  double cell_size_;
  Eigen::Vector3i cells_;
};

}  // namespace dnurbs
