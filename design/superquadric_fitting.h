#pragma once
// Fitting a superquadric with global deformations to points (issue 9): the rigid pose
// (centre c, rotation R), sizes (A1, A2, A3) = a (a1, a2, a3), squareness (e1, e2), tapering
// (t1, t2) and bending amplitude b1, found by minimizing the squared radial distances
//
//   d_k = |e_k| (1 - F(e_k)^(-e1/2)),
//   F(e) = ((e_x/A1)^2/e2 + (e_y/A2)^2/e2)^(e2/e1) + (e_z/A3)^2/e1   (inside-outside function),
//
// where e_k is point k mapped back to the undeformed superellipsoid: p = R^T (x_k - c), bending
// and tapering undone in closed form (z is unchanged by both). The bend's offset b2 and
// frequency b3 are settings (held), twist and shear are zero. NLopt's bounded LD_LBFGS minimizes
// (1/N) sum d_k^2 with its analytic gradient (superquadric_fit_objective) from starts at the
// centroid and the principal axes of the points (every axis assignment and sign), then the best
// start is polished. The derivative-free LN_BOBYQA remains selectable: it needs no derivative
// where the distance is not differentiable (exponents above 2 make |e|^(2/e) a cusp at e = 0).
//
// The result is canonical: rotations by pi about the body axes map (t1, t2, b1) to
// (-t1, -t2, b1) (about x), (-t1, -t2, -b1) (about y) and (t1, t2, -b1) (about z) with the same
// shape; the fitter returns the representative with b1 >= 0 and t1 >= 0.

#include <functional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "dnurbs/surface/deformable_superquadric_shape.h"

namespace dnurbs {

/// The NLopt algorithm of a superquadric fit.
enum class SuperquadricFitAlgorithm {
  kLbfgs,   ///< NLOPT_LD_LBFGS with bounds and the analytic gradient (default)
  kBobyqa,  ///< NLOPT_LN_BOBYQA, derivative-free
};

struct SuperquadricFitSettings {
  SuperquadricFitAlgorithm algorithm = SuperquadricFitAlgorithm::kLbfgs;
  double bend_offset = 0.0;     ///< b2 (held)
  double bend_frequency = 0.5;  ///< b3 (held)
  double minimum_exponent = 0.1;
  double maximum_exponent = 4.0;
  double maximum_taper = 0.9;   ///< |t1|, |t2| <= this (< 1 keeps the taper factor positive)
  int start_evaluations = 300;  ///< of each of the 24 starts (> 0)
  int max_evaluations = 20000;  ///< of the polishing run of the best start (> 0)
  double variable_tolerance = 1e-12;
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
};

/// Radial distance of world point x to the superquadric (shape, centre, rotation), positive
/// outside; twist and shear of `shape` must be zero (throws Error otherwise).
double superquadric_radial_distance(const SuperquadricShapeParameters& shape,
                                    const Eigen::Vector3d& centre, const Eigen::Matrix3d& rotation,
                                    const Eigen::Vector3d& x);

/// The fit's objective (1/N) sum_k d_k^2 at `variables` = (centre (3), rotation vector r with
/// R = exp([r]x) (3), sizes A1..A3, e1, e2, t1, t2, b1) and, if `gradient` is not null, its
/// analytic gradient (resized to 14). Throws Error for bad points, settings or variable count.
double superquadric_fit_objective(const Eigen::MatrixX3d& points,
                                  const SuperquadricFitSettings& settings,
                                  const Eigen::VectorXd& variables, Eigen::VectorXd* gradient);

/// Fits points (count by 3, at least 12, not all on a plane). Throws Error for empty, too few or
/// non-finite points or bad settings.
SuperquadricFitResult fit_superquadric(const Eigen::MatrixX3d& points,
                                       const SuperquadricFitSettings& settings = {});

}  // namespace dnurbs
