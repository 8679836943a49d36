#pragma once
// Knot vectors of B-spline bases: validation, span lookup, multiplicity and the non-empty spans
// over which every integral of dnurbs is a sum (Piegl & Tiller, The NURBS Book, ch. 2).

#include <cstddef>
#include <utility>
#include <vector>

namespace dnurbs {

/// Highest B-spline degree dnurbs supports; evaluation works in fixed-size storage of this size.
inline constexpr int kMaxDegree = 15;

/// Relative tolerance for round-off at the seam of a periodic knot vector. A period knot within
/// kPeriodicSeamTolerance * max(|t_p|, |t_{p+n}|, T) of the period start t_p or end t_{p+n} is
/// that seam knot (it is stored as exactly t_p or t_{p+n}), so that lists whose wrapped copies
/// t_i = t_{i+n} - T differ from the listed knots by round-off keep the seam multiplicity they
/// give. The same tolerance maps parameters at the seam onto the period start (wrap_to_period).
inline constexpr double kPeriodicSeamTolerance = 1e-12;

/// A non-decreasing knot vector for a B-spline basis of a given degree.
///
/// Open (the default): knots t_0..t_m with m + 1 = control_point_count + degree + 1; the domain
/// is [t_p, t_{m-p}]. Clamped vectors repeat the end knots p + 1 times.
///
/// Periodic: the basis of a closed curve with `control_point_count` distinct control points n.
/// The stored knots are one period [t_p, t_{p+n}] extended by p knots on each side with the same
/// spacing (n + 2p + 1 knots), and control point index k of the extended (wrapped) polygon is
/// distinct control point k mod n. Parameters outside the domain wrap around. The seam knot
/// t_p = t_{p+n} - T has the multiplicity (copies of t_p at the start of the period list) +
/// (copies of t_{p+n} at its end) - 1, at most p like every other knot.
class KnotVector {
 public:
  /// Open knot vector; throws Error naming the value if the knots are not finite, decrease,
  /// have an interior multiplicity above the degree, an end multiplicity above degree + 1, or
  /// are too few (fewer than 2 (degree + 1)), or if the degree is outside 1..kMaxDegree.
  KnotVector(int degree, std::vector<double> knots);

  /// Clamped knot vector with uniformly spaced interior knots over [start, end].
  static KnotVector clamped_uniform(int degree, int control_point_count, double start = 0.0,
                                    double end = 1.0);
  /// Clamped knot vector with the given breakpoints (strictly increasing, first and last are
  /// the domain ends); interior breakpoints get multiplicity 1.
  static KnotVector clamped_from_breakpoints(int degree, const std::vector<double>& breakpoints);
  /// Unclamped uniform knot vector t_i = i (domain [p, n]).
  static KnotVector uniform(int degree, int control_point_count);
  /// Periodic knot vector from the knots t_p..t_{p+n} of one period (n + 1 non-decreasing values
  /// for n distinct control points, n >= degree + 1, multiplicity at most degree also across
  /// the wrap). Knots within the seam tolerance (kPeriodicSeamTolerance) of the period start or
  /// end are snapped onto it, so round-off there neither reads as a decrease nor splits the seam
  /// knot. Throws Error naming the value for too few knots, a non-finite or decreasing knot, an
  /// empty period or a multiplicity above the degree.
  static KnotVector periodic(int degree, const std::vector<double>& period_knots);
  /// The knots t_p..t_{p+n} of one period (periodic vectors) or the whole vector (open ones).
  std::vector<double> period_knots() const;
  /// Periodic knot vector with n equal spans over [start, end].
  static KnotVector periodic_uniform(int degree, int control_point_count, double start = 0.0,
                                     double end = 1.0);

  int degree() const { return degree_; }
  bool is_periodic() const { return periodic_; }
  /// Number of distinct control points (coordinates) this basis drives.
  int control_point_count() const { return control_point_count_; }
  /// Number of basis functions, n for open vectors and n + p (wrapped) for periodic ones.
  int basis_count() const { return static_cast<int>(knots_.size()) - degree_ - 1; }
  const std::vector<double>& knots() const { return knots_; }
  double operator[](int i) const { return knots_[static_cast<std::size_t>(i)]; }
  int size() const { return static_cast<int>(knots_.size()); }

  double domain_start() const { return knots_[static_cast<std::size_t>(degree_)]; }
  double domain_end() const {
    return knots_[knots_.size() - 1 - static_cast<std::size_t>(degree_)];
  }
  /// True if every knot of the two vectors agrees exactly and both have the same kind.
  bool operator==(const KnotVector& other) const = default;

  /// Maps a parameter into the domain: periodic vectors wrap, open ones throw Error if u is
  /// outside [domain_start, domain_end] by more than a relative 1e-12 (then u is clamped).
  double to_domain(double u) const;
  /// Periodic vectors: u wrapped into [domain_start, domain_end), with parameters within the seam
  /// tolerance of either end of the period (kPeriodicSeamTolerance) mapped onto domain_start
  /// exactly. Open vectors: to_domain(u).
  double wrap_to_period(double u) const;
  /// Knot t_i of the bi-infinite periodic sequence for any integer i: t_{i+n} = t_i + T, and the
  /// copies of the seam knot are exactly t_p + k T for every period k (with t_p + T = t_{p+n}),
  /// so multiplicities are the same in every period. Equals knots()[i] for 0 <= i < size().
  /// Open vectors: knots()[i], and Error if i is outside 0..size()-1.
  double extended_knot(int i) const;
  /// Index k of the knot span [t_k, t_{k+1}) that contains u (after to_domain), with
  /// p <= k < basis_count() and t_k < t_{k+1}; u at the domain end gives the last non-empty span.
  int find_span(double u) const;
  /// Number of knots equal to u.
  int multiplicity(double u) const;
  /// Indices k of the non-empty spans of the domain, in increasing order.
  std::vector<int> non_empty_spans() const;
  /// Distinct control point driven by basis function j (0..p) of span k.
  int control_point_index(int span, int j) const {
    const int index = span - degree_ + j;
    return periodic_ ? index % control_point_count_ : index;
  }

 private:
  struct PeriodicTag {};
  KnotVector(PeriodicTag, int degree, const std::vector<double>& period_knots);
  void validate() const;
  /// Period knot x (a stored t_p..t_{p+n}) moved by `periods` periods, seam copies exact.
  double shifted_period_knot(double x, int periods) const;

  int degree_ = 0;
  bool periodic_ = false;
  int control_point_count_ = 0;
  std::vector<double> knots_;
};

}  // namespace dnurbs
