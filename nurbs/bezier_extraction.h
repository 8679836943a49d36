#pragma once
// Bezier extraction: the Bernstein control points of one non-empty knot span of a B-spline, or
// of one span pair of a tensor-product one (the blossoms at the span's ends; Ramshaw, Blossoms
// are polar forms, CAGD 6, 1989; Piegl & Tiller, The NURBS Book, A5.6 does the same by knot
// insertion).

#include <Eigen/Core>

#include "dnurbs/nurbs/knot_vector.h"

namespace dnurbs {

/// The p + 1 Bezier control rows of the non-empty span k = [t_k, t_{k+1}] of the B-spline with
/// knots `knots` and control rows `rows` (knots.control_point_count() by #columns; periodic
/// vectors wrap): row j is the blossom b(t_k^(p-j), t_{k+1}^j), computed by de Boor's recurrence
/// whose weights all lie in [0, 1]. Result (p + 1) by #columns. Throws Error if span k is not a
/// non-empty span of the domain.
Eigen::MatrixXd bezier_segment(const KnotVector& knots, const Eigen::MatrixXd& rows, int span);

/// The (p + 1) (q + 1) Bezier control rows of the span pair (span_u, span_v) of a tensor-product
/// B-spline whose control rows are stored with the u index outer (row i * count_v + j, as
/// NurbsSurface stores control points). Result (p + 1)(q + 1) by #columns, the u index outer.
Eigen::MatrixXd bezier_patch(const KnotVector& knots_u, const KnotVector& knots_v,
                             const Eigen::MatrixXd& rows, int span_u, int span_v);

}  // namespace dnurbs
