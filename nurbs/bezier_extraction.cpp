#include "dnurbs/nurbs/bezier_extraction.h"

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

void check_span(const KnotVector& knots, int span) {
  if (span < knots.degree() || span >= knots.basis_count() || !(knots[span] < knots[span + 1])) {
    throw make_error("Bezier extraction: span ", span, " is not a non-empty span of the domain");
  }
}

// Bezier rows of span k from its p + 1 local control rows P_{k-p..k} (rows of `local`).
Eigen::MatrixXd bezier_from_local(const KnotVector& knots, const Eigen::MatrixXd& local, int span) {
  const int p = knots.degree();
  const double start = knots[span];
  const double end = knots[span + 1];
  Eigen::MatrixXd bezier(p + 1, local.cols());
  Eigen::MatrixXd work(p + 1, local.cols());
  for (int j = 0; j <= p; ++j) {
    // de Boor's recurrence with the arguments x_1..x_p = start (p - j times), end (j times):
    // d_i <- (1 - alpha) d_{i-1} + alpha d_i, alpha = (x_r - t_{k-p+i}) / (t_{k+1+i-r} -
    // t_{k-p+i}) in [0, 1] since t_{k-p+i} <= t_k <= x_r <= t_{k+1} <= t_{k+1+i-r}.
    work = local;
    for (int r = 1; r <= p; ++r) {
      const double x = r <= p - j ? start : end;
      for (int i = p; i >= r; --i) {
        const double low = knots[span - p + i];
        const double alpha = (x - low) / (knots[span + 1 + i - r] - low);
        work.row(i) = (1.0 - alpha) * work.row(i - 1) + alpha * work.row(i);
      }
    }
    bezier.row(j) = work.row(p);
  }
  return bezier;
}

}  // namespace

Eigen::MatrixXd bezier_segment(const KnotVector& knots, const Eigen::MatrixXd& rows, int span) {
  check_span(knots, span);
  const int p = knots.degree();
  Eigen::MatrixXd local(p + 1, rows.cols());
  for (int i = 0; i <= p; ++i) {
    local.row(i) = rows.row(knots.control_point_index(span, i));
  }
  return bezier_from_local(knots, local, span);
}

Eigen::MatrixXd bezier_patch(const KnotVector& knots_u, const KnotVector& knots_v,
                             const Eigen::MatrixXd& rows, int span_u, int span_v) {
  check_span(knots_u, span_u);
  check_span(knots_v, span_v);
  const int p = knots_u.degree();
  const int q = knots_v.degree();
  const int count_v = knots_v.control_point_count();
  const Eigen::Index columns = rows.cols();
  // Along v for each of the p + 1 local u rows, then along u for each Bezier v index.
  Eigen::MatrixXd along_v((p + 1) * (q + 1), columns);
  Eigen::MatrixXd local(q + 1, columns);
  for (int a = 0; a <= p; ++a) {
    const int i = knots_u.control_point_index(span_u, a);
    for (int b = 0; b <= q; ++b) {
      local.row(b) = rows.row(i * count_v + knots_v.control_point_index(span_v, b));
    }
    along_v.middleRows(static_cast<Eigen::Index>(a) * (q + 1), q + 1) =
        bezier_from_local(knots_v, local, span_v);
  }
  Eigen::MatrixXd patch((p + 1) * (q + 1), columns);
  Eigen::MatrixXd column(p + 1, columns);
  for (int b = 0; b <= q; ++b) {
    for (int a = 0; a <= p; ++a) {
      column.row(a) = along_v.row(a * (q + 1) + b);
    }
    const Eigen::MatrixXd bezier = bezier_from_local(knots_u, column, span_u);
    for (int a = 0; a <= p; ++a) {
      patch.row(a * (q + 1) + b) = bezier.row(a);
    }
  }
  return patch;
}

}  // namespace dnurbs
