#pragma once
// Fast repeated evaluation of a NURBS surface: every non-empty span pair is converted once into a
// local polynomial patch (power basis, homogeneous coordinates) that Horner's rule evaluates.

#include <vector>

#include <Eigen/Core>

#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs {

/// Points and partial derivatives up to second order of a NURBS surface S(u, v), evaluated from
/// per-span polynomial patches cached at construction.
///
/// On the span pair [u_k, u_k+1) x [v_l, v_l+1) every basis product N_i,p(u) N_j,q(v) is a
/// polynomial, so the homogeneous surface S^w = (sum N N w P, sum N N w) is a polynomial patch
/// sum_{a,b} C_ab s^a t^b in the local parameters s = (u - mid_u) / half_u, t = (v - mid_v) /
/// half_v in [-1, 1] (centred so that the power basis stays well conditioned). The coefficients
/// are the Taylor coefficients at the span centre (Piegl & Tiller A2.3 for the basis
/// derivatives), C_ab = sum_ij N_i^(a) N_j^(b) half_u^a half_v^b / (a! b!) w_ij P_ij. Evaluation is
/// Horner's rule with derivatives plus the quotient rule on homogeneous coordinates (Piegl &
/// Tiller A4.4) and never allocates.
///
/// Memory: (p + 1)(q + 1) x 4 doubles (3 if non-rational) per non-empty span pair. The evaluator
/// is a snapshot: after the surface's control points, weights or knots change,
/// build a new one.
class SpanCachedSurfaceEvaluator {
 public:
  /// Highest derivative order `derivatives` computes (S, S_u, S_v, S_uu, S_uv, S_vv).
  static constexpr int kMaxOrder = 2;

  /// Converts every non-empty span pair of `surface` (open or periodic, rational or not).
  explicit SpanCachedSurfaceEvaluator(const NurbsSurface& surface);

  int degree_u() const { return degree_u_; }
  int degree_v() const { return degree_v_; }
  bool is_rational() const { return rational_; }

  /// S(u, v); parameters map into the domain as KnotVector::to_domain does (periodic ones wrap,
  /// open ones outside the domain throw Error).
  Eigen::Vector3d point(double u, double v) const;
  /// S^(k,l) for k + l <= order; throws Error if order is outside 0..kMaxOrder.
  void derivatives(double u, double v, int order, SurfaceDerivatives& result) const;

 private:
  /// Local parameter and patch index along one direction.
  struct SpanLocation {
    int span = 0;
    double local = 0.0;       ///< s or t in [-1, 1]
    double inverse_half = 0;  ///< 1 / half width: d/du = inverse_half d/ds
  };
  SpanLocation locate_u(double u) const;
  SpanLocation locate_v(double v) const;
  static SpanLocation locate(const KnotVector& knots, const std::vector<double>& span_starts,
                             const std::vector<double>& inverse_half_widths, double parameter);
  /// Coefficients of span pair (span_u, span_v): (degree_u + 1) x (degree_v + 1) vectors of
  /// components_ doubles, v power outer, u power inner.
  const double* patch(int span_u, int span_v) const {
    return coefficients_.data() + static_cast<std::size_t>(span_u * span_count_v_ + span_v) *
                                      static_cast<std::size_t>(patch_size_);
  }

  KnotVector knots_u_;
  KnotVector knots_v_;
  int degree_u_ = 0;
  int degree_v_ = 0;
  bool rational_ = false;
  int span_count_v_ = 0;
  int components_ = 4;  ///< doubles per coefficient: 4 (w P, w) rational, 3 (P) otherwise
  int patch_size_ = 0;
  /// Start parameter of each non-empty span plus the domain end, per direction.
  std::vector<double> span_starts_u_;
  std::vector<double> span_starts_v_;
  /// 2 / (width of each non-empty span), per direction.
  std::vector<double> inverse_half_widths_u_;
  std::vector<double> inverse_half_widths_v_;
  /// Patch coefficients, (w x, w y, w z, w) or (x, y, z) per monomial, span pairs u-major.
  std::vector<double> coefficients_;
};

}  // namespace dnurbs
