#pragma once
// Fitting D-NURBS curves and surfaces to points (issue 9): least squares plus a smoothness
// energy,
//
//   minimize  (1/2) sum_k |x(u_k; q) - p_k|^2 + (smoothness / 2) q^T K q,
//
// K the model's stiffness (its material: tension and rigidity), the parameter u_k of each point
// found by closest-point projection onto the current shape and re-projected between iterations
// (parameter correction). With fixed weights x is linear in q, so each iteration is one sparse
// solve of (A^T A + smoothness K) q = A^T p on the free coordinates (fixed control points keep
// their values). With free weights x is rational in q: each iteration runs NLopt's LD_LBFGS on
// the same objective (analytic gradient sum L^T (x - p) - smoothness f_int(q)), weights bounded
// below by the model's minimum weight.

#include <functional>

#include <Eigen/Core>

#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"

namespace dnurbs {

struct DNurbsFitSettings {
  /// Weight of the smoothness energy (>= 0); 0 is plain least squares.
  double smoothness = 0.0;
  /// Most projection-and-solve iterations (>= 1).
  int max_iterations = 30;
  /// Stop when no parameter moved more than this (relative to the domain) in a re-projection.
  double parameter_tolerance = 1e-12;
  /// Called after every iteration with its number (from 1) and the rms distance of the points
  /// to the shape it produced (progress reports; empty: none).
  std::function<void(int iteration, double rms_error)> on_iteration;
};

struct DNurbsFitResult {
  Eigen::VectorXd coordinates;  ///< the model's coordinates of the fitted shape
  Eigen::MatrixX2d parameters;  ///< u_k (curves use column 0) of each point on the fitted shape
  int iterations = 0;           ///< projection-and-solve iterations done
  double rms_error = 0.0;       ///< sqrt(mean |x(u_k) - p_k|^2), distances to the fitted shape
  double max_error = 0.0;       ///< max |x(u_k) - p_k|
};

/// Fits `model` to `points` (count by 3), starting from its initial shape. Throws Error for
/// empty or non-finite points, bad settings, or (fixed weights) a singular normal matrix (too
/// few points for the control points and no smoothness).
DNurbsFitResult fit_dnurbs_surface(const DNurbsSurface& model, const Eigen::MatrixX3d& points,
                                   const DNurbsFitSettings& settings = {});
DNurbsFitResult fit_dnurbs_curve(const DNurbsCurve& model, const Eigen::MatrixX3d& points,
                                 const DNurbsFitSettings& settings = {});

}  // namespace dnurbs
