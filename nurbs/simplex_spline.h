#pragma once
// Bivariate simplex splines M(u | V) of knot sets V in the plane, evaluated with their first
// and second derivatives by Micchelli's recurrence (C. A. Micchelli, "On a numerically efficient
// method for computing multivariate B-splines", in Multivariate Approximation Theory, 1979;
// Dahmen, Micchelli & Seidel, "Blossoming begets B-spline bases built better by B-patches",
// Mathematics of Computation 59, 1992, section 2):
//
//   M(u | V) = sum_l lambda_l(u | W) M(u | V \ {w_l}),             |V| = m + 3 > 3,
//   D_y M(u | V) = m sum_l mu_l(y | W) M(u | V \ {w_l}),
//   M(u | {v0, v1, v2}) = chi_[v0, v1, v2)(u) / |det(v0, v1, v2)|,
//
// where W = {w_0, w_1, w_2} is any affinely independent triple of V, lambda(u | W) are the
// barycentric coordinates of u and mu(y | W) those of the direction y (they sum to 0), and
// det(v0, v1, v2) = det[[1, 1, 1], [v0, v1, v2]] is twice the signed area. With this
// normalization (Seidel's, "Polar forms and triangular B-spline surfaces", 1992) the integral of
// a degree-m simplex spline is 1 / ((m + 1)(m + 2)).
//
// The recurrence branches three ways per degree; evaluated naively it costs 3^m. Here every
// knot subset reached from the requested sets is a node of a directed acyclic graph built once
// (the choice of W depends only on the knots), and one evaluation visits each node once.
//
// Half-open convention: chi_[v0, v1, v2) is 1 where u + eps d + eps^2 d_perp lies inside the
// triangle for every small eps > 0 (d the evaluation direction, d_perp it turned by +90
// degrees). Points within the snap tolerance of an edge line count as on it. The side of each
// edge is computed from its lexicographically smaller end, so two triangles that share an edge
// decide a point on it in opposite ways, exactly: every point of a tiling is in exactly one
// half-open triangle, and the splines are the limits of their polynomial pieces from direction d.

#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace dnurbs {

/// +1 if u + eps d + eps^2 d_perp lies strictly left of the directed line p -> q for every
/// small eps > 0, -1 if right (see the half-open convention above). `tolerance` is the distance
/// from the line within which u counts as on it. Antisymmetric: half_open_side(q, p, ...) is
/// exactly -half_open_side(p, q, ...).
int half_open_side(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& u,
                   const Eigen::Vector2d& direction, double tolerance);

/// An edge p -> q prepared for repeated half-open side tests: its lexicographically smaller end
/// `origin`, the vector to the other end, its length and the orientation sign (+1 if p is the
/// smaller end). side(u, ...) equals half_open_side(p, q, u, ...).
struct HalfOpenEdge {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  Eigen::Vector2d edge = Eigen::Vector2d::Zero();
  double length = 0.0;
  double sign = 1.0;

  HalfOpenEdge() = default;
  HalfOpenEdge(const Eigen::Vector2d& p, const Eigen::Vector2d& q);
  int side(const Eigen::Vector2d& u, const Eigen::Vector2d& direction, double tolerance) const;
};

/// Twice the signed area of the triangle (a, b, c): positive if counter-clockwise.
inline double signed_double_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                 const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

/// Highest derivative order of SimplexSplineSet::evaluate_derivatives.
inline constexpr int kMaxSimplexDerivativeOrder = 8;

/// Number of partial derivatives of total order <= order: (order + 1)(order + 2) / 2.
inline constexpr int derivative_count(int order) {
  return (order + 1) * (order + 2) / 2;
}

/// Row of d^(a+b) / du^a dv^b in derivative tables: by total order k = a + b, then b; so
/// value, d/du, d/dv, d2/du2, d2/dudv, d2/dv2, d3/du3, ... (the first six are the order of
/// SurfaceQuantity).
inline constexpr int derivative_index(int a, int b) {
  return (a + b) * (a + b + 1) / 2 + b;
}

/// Simplex splines of up to 32 knots, the sets requested at construction, evaluated together.
///
/// knots  K by 2 knot positions (K <= 32); a knot set is a bit mask over them
/// sets   the requested knot sets (each of >= 3 knots); spline s is M(u | sets[s])
///
/// Knots must be in general position where the recurrence needs it: a set whose knots are all
/// collinear is the zero function (a measure on a line, zero almost everywhere); any other set
/// of >= 4 knots has an affinely independent triple. The triple W of each set is chosen once:
/// the last knot (highest index) of each of three `groups` when the set meets exactly three
/// groups (the knot clouds of a triangle: a DMS knot set minus one of these is again a DMS knot
/// set, so the sets of one triangle share most of their graph), else the triple of largest
/// area (small barycentric coordinates near the set keep the cancellation small). Barycentric
/// coordinates are computed from the differences w - u, so round-off stays near 1e-16 relative
/// (partition of unity to 1e-15 measured up to degree 6).
class SimplexSplineSet {
 public:
  /// `group[k]` is the group of knot k (or empty: no groups). Throws Error for more than 32
  /// knots, an empty set, a set with fewer than 3 knots or a knot index out of range.
  SimplexSplineSet(const Eigen::MatrixX2d& knots, const std::vector<std::uint32_t>& sets,
                   const std::vector<int>& group = {});

  int knot_count() const { return static_cast<int>(knots_.rows()); }
  int set_count() const { return static_cast<int>(roots_.size()); }
  /// Nodes of the recurrence graph (distinct knot subsets, including the zero functions).
  int node_count() const { return static_cast<int>(nodes_.size()); }

  /// M(u | sets[s]) and its derivatives up to `order` (0..2) for every set s, as columns of
  /// `result` (6 by set_count(); rows beyond the order are zero). `direction` (non-zero) selects
  /// the polynomial piece on knot lines through u; `tolerance` is the snap distance.
  void evaluate(const Eigen::Vector2d& u, const Eigen::Vector2d& direction, double tolerance,
                int order, Eigen::Matrix<double, 6, Eigen::Dynamic>& result) const;
  /// The same with caller-owned scratch storage (resized as needed), so that repeated
  /// evaluation does not allocate.
  void evaluate(const Eigen::Vector2d& u, const Eigen::Vector2d& direction, double tolerance,
                int order, Eigen::Matrix<double, 6, Eigen::Dynamic>& result,
                std::vector<double>& scratch) const;
  /// Every partial derivative d^(a+b) M / du^a dv^b with a + b <= order (0..
  /// kMaxSimplexDerivativeOrder): result is derivative_count(order) by set_count(), row
  /// derivative_index(a, b). Derivatives beyond a spline's degree are zero (its pieces are
  /// polynomials of that degree).
  void evaluate_derivatives(const Eigen::Vector2d& u, const Eigen::Vector2d& direction,
                            double tolerance, int order, Eigen::MatrixXd& result,
                            std::vector<double>& scratch) const;

 private:
  struct Node {
    std::uint32_t mask = 0;
    int degree = 0;  // |set| - 3
    // Leaves (degree 0): corners in counter-clockwise order and 1 / |det|.
    // Inner nodes: the triple W (knot indices) and its three children V \ {w_l} (-1: zero).
    int knot[3] = {-1, -1, -1};
    int child[3] = {-1, -1, -1};
    double leaf_value = 0.0;
    // Inner nodes: 1 / det(W), and mu_l(e_u | W), mu_l(e_v | W) (the barycentric coordinates of
    // the unit directions). lambda_l(u | W) is evaluated as det(u, w_l+1, w_l+2) / det(W) from the
    // differences w - u, which loses far less to cancellation than an affine map in absolute
    // coordinates when W is small or far from u.
    double inverse_det = 0.0;
    double mu_u[3] = {0.0, 0.0, 0.0};
    double mu_v[3] = {0.0, 0.0, 0.0};
    // Bounding box of the knots (the spline and its derivatives vanish outside it) and, for
    // leaves, the three edges prepared for the half-open test.
    Eigen::Vector2d box_min = Eigen::Vector2d::Zero();
    Eigen::Vector2d box_max = Eigen::Vector2d::Zero();
    HalfOpenEdge edges[3];
  };

  int build(std::uint32_t mask, std::unordered_map<std::uint32_t, int>& index);
  // All derivatives up to `order` of every node into scratch (derivative_count(order) each).
  void evaluate_nodes(const Eigen::Vector2d& u, const Eigen::Vector2d& direction, double tolerance,
                      int order, std::vector<double>& scratch) const;
  void choose_triple(std::uint32_t mask, Node& node) const;

  Eigen::MatrixX2d knots_;
  std::vector<int> group_;
  std::vector<Node> nodes_;  // children before parents
  std::vector<int> roots_;   // node of each requested set (-1: the zero function)
};

}  // namespace dnurbs
