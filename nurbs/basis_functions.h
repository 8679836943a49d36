#pragma once
// B-spline basis functions and their derivatives (Piegl & Tiller A2.2 and A2.3), evaluated into
// fixed-capacity storage so that no evaluation allocates.

#include <Eigen/Core>

#include "dnurbs/nurbs/knot_vector.h"

namespace dnurbs {

/// Highest derivative order the fixed-capacity tables hold (higher derivatives of a degree-p
/// basis are zero beyond order p, and p <= kMaxDegree).
inline constexpr int kMaxDerivativeOrder = kMaxDegree;

/// Values N_{k-p+j,p}(u), j = 0..p, of the p + 1 basis functions that are non-zero on span k.
using BasisValues = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxDegree + 1, 1>;

/// Row d holds the d-th derivatives of the p + 1 non-zero basis functions: (order + 1) by (p + 1).
using BasisDerivatives = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor,
                                       kMaxDerivativeOrder + 1, kMaxDegree + 1>;

/// Piegl & Tiller A2.2: the p + 1 non-zero basis functions at u of the span k = find_span(u).
void basis_functions(const KnotVector& knots, int span, double u, BasisValues& values);

/// Piegl & Tiller A2.3: the non-zero basis functions and their derivatives up to `order` at u of
/// span k. Rows above the degree are zero. Throws Error if order is outside 0..kMaxDerivativeOrder.
void basis_functions_with_derivatives(const KnotVector& knots, int span, double u, int order,
                                      BasisDerivatives& derivatives);

}  // namespace dnurbs
