#pragma once
// Quadrature over the domain triangles of a triangular B-spline basis for the triangular
// D-NURBS model (Qin & Terzopoulos, "Triangular NURBS and their dynamic generalizations",
// Computer Aided Geometric Design 14, 1997, section 4: M, D and K as integrals over the
// parametric domain), with the non-zero B-splines cached for every point (they depend only on
// the knots, never on the state): on a polynomial cell every B-spline is one polynomial of
// degree n, so the cache holds its Taylor coefficients at the cell's centroid (all derivatives
// up to order n from the recurrence) and the values and derivatives at the cell's points are
// polynomial evaluations.
//
// DMS splines are polynomials of degree n on the cells of the partition of the plane by the
// segments between knots, which do not follow the domain triangles: every domain triangle is
// crossed by knot segments near its edges and corners, and across them the n-th derivatives
// jump. Two modes:
//  - exact (subdivisions = 0, the default of the model): a Dunavant rule of degree d on every
//    triangle of the fan of every polynomial cell (nurbs/triangular_polynomial_cells.h), exact
//    for every integrand that is a polynomial of degree <= d on each cell: M, D and forces of
//    polynomial densities for non-rational surfaces (d = 2n), K (degree 2n - 2);
//  - composite (subdivisions = s >= 1): the rule on s^2 congruent sub-triangles of every domain
//    triangle, blind to the cells. Measured against the exact mode (degree 2, unit square of
//    4 x 4 cells, standard clouds, rule of degree 4; test_triangular_quadrature.cpp): relative
//    errors of M / K of 0.16 / 0.90 at s = 1, 0.057 / 0.45 at s = 2, 0.018 / 0.38 at s = 4 and
//    0.0021 / 0.096 at s = 8. K's integrand jumps across the knot segments, so its error falls
//    only like 1/s: the composite mode is for comparison and quick previews, not accuracy.
//
// The exact mode costs about 56 (n = 2, 16 x 16 grid), 150 (n = 3, 8 x 8) and 300 (n = 4,
// 4 x 4) cells per domain triangle, i.e. about 580, 3400 and 9100 points at d = 2n; the cache
// holds one Taylor polynomial per cell and non-zero B-spline (not values per point), and
// building it (one recurrence evaluation per cell) takes 0.3 s for the 512 triangles of the
// degree-2 16 x 16 grid.

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/quadrature_assembly.h"
#include "dnurbs/nurbs/dunavant_rules.h"
#include "dnurbs/nurbs/triangular_bspline_basis.h"

namespace dnurbs {

/// Quadrature points of all domain triangles and the B-splines cached at them.
class TriangularQuadrature {
 public:
  /// `degree`: the Dunavant rule (interior_positive_dunavant_rule(degree), 1..14) applied on the
  /// fan triangles of the polynomial cells (subdivisions = 0) or on `subdivisions` (1..64)
  /// sub-triangles per edge; derivatives cached up to `order` (0..2). Throws Error for values
  /// out of range.
  TriangularQuadrature(std::shared_ptr<const TriangularBSplineBasis> basis, int degree,
                       int subdivisions, int order);

  const TriangularBSplineBasis& basis() const { return *basis_; }
  int element_count() const { return static_cast<int>(element_functions_.size()); }
  int point_count() const { return static_cast<int>(parameter_.size()); }
  /// Points of element e (domain triangle e) are element_begin(e) .. element_begin(e + 1) - 1.
  int element_begin(int e) const { return element_begin_[static_cast<size_t>(e)]; }
  /// Parameter and weight (rule weight times sub-triangle area) of a point.
  const Eigen::Vector2d& parameter(int point) const {
    return parameter_[static_cast<size_t>(point)];
  }
  double weight(int point) const { return weight_[static_cast<size_t>(point)]; }
  /// The domain triangle of a point.
  int element_of(int point) const { return element_of_[static_cast<size_t>(point)]; }
  /// The B-splines of element e (of the triangles that overlap it): local index -> function.
  const std::vector<int>& element_functions(int e) const {
    return element_functions_[static_cast<size_t>(e)];
  }
  /// Largest number of B-splines of one element.
  int max_local_count() const { return max_local_count_; }
  /// Derivative order cached.
  int order() const { return order_; }

  /// The non-zero B-splines at a point: `values` lists them (global function indices, 6 rows
  /// of derivatives up to order()), `local` their local indices in the element's list.
  void basis_at(int point, TriangularBasisValues& values, std::vector<int>& local) const;

  /// The node-to-node pattern of the element couplings (every element padded to
  /// max_local_count() with repeats of its first B-spline, which get zero values).
  AssemblyPattern assembly_pattern() const;

  /// Doubles held by the B-spline cache (Taylor coefficients), for cost reports.
  size_t cached_coefficient_count() const { return entry_coefficient_.size(); }

 private:
  // Adds a piece: the Taylor coefficients at `origin` of the B-splines of element e that do not
  // vanish there (pieces of the limit from `direction`); returns its index.
  int add_piece(int e, const Eigen::Vector2d& origin, const Eigen::Vector2d& direction);
  void add_point(int e, int piece, const Eigen::Vector2d& u, double weight);

  std::shared_ptr<const TriangularBSplineBasis> basis_;
  int order_ = 0;
  int max_local_count_ = 0;
  std::vector<std::vector<int>> element_functions_;
  std::vector<int> element_begin_;
  std::vector<int> element_of_;
  std::vector<Eigen::Vector2d> parameter_;
  std::vector<double> weight_;
  // The cache: piece of each point, and per piece (a polynomial cell, or a single point of the
  // composite rule) its origin and its non-zero B-splines, entries piece_begin_[c] ..
  // piece_begin_[c + 1] - 1 of entry_local_ (local index in the element's list) and
  // entry_coefficient_ (derivative_count(taylor_order_) Taylor coefficients each,
  // d^(a+b) N / du^a dv^b / (a! b!) at the origin, in derivative_index order).
  int taylor_order_ = 0;
  std::vector<int> point_piece_;
  std::vector<Eigen::Vector2d> piece_origin_;
  std::vector<int> piece_begin_;
  std::vector<int> entry_local_;
  std::vector<double> entry_coefficient_;
};

}  // namespace dnurbs
