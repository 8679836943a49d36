#pragma once
// Knot clouds of triangular B-splines (DMS splines: Dahmen, Micchelli & Seidel, "Blossoming
// begets B-spline bases built better by B-patches", Mathematics of Computation 59, 1992; Fong &
// Seidel, "An implementation of triangular B-spline surfaces over arbitrary triangulations",
// Computer Aided Geometric Design 10, 1993): for every vertex i of the domain triangulation a
// cloud of n + 1 knots t_{i,0} = vertex i, t_{i,1}, ..., t_{i,n} near it. Triangle I = (i, j, k)
// and multi-index beta (|beta| = n) give the knot set
//
//   V_beta^I = {t_{i,0..beta_0}, t_{j,0..beta_1}, t_{k,0..beta_2}}           (n + 3 knots).
//
// Conditions checked (check_knot_clouds), each with an Error naming the triangle and knots:
//  1. t_{i,0} is vertex i.
//  2. DMS condition (i): for every triangle I and every |beta| <= n the knot triangle
//     (t_{i,beta_0}, t_{j,beta_1}, t_{k,beta_2}) is non-degenerate and counter-clockwise like I
//     (its determinant d_beta^I is the normalization of the B-spline and must be > 0).
//  3. DMS condition (ii): the interior of the intersection of those knot triangles is not empty.
//  4. Boundary: the knots t_{j,1..n}, t_{k,1..n} of a boundary edge (j, k) lie strictly outside
//     the domain across that edge. Then the half-open convex hull of every "edge" knot set
//     {t_{j,0..a}, t_{k,0..b}} misses the domain, which is what makes the B-splines sum to one
//     on the whole domain: in the proof of the DMS identity by Micchelli's recurrence these
//     edge sets are the terms that cancel between the two triangles of an interior edge and are
//     left over on a boundary edge.
//  5. General position: no three knots of one triangle's 3 (n + 1) knots are collinear (relative
//     area above kGeneralPosition). Collinear knots would lower the smoothness below C^(n-1).

#include <Eigen/Core>

#include "dnurbs/nurbs/triangulation.h"

namespace dnurbs {

/// Highest degree of triangular B-splines supported: the knots of one triangle
/// (3 (n + 1)) must fit the 32-bit knot masks of SimplexSplineSet, and the recurrence graph
/// grows quickly with n (measured in the tests up to this degree).
inline constexpr int kMaxTriangularDegree = 6;

/// Settings of the standard knot placement (standard_knot_clouds).
struct KnotCloudSettings {
  /// Cloud radius as a fraction rho (0 < rho < 0.5) of the vertex's local size h_i, the smallest
  /// height at vertex i of the triangles around it: knot b (1..n) lies at distance
  /// rho h_i (1/2 + b / (2 n)) from the vertex. Moving each corner of a knot triangle by at most
  /// rho times its height changes its determinant by about 3 rho of itself to first order, so
  /// small rho keeps condition 2; check_knot_clouds decides. Larger clouds spread the knot
  /// segments (where the n-th derivatives jump) over the triangles instead of crowding them
  /// along the edges: the deflection error of the simply supported plate of degree 2 on 8 x 8
  /// cells is 3.7%, 2.9%, 2.3% and 1.6% for rho = 0.1, 0.2, 0.3 and 0.45 (the standard
  /// placement passes the checks up to 0.45 on the test domains for degrees 1..6). 0.3 leaves
  /// a margin for irregular triangulations.
  double radius = 0.3;
  /// Candidate rotations of the cloud tried per vertex (the best by knot quality is kept).
  int candidates = 24;
};

/// The knot clouds of a triangulation for degree n: knot b of vertex i is row i (n + 1) + b.
class TriangularKnotClouds {
 public:
  /// Relative area below which three knots count as collinear (condition 5) and a knot
  /// triangle as degenerate (condition 2): 2 area / (longest side)^2.
  static constexpr double kGeneralPosition = 1e-9;

  /// `knots` has triangulation.vertex_count() (degree + 1) rows. Checks sizes, finiteness and
  /// t_{i,0} = vertex i (throws Error); the DMS conditions are checked by check_knot_clouds.
  TriangularKnotClouds(const Triangulation& triangulation, int degree, Eigen::MatrixX2d knots);

  int degree() const { return degree_; }
  int vertex_count() const { return static_cast<int>(knots_.rows()) / (degree_ + 1); }
  /// t_{i,b}.
  Eigen::Vector2d knot(int vertex, int b) const { return knots_.row(vertex * (degree_ + 1) + b); }
  /// All knots, #V (n + 1) by 2.
  const Eigen::MatrixX2d& knots() const { return knots_; }

 private:
  int degree_ = 0;
  Eigen::MatrixX2d knots_;
};

/// The standard placement: t_{i,0} = vertex i; t_{i,1..n} at the distances of
/// KnotCloudSettings::radius, at angles spread by the golden ratio over the allowed range: the
/// full circle at an interior vertex, the outside wedge (where both boundary edges at the
/// vertex have the vertex's knots on their outer side) at a boundary vertex, with 15% of the
/// wedge kept free at each side. Of `candidates` rotations of the angles, the one that maximizes
/// the smallest relative area of the knot triples it forms with the clouds already placed is
/// kept. Throws Error for a degree outside 1..kMaxTriangularDegree or a bad setting; the result
/// satisfies check_knot_clouds (it is checked).
TriangularKnotClouds standard_knot_clouds(const Triangulation& triangulation, int degree,
                                          const KnotCloudSettings& settings = {});

/// Checks conditions 1-5 above; throws Error naming the first violation.
void check_knot_clouds(const Triangulation& triangulation, const TriangularKnotClouds& clouds);

}  // namespace dnurbs
