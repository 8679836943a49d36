#pragma once
// The nearest point of a NURBS curve to a query point, found with a guarantee: the curve is cut
// into its Bezier segments; a segment whose control points' bounding box is farther than the
// best distance found so far cannot hold a nearer point (a rational segment with positive
// weights lies in the convex hull of its projected control points), and in every other segment
// the stationary points of the squared distance are isolated exactly as sign changes of a
// polynomial in Bernstein form, then polished by bracketed Newton. Segment ends are candidates
// too where the minimum can sit without being stationary: the curve's ends and C^0 knots.

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/nurbs/bernstein.h"
#include "dnurbs/nurbs/nearest_candidate.h"
#include "dnurbs/nurbs/nurbs_curve.h"

namespace dnurbs {

/// The nearest point of a curve: its parameter, the point C(parameter) and |C - Q|.
struct CurveProjection {
  double parameter = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance = 0.0;
};

/// A curve prepared for many closest-point queries: per non-empty span its Bezier segment
/// (homogeneous, (p + 1) by 4), the bounding box of its projected control points and the
/// Bernstein coefficients of the stationarity condition (C - Q).C' = 0 (times w^3 > 0) split as
/// e_k - Q.f_k, so that a query costs O(#spans) bound tests plus O(p^2) per segment it cannot
/// exclude. Built once (O(#spans p^3)); the projector is immutable afterwards, so one projector
/// may serve queries from several threads. It keeps its own copy of the curve.
class CurveProjector {
 public:
  explicit CurveProjector(NurbsCurve curve);

  const NurbsCurve& curve() const { return curve_; }
  /// Diagonal of the bounding box of the control points.
  double scale() const { return scale_; }

  /// The globally nearest curve point to `point` (finite, else Error). Ties (distances within
  /// kProjectionTieTolerance, nearest_candidate.h) go to the smallest parameter; periodic curves
  /// report parameters in [domain_start, domain_end). `point` and `distance` are those of
  /// curve().point(parameter).
  CurveProjection closest_point(const Eigen::Vector3d& point) const;

  /// The nearest curve point if it is nearer than `bound` (plus the tie tolerance), else
  /// nothing; segments farther than `bound` are not examined.
  std::optional<CurveProjection> closest_point_within(const Eigen::Vector3d& point,
                                                      double bound) const;

  /// Point inversion: the parameter of a point on the curve, to round-off (|du| |C'| ~ 1e-16
  /// times the curve's size). Throws Error naming the distance if `point` is farther than
  /// `tolerance` from the curve.
  double invert(const Eigen::Vector3d& point, double tolerance) const;

 private:
  /// One Bezier segment over [start, end] and its stationarity polynomial g = e - Q.f.
  struct Segment {
    double start = 0.0;
    double end = 0.0;
    Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor, kMaxDegree + 1, 4> homogeneous;
    Eigen::Vector3d box_min = Eigen::Vector3d::Zero();
    Eigen::Vector3d box_max = Eigen::Vector3d::Zero();
    std::array<double, kMaxBernsteinDegree + 1> e{};
    std::array<Eigen::Vector3d, kMaxBernsteinDegree + 1> f{};
    double e_magnitude = 0.0;  ///< max |e_k|
    double f_magnitude = 0.0;  ///< max |f_k|
    /// The segment's start / end is an end of an open curve or a C^0 knot (multiplicity >= p):
    /// the minimum may sit there without being stationary.
    bool start_is_corner = false;
    bool end_is_corner = false;
  };
  using Best = NearestCandidate<double>;
  /// A point of a segment: C, C', C'' at local parameter t in [0, 1].
  struct SegmentPoint {
    Eigen::Vector3d point;
    Eigen::Vector3d first;
    Eigen::Vector3d second;
  };

  void build_segment(int span, const Eigen::MatrixXd& homogeneous_rows);
  SegmentPoint evaluate(const Segment& segment, double t) const;
  void consider(const Segment& segment, double t, const Eigen::Vector3d& point,
                const Eigen::Vector3d& query, bool exact, Best& best) const;
  void search_segment(const Segment& segment, const Eigen::Vector3d& query, Best& best) const;
  void isolate(const Segment& segment, const Eigen::Vector3d& query, const double* coefficients,
               double noise, double low, double high, int depth, Best& best) const;
  double solve_bracketed(const Segment& segment, const Eigen::Vector3d& query, double low,
                         double high) const;

  NurbsCurve curve_;
  /// Degree of the stationarity polynomial: 3p - 1 (rational) or 2p - 1 (polynomial).
  int condition_degree_ = 0;
  double scale_ = 0.0;
  std::vector<Segment> segments_;
};

}  // namespace dnurbs
