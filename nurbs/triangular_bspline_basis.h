#pragma once
// Triangular B-splines (DMS splines) of degree n over a triangulated planar domain (Dahmen,
// Micchelli & Seidel, "Blossoming begets B-spline bases built better by B-patches", Mathematics
// of Computation 59, 1992; Seidel, "Polar forms and triangular B-spline surfaces", in
// Computing in Euclidean Geometry, 1992; the basis of Qin & Terzopoulos, "Triangular NURBS and
// their dynamic generalizations", Computer Aided Geometric Design 14, 1997, eq. 1):
//
//   N_beta^I(u) = d_beta^I M(u | V_beta^I),   d_beta^I = det(t_{i,beta_0}, t_{j,beta_1},
//   t_{k,beta_2}),
//
// for every triangle I = (i, j, k) and |beta| = n, with the knot sets V_beta^I of
// triangular_knot_clouds.h and the simplex splines M of simplex_spline.h (Seidel's
// normalization, so that sum_I sum_beta N_beta^I = 1 on the domain). Every polynomial F of
// degree <= n is reproduced with the coefficients given by its blossom f:
//
//   F(u) = sum_I sum_beta f(t_{i,0..beta_0-1}, t_{j,0..beta_1-1}, t_{k,0..beta_2-1}) N_beta^I(u).
//
// The splines are piecewise polynomials of degree n, C^(n-1) for knots in general position,
// over the partition of the plane by all segments between knots of one knot set: not over the
// domain triangles (see the quadrature notes of the triangular D-NURBS model).
//
// What depends only on the knots is built once: per triangle, the recurrence graph of all its
// knot sets (SimplexSplineSet, shared subsets evaluated once per point), the normalizations,
// the convex hull of its knots (the union of its splines' supports) and the list of triangles
// it overlaps.

#include <array>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/nurbs/simplex_spline.h"
#include "dnurbs/nurbs/triangular_knot_clouds.h"
#include "dnurbs/nurbs/triangulation.h"

namespace dnurbs {

/// The B-splines that may be non-zero at one point, with derivatives: value(q, a) is quantity q
/// (0 N, 1 N_u, 2 N_v, 3 N_uu, 4 N_uv, 5 N_vv) of B-spline function[a]. The list is the same
/// for every point of one domain triangle (the splines of the triangles overlapping it), so
/// some values are zero. The scratch members are workspace that makes repeated evaluation
/// allocation-free.
struct TriangularBasisValues {
  int triangle = -1;  ///< the domain triangle the point was evaluated in
  int count = 0;      ///< number of B-splines listed
  std::vector<int> function;
  Eigen::Matrix<double, 6, Eigen::Dynamic> value;
  std::vector<double> scratch;
  Eigen::Matrix<double, 6, Eigen::Dynamic> simplex;
};

/// The triangular B-spline basis of a triangulation and its knot clouds.
///
/// B-spline numbering: function index I (n + 1)(n + 2)/2 + b for triangle I and local index b
/// of multi-index beta, with the multi-indices ordered (n, 0, 0), (n - 1, 1, 0),
/// (n - 1, 0, 1), (n - 2, 2, 0), ... (beta_0 descending, then beta_1 descending).
class TriangularBSplineBasis {
 public:
  /// Snap distance of the half-open convention, relative to the domain diameter: points closer
  /// to a knot line count as on it (well below any quadrature or tessellation spacing).
  static constexpr double kSnapTolerance = 1e-12;

  /// Checks the knot clouds (check_knot_clouds; throws Error naming the violation) and builds
  /// the per-triangle recurrence graphs.
  TriangularBSplineBasis(Triangulation triangulation, TriangularKnotClouds clouds);

  int degree() const { return clouds_.degree(); }
  /// (n + 1)(n + 2) / 2.
  int functions_per_triangle() const { return per_triangle_; }
  int function_count() const { return per_triangle_ * triangulation_.triangle_count(); }
  const Triangulation& triangulation() const { return triangulation_; }
  const TriangularKnotClouds& knot_clouds() const { return clouds_; }

  /// Multi-index of local index b (0..functions_per_triangle()-1) and the inverse.
  std::array<int, 3> multi_index(int b) const { return multi_indices_[static_cast<size_t>(b)]; }
  int local_index(const std::array<int, 3>& beta) const;
  /// The triangle of a B-spline.
  int triangle_of(int function) const { return function / per_triangle_; }
  /// d_beta^I of a B-spline (> 0).
  double normalization(int function) const { return normalization_[static_cast<size_t>(function)]; }
  /// V_beta^I, (n + 3) by 2.
  Eigen::MatrixX2d knot_set(int function) const;
  /// The n knots t_{i,0..beta_0-1}, t_{j,0..beta_1-1}, t_{k,0..beta_2-1} whose blossom is the
  /// B-spline's coefficient in the reproduction of a polynomial (n by 2).
  Eigen::MatrixX2d blossom_arguments(int function) const;
  /// The means of the blossom arguments, function_count() by 2: the coefficients that reproduce
  /// the identity map u -> u (the blossom of an affine map is the map of the mean).
  Eigen::MatrixX2d domain_points() const;
  /// Nodes of triangle t's recurrence graph (for cost reports and tests).
  int recurrence_node_count(int t) const { return splines_[static_cast<size_t>(t)].node_count(); }

  /// Triangles whose B-splines may be non-zero on triangle t (their knot hulls meet it), sorted.
  const std::vector<int>& overlapping_triangles(int t) const {
    return overlapping_[static_cast<size_t>(t)];
  }

  /// The B-splines at u with derivatives up to `order` (0..2), as the limit from inside the
  /// domain triangle that contains u (Triangulation::locate). Throws Error if u is outside the
  /// domain or order is outside 0..2.
  void evaluate(const Eigen::Vector2d& u, int order, TriangularBasisValues& values) const;
  /// The same as the limit from inside triangle t (u in or on t; on an edge or vertex this picks
  /// the side: the polynomial pieces are followed from u towards t's centroid). Lists the
  /// B-splines of overlapping_triangles(t).
  void evaluate_in_triangle(int t, const Eigen::Vector2d& u, int order,
                            TriangularBasisValues& values) const;
  /// The same with an explicit direction: the limit of the pieces at u + eps direction.
  void evaluate_in_triangle(int t, const Eigen::Vector2d& u, const Eigen::Vector2d& direction,
                            int order, TriangularBasisValues& values) const;
  /// Every partial derivative d^(a+b) N / du^a dv^b, a + b <= order (0..
  /// kMaxSimplexDerivativeOrder), of the B-splines of overlapping_triangles(t) at u from
  /// `direction`: `derivatives` is derivative_count(order) by count, row derivative_index(a, b),
  /// column k for B-spline functions[k]. With order n this is the whole polynomial piece at u.
  void derivatives_in_triangle(int t, const Eigen::Vector2d& u, const Eigen::Vector2d& direction,
                               int order, std::vector<int>& functions, Eigen::MatrixXd& derivatives,
                               std::vector<double>& scratch) const;

 private:
  void check_point(int t, const Eigen::Vector2d& u, const Eigen::Vector2d& direction) const;
  bool outside_knot_box(int s, const Eigen::Vector2d& u) const;

  Triangulation triangulation_;
  TriangularKnotClouds clouds_;
  int per_triangle_ = 0;
  std::vector<std::array<int, 3>> multi_indices_;
  std::vector<SimplexSplineSet> splines_;      // per triangle, sets in local order
  std::vector<double> normalization_;          // per function
  std::vector<Eigen::Vector4d> knot_box_;      // per triangle: min u, min v, max u, max v
  std::vector<std::vector<int>> overlapping_;  // per triangle
  double tolerance_ = 0.0;                     // snap distance
};

}  // namespace dnurbs
