#pragma once
// Fitting a deformable superquadric to points (issue 9; Terzopoulos, "Deformable Models",
// eqs. 1.28-1.33): the rigid pose (centre c, rotation R), sizes (A1, A2, A3) = a (a1, a2, a3),
// squareness (e1, e2) and the global deformations T = shear o twist o bend o taper -- tapering
// (t1, t2), bending (b1, and on request its offset b2 and frequency b3), twisting tau and
// shearing (sx, sy) -- found by minimizing the mean squared radial distance (1/N) sum_k d_k^2
// (design/superquadric_radial_distance.h: x_k mapped back to the undeformed superellipsoid in
// closed form, d_k measured along the ray from the body origin). Optionally a local stage then
// fits the displacement field d = S q_d on the model's finite-element mesh
// (design/superquadric_local_fitting.h).
//
// NLopt's bounded LD_LBFGS minimizes with the analytic gradient (superquadric_fit_objective)
// from starts at the centroid and the principal axes of the points (every axis assignment and
// sign; deformations 0), each run with twist, shear, b2 and b3 held (a twisted and sheared shape
// tilts the principal axes: with them free from such a start 1 of 6 random test shapes fell into
// a local minimum with the wrong sign of tau). The best start is then polished with every fitted
// parameter free, first by LBFGS, then by Levenberg-Marquardt steps on the residuals d_k, which
// converge quadratically to a zero residual (noise-free points are fitted to round-off). Given a
// start, only the polish runs from it. The derivative-free LN_BOBYQA remains selectable (without
// the Levenberg-Marquardt steps): it needs no derivative where the distance is not
// differentiable (exponents above 2 make |e|^(2/e) a cusp at e = 0).
// Parameters that are not fitted are held: b2 and b3 at bend_offset and bend_frequency, tau, sx
// and sy at 0 (at the start's values when a start is given).
//
// The result is canonical: rotations by pi about the body axes map the deformations to others
// with the same shape,
//   about x: (t1, t2, b1, b2, tau, sx, sy) -> (-t1, -t2,  b1, -b2, tau, -sx,  sy),
//   about y:                               -> (-t1, -t2, -b1, -b2, tau,  sx, -sy),
//   about z:                               -> ( t1,  t2, -b1,  b2, tau, -sx, -sy),
// and the fitter returns the representative with b1 >= 0 and t1 >= 0.

#include <functional>
#include <numbers>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "dnurbs/design/superquadric_local_fitting.h"
#include "dnurbs/design/superquadric_radial_distance.h"
#include "dnurbs/surface/deformable_superquadric_shape.h"

namespace dnurbs {

/// The NLopt algorithm of a superquadric fit.
enum class SuperquadricFitAlgorithm {
  kLbfgs,   ///< NLOPT_LD_LBFGS with bounds and the analytic gradient (default)
  kBobyqa,  ///< NLOPT_LN_BOBYQA, derivative-free
};

/// A superquadric to start the fit from instead of the principal-axes starts.
struct SuperquadricFitStart {
  SuperquadricShapeParameters shape;  ///< q_s (a a1, a a2, a a3 are the sizes)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< body to world
};

struct SuperquadricFitSettings {
  SuperquadricFitAlgorithm algorithm = SuperquadricFitAlgorithm::kLbfgs;
  bool fit_twist = true;        ///< tau is fitted (else held)
  bool fit_shear = true;        ///< sx, sy are fitted (else held)
  bool fit_bend_shape = false;  ///< b2, b3 are fitted (no effect where b1 = 0: held by default)
  double bend_offset = 0.0;     ///< b2 when held (finite)
  double bend_frequency = 0.5;  ///< b3 when held (finite)
  double minimum_exponent = 0.1;
  double maximum_exponent = 4.0;
  double maximum_taper = 0.9;  ///< |t1|, |t2| <= this (< 1 keeps the taper factor positive)
  double maximum_twist = std::numbers::pi;  ///< |tau| <= this (> 0)
  double maximum_shear = 2.0;               ///< |sx|, |sy| <= this (> 0)
  int start_evaluations = 300;              ///< of each of the 24 starts (> 0)
  int max_evaluations = 20000;              ///< of the polishing run of the best start (> 0)
  double variable_tolerance = 1e-12;
  /// Start here (only the polishing run) instead of from the principal axes.
  std::optional<SuperquadricFitStart> start;
  /// Fit the local displacements after the global shape (none if empty).
  std::optional<SuperquadricLocalFitSettings> local;
  /// Called after every objective evaluation with the evaluations so far and the rms radial
  /// distance of the best parameters so far (progress reports; empty: none).
  std::function<void(int evaluations, double best_rms)> on_evaluation;
};

struct SuperquadricFitResult {
  SuperquadricShapeParameters shape;  ///< q_s with a = 1 (so a1..a3 are the sizes A1..A3)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< body to world
  double rms_error = 0.0;                                  ///< sqrt(mean d_k^2), radial distances
  double max_error = 0.0;                                  ///< max |d_k|
  int evaluations = 0;  ///< of sum d_k^2 (with its gradient for LBFGS), over every start
  int status = 0;       ///< nlopt::result of the polishing run
  /// The local stage's result when settings.local was given.
  std::optional<SuperquadricLocalFitResult> local;
};

/// Number of variables of superquadric_fit_objective.
inline constexpr int kSuperquadricFitVariableCount = 19;

/// The fit's objective (1/N) sum_k d_k^2 at `variables` = (centre (3), rotation vector r with
/// R = exp([r]x) (3), sizes A1..A3, e1, e2, t1, t2, b1, b2, b3, tau, sx, sy), a 19-vector, and,
/// if `gradient` is not null, its analytic gradient over all 19 (resized to 19). Throws Error for
/// bad points, settings or variable count.
double superquadric_fit_objective(const Eigen::MatrixX3d& points,
                                  const SuperquadricFitSettings& settings,
                                  const Eigen::VectorXd& variables, Eigen::VectorXd* gradient);

/// Fits points (count by 3, at least as many as fitted parameters, not all on a plane). Throws
/// Error naming the value for empty, too few or non-finite points, bad settings or a bad start.
SuperquadricFitResult fit_superquadric(const Eigen::MatrixX3d& points,
                                       const SuperquadricFitSettings& settings = {});

}  // namespace dnurbs
