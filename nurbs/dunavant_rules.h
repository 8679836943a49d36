#pragma once
// Symmetric quadrature rules on the triangle: Dunavant, "High degree efficient symmetrical
// Gaussian quadrature rules for the triangle", International Journal for Numerical Methods in
// Engineering 21, 1985 (Table I, degrees 1..14), the integrators of the triangular D-NURBS
// model's mass, damping and stiffness matrices; and their composite form on a triangle split
// into s^2 congruent sub-triangles.
//
// The published table gives 15 digits. Each rule is polished once, when first used, by
// Gauss-Newton iteration in long double on its moment equations (every monomial u^i v^j,
// i + j <= degree, integrated exactly), keeping Dunavant's orbit structure; the polished rules
// integrate every monomial of their degree to round-off (tested to 1e-14).

#include <Eigen/Core>

namespace dnurbs {

/// Highest degree of the Dunavant rules provided.
inline constexpr int kMaxDunavantDegree = 14;

/// A quadrature rule on a triangle in barycentric form: the integral of f over a triangle T
/// with corners (a, b, c) is approximated by area(T) sum_g weights[g] f(l_0 a + l_1 b + l_2 c),
/// l = barycentric.row(g).
///
/// barycentric  #points by 3 barycentric coordinates (each row sums to 1)
/// weights      #points weights summing to 1
struct TriangleRule {
  int degree = 0;  ///< every polynomial of total degree <= degree is integrated exactly
  Eigen::MatrixX3d barycentric;
  Eigen::VectorXd weights;
  /// True if every point lies in the closed triangle (Dunavant's degree 11 rule has points
  /// outside) and every weight is positive (degrees 3 and 7 have a negative centroid weight).
  bool interior_and_positive = true;

  int point_count() const { return static_cast<int>(weights.size()); }
};

/// Dunavant's rule of exactly this degree (1..kMaxDunavantDegree), polished and cached
/// (thread-safe). Throws Error for other degrees.
const TriangleRule& dunavant_rule(int degree);

/// The Dunavant rule of lowest degree >= `degree` whose points are all inside the triangle and
/// whose weights are all positive (what mass matrices need: a positive rule keeps them
/// positive semi-definite, and points outside a domain triangle may lie outside the domain).
/// Throws Error if `degree` is outside 1..kMaxDunavantDegree.
const TriangleRule& interior_positive_dunavant_rule(int degree);

/// The rule applied on each of the s^2 sub-triangles of the triangle split uniformly
/// (subdivisions = s >= 1 per edge): exact for the same polynomials, and for piecewise
/// smooth integrands whose pieces are not aligned with the triangle the error shrinks with s.
TriangleRule subdivided_rule(const TriangleRule& rule, int subdivisions);

}  // namespace dnurbs
