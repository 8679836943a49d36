#pragma once
// A triangulation of a planar parametric domain: the domain of triangular B-splines and
// triangular NURBS (Dahmen, Micchelli & Seidel, "Blossoming begets B-spline bases built better
// by B-patches", Mathematics of Computation 59, 1992; Qin & Terzopoulos, "Triangular NURBS and
// their dynamic generalizations", Computer Aided Geometric Design 14, 1997). Connectivity
// (triangles, edge neighbours, vertex fans, the boundary) is kept beside the geometry (vertex
// positions), and point location uses a uniform bin grid built once.
//
// Points on shared edges and vertices belong to one triangle by the half-open convention: the
// triangle that contains u + eps d for a fixed generic direction d (kHalfOpenDirection) and
// every small eps > 0; on the domain boundary, where u + eps d may leave the domain, the lowest
// numbered closed triangle that contains u.

#include <array>
#include <vector>

#include <Eigen/Core>

namespace dnurbs {

/// A conforming triangulation of a planar domain (which may be non-convex and have holes).
///
/// vertices   #V by 2 positions (u, v)
/// triangles  #T by 3 vertex indices, counter-clockwise (positive signed area)
///
/// Validated at construction; violations throw Error naming the triangle, edge or vertex:
/// finite coordinates; indices in range; every triangle positively oriented and not degenerate
/// (area above kDegenerateArea times the squared length of its longest edge); every vertex used;
/// conforming: an edge is shared by at most two triangles, with opposite orientations, no vertex
/// lies inside another triangle or in the interior of an edge it does not end (no T-junctions),
/// no two edges cross; every boundary vertex has exactly one boundary edge in and one out (the
/// boundary is a set of simple closed polygons, so every vertex has one well-defined outside).
class Triangulation {
 public:
  /// Relative area below which a triangle counts as degenerate: 2 area / longest edge^2.
  static constexpr double kDegenerateArea = 1e-10;
  /// The generic direction of the half-open convention (not parallel to any axis or diagonal).
  static Eigen::Vector2d half_open_direction() { return {0.8191520442889918, 0.5735764363510461}; }

  Triangulation(Eigen::MatrixX2d vertices, Eigen::MatrixX3i triangles);

  int vertex_count() const { return static_cast<int>(vertices_.rows()); }
  int triangle_count() const { return static_cast<int>(triangles_.rows()); }
  const Eigen::MatrixX2d& vertices() const { return vertices_; }
  const Eigen::MatrixX3i& triangles() const { return triangles_; }
  Eigen::Vector2d vertex(int i) const { return vertices_.row(i).transpose(); }
  /// Corner c (0..2) of triangle t.
  Eigen::Vector2d corner(int t, int c) const { return vertex(triangles_(t, c)); }

  /// The triangle across edge e of triangle t (edge e joins corners e + 1 and e + 2, mod 3,
  /// opposite corner e), or -1 on the boundary.
  int neighbor(int t, int e) const { return neighbors_[static_cast<size_t>(3 * t + e)]; }
  /// The triangles that have vertex i as a corner, counter-clockwise around it.
  const std::vector<int>& vertex_triangles(int i) const {
    return vertex_triangles_[static_cast<size_t>(i)];
  }
  bool is_boundary_vertex(int i) const { return boundary_next_[static_cast<size_t>(i)] >= 0; }
  /// For a boundary vertex i, the vertices after and before it along the boundary (the domain on
  /// the left of previous -> i -> next); -1 for interior vertices.
  int boundary_next(int i) const { return boundary_next_[static_cast<size_t>(i)]; }
  int boundary_previous(int i) const { return boundary_previous_[static_cast<size_t>(i)]; }
  /// Boundary edges (a, b) with the domain on their left, #boundary edges by 2.
  Eigen::MatrixX2i boundary_edges() const;

  /// Area of triangle t and of the whole domain.
  double area(int t) const;
  double domain_area() const { return domain_area_; }
  /// Length of the diagonal of the domain's bounding box.
  double diameter() const { return diameter_; }
  Eigen::Vector2d centroid(int t) const;
  /// Barycentric coordinates of u with respect to the corners of triangle t.
  Eigen::Vector3d barycentric(int t, const Eigen::Vector2d& u) const;

  /// The triangle whose closure contains u (the half-open convention picks one on shared edges
  /// and vertices), or -1 if u is outside the domain (farther than kLocateTolerance times the
  /// diameter). Uses the bin grid: about one triangle per bin is tested.
  int locate(const Eigen::Vector2d& u) const;
  /// Appends to `result` every triangle whose bounding box may overlap the box [lo, hi] (from
  /// the bin grid; a superset, possibly with repeats).
  void triangles_near_box(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                          std::vector<int>& result) const;
  /// Relative distance within which a point on the boundary still counts as inside.
  static constexpr double kLocateTolerance = 1e-12;

 private:
  void build_connectivity();
  void check_geometry() const;
  void build_bins();
  // Triangles whose bounding box overlaps the bins covering [lo, hi].
  template <typename Visit>
  void visit_bins(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, Visit visit) const;
  bool closed_contains(int t, const Eigen::Vector2d& u, double tolerance) const;
  bool half_open_contains(int t, const Eigen::Vector2d& u, double tolerance) const;

  Eigen::MatrixX2d vertices_;
  Eigen::MatrixX3i triangles_;
  std::vector<int> neighbors_;                      // 3 per triangle
  std::vector<std::vector<int>> vertex_triangles_;  // fan of each vertex, counter-clockwise
  std::vector<int> boundary_next_;                  // -1 for interior vertices
  std::vector<int> boundary_previous_;
  double domain_area_ = 0.0;
  double diameter_ = 0.0;
  // Bin grid for locate(): bins_x_ by bins_y_ bins over the bounding box; bin b holds the
  // triangles bin_triangles_[bin_start_[b] .. bin_start_[b + 1]).
  Eigen::Vector2d box_min_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d bin_size_ = Eigen::Vector2d::Ones();
  int bins_x_ = 1;
  int bins_y_ = 1;
  std::vector<int> bin_start_;
  std::vector<int> bin_triangles_;
};

}  // namespace dnurbs
