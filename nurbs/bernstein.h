#pragma once
// Polynomials in Bernstein form on [0, 1]: products, subdivision, sign changes and evaluation
// with derivatives (Farouki & Rajan, Algorithms for polynomials in Bernstein form, CAGD 5,
// 1988), the tools of the closest-point search's root isolation.

#include <array>

#include "dnurbs/nurbs/knot_vector.h"

namespace dnurbs {

/// Highest degree of a Bernstein polynomial these tools handle: the closest-point conditions
/// of a rational curve of degree p have degree 3p - 1.
inline constexpr int kMaxBernsteinDegree = 3 * kMaxDegree;

/// Binomial coefficient C(n, k) as a double (0 outside 0 <= k <= n).
double binomial_coefficient(int n, int k);

/// Weight of a_i b_j in coefficient i + j of the product of polynomials of degrees m and n in
/// Bernstein form: C(m, i) C(n, j) / C(m + n, i + j) (Farouki & Rajan eq. 7).
double bernstein_product_weight(int m, int i, int n, int j);

/// de Casteljau subdivision at t = 1/2 of the degree + 1 coefficients c[0], c[stride], ...:
/// `left` and `right` (same stride) get the coefficients over [0, 1/2] and [1/2, 1] mapped to
/// [0, 1]. `left` or `right` may alias `c`.
void split_bernstein_half(const double* c, int degree, int stride, double* left, double* right);

/// Number of sign changes of the coefficients, skipping those with |c| <= noise (Descartes'
/// rule of signs in Bernstein form bounds the roots in (0, 1) by it, with the same parity).
int bernstein_sign_changes(const double* c, int count, double noise);

/// The degree + 1 Bernstein basis functions B_{i,degree}(t), degree <= kMaxBernsteinDegree, into
/// values[0..degree] (the triangle B_{i,k} = (1 - t) B_{i,k-1} + t B_{i-1,k-1}).
void bernstein_values(int degree, double t, double* values);

/// Value at (s, t) of the tensor-product Bernstein polynomial with the (m + 1)(n + 1)
/// coefficients c (row i * (n + 1) + j for B_{i,m}(s) B_{j,n}(t)).
double bernstein_net_value(const double* c, int m, int n, double s, double t);

/// Bernstein basis functions of degree p at t with their first and second derivatives:
/// values[0][i] = B_{i,p}(t), values[1][i] = B'_{i,p}(t), values[2][i] = B''_{i,p}(t).
using BernsteinBasis = std::array<std::array<double, kMaxDegree + 1>, 3>;
void bernstein_basis(int degree, double t, BernsteinBasis& values);

}  // namespace dnurbs
